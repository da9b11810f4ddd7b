#include "peers/ndt/branch_and_bound.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::peers {

double SearchGrid::yawOf(int yaw) const {
  const double a = 2.0 * M_PI * yaw / yaw_count;
  return a > M_PI ? a - 2.0 * M_PI : a;
}

Eigen::Vector3d SearchGrid::pose(const GridPose& p) const {
  return {grid->origin.x() + p.x * grid->resolution_m, grid->origin.y() + p.y * grid->resolution_m, yawOf(p.yaw)};
}

bool SearchGrid::excluded(const Exclusion& e, int yaw, int x, int y) const {
  const double d = std::hypot(x - e.center.x, y - e.center.y) * grid->resolution_m;
  const double a = std::abs(std::remainder(2.0 * M_PI * (yaw - e.center.yaw) / yaw_count, 2.0 * M_PI));
  return d <= e.distance_m && a <= e.angle_rad;
}

int yawCount(double resolution_m, double max_range_m) {
  const double r = std::max(max_range_m, resolution_m);
  const double step = std::acos(1.0 - resolution_m * resolution_m / (2.0 * r * r));
  return std::max(1, static_cast<int>(std::ceil(2.0 * M_PI / step)));
}

Cloud2 scanCells(const Cloud2& slice, double resolution_m) {
  // Sort by cell, keep the first point of each cell: deterministic for a given input order.
  std::vector<std::pair<std::pair<int, int>, std::size_t>> keyed;
  keyed.reserve(slice.size());
  for (std::size_t i = 0; i < slice.size(); ++i) {
    if (!slice[i].allFinite()) continue;
    keyed.push_back({{static_cast<int>(std::floor(slice[i].x() / resolution_m)), static_cast<int>(std::floor(slice[i].y() / resolution_m))}, i});
  }
  std::stable_sort(keyed.begin(), keyed.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  Cloud2 out;
  for (std::size_t i = 0; i < keyed.size(); ++i)
    if (i == 0 || keyed[i].first != keyed[i - 1].first) out.push_back(slice[keyed[i].second]);
  return out;
}

namespace {

// The scan cells' offsets (the cell each rotated point falls in with zero translation), per yaw.
using Offsets = std::vector<Eigen::Vector2i>;

Offsets offsetsAt(const SearchGrid& g, const Cloud2& scan, int yaw) {
  const double a = g.yawOf(yaw), c = std::cos(a), s = std::sin(a), r = g.grid->resolution_m;
  Offsets out;
  out.reserve(scan.size());
  for (const auto& p : scan)
    out.emplace_back(static_cast<int>(std::floor((c * p.x() - s * p.y()) / r)), static_cast<int>(std::floor((s * p.x() + c * p.y()) / r)));
  return out;
}

int boundAt(const GridPyramid& pyramid, const Offsets& offsets, int level, int x, int y) {
  int sum = 0;
  for (const auto& o : offsets) sum += pyramid.at(level, o.x() + x, o.y() + y);
  return sum;
}

struct Search {
  const SearchGrid& g;
  const Exclusion* exclude;
  SearchResult result;

  // Nothing below a node of this bound, whose smallest leaf is (yaw, x, y), can beat the best.
  bool pruned(int bound, int yaw, int x, int y) const {
    return bound < result.best.score || (bound == result.best.score && result.best.before(yaw, x, y));
  }

  void descend(const Offsets& offsets, int level, int yaw, int x, int y, int bound) {
    if (pruned(bound, yaw, x, y)) return;
    if (level == 0) {
      if (exclude && g.excluded(*exclude, yaw, x, y)) return;
      result.best = {yaw, x, y, bound};
      return;
    }
    struct Child {
      int x, y, bound;
    };
    Child children[4];
    int n = 0;
    const int w = 1 << (level - 1);
    for (int dy = 0; dy < 2; ++dy)
      for (int dx = 0; dx < 2; ++dx) {
        const int cx = x + dx * w, cy = y + dy * w;
        if (cx >= g.pyramid->width() || cy >= g.pyramid->height()) continue;
        children[n++] = {cx, cy, boundAt(*g.pyramid, offsets, level - 1, cx, cy)};
        ++result.nodes;
      }
    std::stable_sort(children, children + n, [](const Child& a, const Child& b) { return a.bound > b.bound; });
    for (int i = 0; i < n; ++i) descend(offsets, level - 1, yaw, children[i].x, children[i].y, children[i].bound);
  }
};

}  // namespace

SearchResult branchAndBound(const SearchGrid& g, const Cloud2& scan_cells, const Exclusion* exclude) {
  Search s{g, exclude, {}};
  if (scan_cells.empty() || g.pyramid->width() <= 0 || g.pyramid->height() <= 0) return s.result;
  const int top = g.pyramid->levels() - 1, step = 1 << top;
  struct Root {
    int yaw, x, y, bound;
  };
  std::vector<Offsets> offsets(g.yaw_count);
  std::vector<Root> roots;
  for (int yaw = 0; yaw < g.yaw_count; ++yaw) {
    offsets[yaw] = offsetsAt(g, scan_cells, yaw);
    for (int y = 0; y < g.pyramid->height(); y += step)
      for (int x = 0; x < g.pyramid->width(); x += step) roots.push_back({yaw, x, y, boundAt(*g.pyramid, offsets[yaw], top, x, y)});
  }
  s.result.nodes = static_cast<long>(roots.size());
  // Best bound first (ties in (yaw, x, y) order, as they were made): good leaves early prune most.
  std::stable_sort(roots.begin(), roots.end(), [](const Root& a, const Root& b) { return a.bound > b.bound; });
  for (const Root& r : roots) s.descend(offsets[r.yaw], top, r.yaw, r.x, r.y, r.bound);
  return s.result;
}

SearchResult exhaustiveSearch(const SearchGrid& g, const Cloud2& scan_cells, const Exclusion* exclude) {
  SearchResult out;
  if (scan_cells.empty()) return out;
  const OccupancyGrid& grid = *g.grid;
  for (int yaw = 0; yaw < g.yaw_count; ++yaw) {
    const double a = g.yawOf(yaw), c = std::cos(a), s = std::sin(a);
    for (int x = 0; x < grid.width; ++x)
      for (int y = 0; y < grid.height; ++y) {
        ++out.nodes;
        if (exclude && g.excluded(*exclude, yaw, x, y)) continue;
        int score = 0;
        for (const auto& p : scan_cells) {
          // The point in the map at this pose, then its cell.
          const double mx = c * p.x() - s * p.y() + x * grid.resolution_m, my = s * p.x() + c * p.y() + y * grid.resolution_m;
          score += grid.occupied(static_cast<int>(std::floor(mx / grid.resolution_m)), static_cast<int>(std::floor(my / grid.resolution_m)));
        }
        if (score > out.best.score) out.best = {yaw, x, y, score};  // the loop order is the tie order
      }
  }
  return out;
}

}  // namespace bimloc::peers
