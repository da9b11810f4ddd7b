#include "sim/worldgen/spec_symmetry.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>

namespace bimloc::worldgen {
namespace {

using Box = std::array<long long, 4>;  // x0, y0, x1, y1 in 0.1 mm
constexpr long long kUnitsPerMetre = 10000, kTolerance = 100;  // 1 cm
constexpr long long kLowest = std::numeric_limits<long long>::min();

Box boxOf(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double thickness) {
  const Eigen::Vector2d dir = (b - a).normalized(), half = Eigen::Vector2d(-dir.y(), dir.x()) * (thickness / 2);
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const Eigen::Vector2d& p : std::array<Eigen::Vector2d, 4>{a + half, a - half, b + half, b - half}) {
    x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y()), x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
  }
  const auto u = [](double v) { return std::llround(v * kUnitsPerMetre); };
  return {u(x0), u(y0), u(x1), u(y1)};
}

// The box's image: x -> sx - x when flip_x, y -> sy - y when flip_y.
Box image(const Box& b, bool flip_x, bool flip_y, long long sx, long long sy) {
  return {flip_x ? sx - b[2] : b[0], flip_y ? sy - b[3] : b[1], flip_x ? sx - b[0] : b[2], flip_y ? sy - b[1] : b[3]};
}

int unmatched(const std::vector<Box>& boxes, bool flip_x, bool flip_y, long long sx, long long sy) {
  const std::set<Box> all(boxes.begin(), boxes.end());
  int n = 0;
  for (const Box& b : boxes) {
    const Box m = image(b, flip_x, flip_y, sx, sy);
    bool found = false;
    for (auto it = all.lower_bound({m[0] - kTolerance, kLowest, kLowest, kLowest}); it != all.end() && (*it)[0] <= m[0] + kTolerance && !found;
         ++it) {
      found = std::abs((*it)[1] - m[1]) <= kTolerance && std::abs((*it)[2] - m[2]) <= kTolerance &&
              std::abs((*it)[3] - m[3]) <= kTolerance;
    }
    n += found ? 0 : 1;
  }
  return n;
}

}  // namespace

std::vector<SymmetryMismatch> symmetryMismatches(const StoreySpec& storey) {
  std::vector<Box> walls, doors;
  for (const WallSpec& w : storey.walls) walls.push_back(boxOf(w.start, w.end, w.thickness_m));
  for (const DoorSpec& d : storey.doors) {
    const WallSpec& w = storey.walls.at(d.wall);
    const Eigen::Vector2d dir = (w.end - w.start).normalized();
    const Eigen::Vector2d c = w.start + dir * d.offset_m;
    doors.push_back(boxOf(c - dir * (d.width_m / 2), c + dir * (d.width_m / 2), w.thickness_m));
  }
  double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
  for (const Eigen::Vector2d& p : storey.outline) {
    x0 = std::min(x0, p.x()), y0 = std::min(y0, p.y()), x1 = std::max(x1, p.x()), y1 = std::max(y1, p.y());
  }
  const long long sx = std::llround((x0 + x1) * kUnitsPerMetre), sy = std::llround((y0 + y1) * kUnitsPerMetre);
  std::vector<SymmetryMismatch> out;
  const struct {
    const char* name;
    bool fx, fy;
  } kinds[] = {{"180 deg turn", true, true}, {"mirror x", true, false}, {"mirror y", false, true}};
  for (const auto& k : kinds) {
    out.push_back({k.name, unmatched(walls, k.fx, k.fy, sx, sy), unmatched(doors, k.fx, k.fy, sx, sy)});
  }
  return out;
}

}  // namespace bimloc::worldgen
