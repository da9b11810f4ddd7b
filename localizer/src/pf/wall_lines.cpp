#include "wall_lines.hpp"

#include <algorithm>
#include <cmath>
#include <utility>

namespace bimloc::pf::detail {

std::vector<LineSpan> wallLines(const bim::Storey& storey, const std::vector<bool>& ignored) {
  const std::size_t n = 2 * storey.walls.size();
  std::vector<LineSpan> lines(n);
  const auto faceOf = [&](std::size_t i) -> const bim::WallFace& { return storey.walls[i / 2].faces[i % 2]; };
  const auto skip = [&](std::size_t i) { return i < ignored.size() && ignored[i]; };
  const double cos_in_line = std::cos(kInLineRad);
  std::vector<std::pair<double, double>> along;  // the in-line faces' stretches, along face i
  for (std::size_t i = 0; i < n; ++i) {
    const bim::WallFace& f = faceOf(i);
    const Eigen::Vector2d start = f.start.head<2>();
    Eigen::Vector2d dir = f.end.head<2>() - start;
    const double length = dir.norm();
    lines[i] = {0.0, length};
    if (skip(i) || !(length > 1e-9)) continue;
    dir /= length;
    const Eigen::Vector3d ni = f.plane.n.normalized();
    along.clear();
    for (std::size_t j = 0; j < n; ++j) {
      if (j == i || skip(j)) continue;
      const bim::WallFace& g = faceOf(j);
      const Eigen::Vector3d nj = g.plane.n.normalized();
      if (ni.dot(nj) < cos_in_line) continue;
      // Both ends of g within kInLineM of face i's plane.
      const double ds = std::abs(ni.dot(g.start) + f.plane.d), de = std::abs(ni.dot(g.end) + f.plane.d);
      if (!(ds <= kInLineM && de <= kInLineM)) continue;
      double a = (g.start.head<2>() - start).dot(dir), b = (g.end.head<2>() - start).dot(dir);
      if (a > b) std::swap(a, b);
      along.emplace_back(a, b);
    }
    std::sort(along.begin(), along.end());
    // Grow [lo, hi] by every in-line stretch within kLineGapM of it, until none is: sorted by
    // start, one pass reaches right; repeated passes reach left as far as chains go.
    double lo = 0.0, hi = length;
    for (bool grew = true; grew;) {
      grew = false;
      for (const auto& [a, b] : along)
        if (a <= hi + kLineGapM && b >= lo - kLineGapM && (a < lo || b > hi)) {
          lo = std::min(lo, a), hi = std::max(hi, b);
          grew = true;
        }
    }
    lines[i] = {lo, hi};
  }
  return lines;
}

}  // namespace bimloc::pf::detail
