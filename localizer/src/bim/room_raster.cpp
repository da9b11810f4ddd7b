#include "room_raster.hpp"

#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <queue>

namespace bimloc::bim::detail {
namespace {

constexpr double kFar = 1e20;  // "no feature" in the distance transform

// One row or column of the exact squared Euclidean distance transform: d(q) = min_p (q-p)^2 + f(p)
// (lower envelope of parabolas, Felzenszwalb and Huttenlocher 2012).
void distance1d(const std::vector<double>& f, std::vector<double>& d, std::vector<int>& v, std::vector<double>& z) {
  const int n = static_cast<int>(f.size());
  int k = 0;
  v[0] = 0;
  z[0] = -std::numeric_limits<double>::infinity();
  z[1] = std::numeric_limits<double>::infinity();
  const auto meet = [&](int q, int p) { return ((f[q] + double(q) * q) - (f[p] + double(p) * p)) / (2.0 * (q - p)); };
  for (int q = 1; q < n; ++q) {
    double s = meet(q, v[k]);
    while (s <= z[k]) {
      --k;
      s = meet(q, v[k]);
    }
    ++k;
    v[k] = q;
    z[k] = s;
    z[k + 1] = std::numeric_limits<double>::infinity();
  }
  k = 0;
  for (int q = 0; q < n; ++q) {
    while (z[k + 1] < q) ++k;
    d[q] = double(q - v[k]) * (q - v[k]) + f[v[k]];
  }
}

}  // namespace

void fillPolygon(const Raster& raster, const Polygon2& polygon, Mask& mask) {
  if (polygon.size() < 3) return;
  double y_min = std::numeric_limits<double>::infinity(), y_max = -y_min;
  for (const auto& p : polygon) y_min = std::min(y_min, p.y()), y_max = std::max(y_max, p.y());
  const double c = raster.cell_m;
  const int j0 = std::max(0, int(std::floor((y_min - raster.origin.y()) / c - 0.5)));
  const int j1 = std::min(raster.height - 1, int(std::ceil((y_max - raster.origin.y()) / c - 0.5)));
  std::vector<double> xs;
  for (int j = j0; j <= j1; ++j) {
    const double y = raster.origin.y() + (j + 0.5) * c;
    xs.clear();
    for (std::size_t e = 0, n = polygon.size(); e < n; ++e) {
      const auto& a = polygon[e];
      const auto& b = polygon[(e + 1) % n];
      if ((a.y() > y) != (b.y() > y)) xs.push_back(a.x() + (y - a.y()) * (b.x() - a.x()) / (b.y() - a.y()));
    }
    std::sort(xs.begin(), xs.end());
    for (std::size_t k = 0; k + 1 < xs.size(); k += 2) {
      // Cells whose centre x lies in [xs[k], xs[k+1]).
      const int i0 = std::max(0, int(std::ceil((xs[k] - raster.origin.x()) / c - 0.5)));
      const int i1 = std::min(raster.width - 1, int(std::ceil((xs[k + 1] - raster.origin.x()) / c - 0.5)) - 1);
      for (int i = i0; i <= i1; ++i) mask[raster.index(i, j)] = 1;
    }
  }
}

std::vector<std::int32_t> squaredDistance(const Raster& raster, const Mask& feature) {
  const int w = raster.width, h = raster.height;
  std::vector<double> grid(raster.size());
  for (std::size_t k = 0; k < grid.size(); ++k) grid[k] = feature[k] ? 0.0 : kFar;
  const int n = std::max(w, h);
  std::vector<double> f, d;
  std::vector<int> v(static_cast<std::size_t>(n) + 1);
  std::vector<double> z(static_cast<std::size_t>(n) + 2);
  f.resize(static_cast<std::size_t>(h)), d.resize(static_cast<std::size_t>(h));
  for (int i = 0; i < w; ++i) {  // columns
    for (int j = 0; j < h; ++j) f[j] = grid[raster.index(i, j)];
    distance1d(f, d, v, z);
    for (int j = 0; j < h; ++j) grid[raster.index(i, j)] = d[j];
  }
  f.resize(static_cast<std::size_t>(w)), d.resize(static_cast<std::size_t>(w));
  for (int j = 0; j < h; ++j) {  // rows
    for (int i = 0; i < w; ++i) f[i] = grid[raster.index(i, j)];
    distance1d(f, d, v, z);
    for (int i = 0; i < w; ++i) grid[raster.index(i, j)] = d[i];
  }
  std::vector<std::int32_t> out(grid.size());
  constexpr double kMax = std::numeric_limits<std::int32_t>::max();
  for (std::size_t k = 0; k < grid.size(); ++k) out[k] = static_cast<std::int32_t>(std::min(grid[k], kMax));
  return out;
}

Mask closing(const Raster& raster, const Mask& mask, double radius_cells) {
  const double r2 = radius_cells * radius_cells;
  const auto to_mask = squaredDistance(raster, mask);
  Mask outside(raster.size());
  for (std::size_t k = 0; k < outside.size(); ++k) outside[k] = to_mask[k] > r2;  // not in the dilation
  const auto to_outside = squaredDistance(raster, outside);
  Mask closed(raster.size());
  for (std::size_t k = 0; k < closed.size(); ++k) closed[k] = !outside[k] && to_outside[k] > r2;
  return closed;
}

Mask reachedFromBorder(const Raster& raster, const Mask& passable) {
  Mask reached(raster.size(), 0);
  std::deque<std::size_t> queue;
  const auto visit = [&](int i, int j) {
    const std::size_t k = raster.index(i, j);
    if (passable[k] && !reached[k]) reached[k] = 1, queue.push_back(k);
  };
  for (int i = 0; i < raster.width; ++i) visit(i, 0), visit(i, raster.height - 1);
  for (int j = 0; j < raster.height; ++j) visit(0, j), visit(raster.width - 1, j);
  while (!queue.empty()) {
    const std::size_t k = queue.front();
    queue.pop_front();
    const int i = int(k % raster.width), j = int(k / raster.width);
    if (i > 0) visit(i - 1, j);
    if (i + 1 < raster.width) visit(i + 1, j);
    if (j > 0) visit(i, j - 1);
    if (j + 1 < raster.height) visit(i, j + 1);
  }
  return reached;
}

std::int32_t labelComponents(const Raster& raster, const Mask& cells, Labels& labels, std::int32_t first_label) {
  std::int32_t next = first_label;
  std::vector<std::size_t> stack;
  Mask seen(raster.size(), 0);
  for (std::size_t start = 0; start < raster.size(); ++start) {
    if (!cells[start] || seen[start]) continue;
    seen[start] = 1;
    stack.push_back(start);
    while (!stack.empty()) {
      const std::size_t k = stack.back();
      stack.pop_back();
      labels[k] = next;
      const int i = int(k % raster.width), j = int(k / raster.width);
      const std::size_t around[4] = {i > 0 ? k - 1 : k, i + 1 < raster.width ? k + 1 : k,
                                     j > 0 ? k - raster.width : k, j + 1 < raster.height ? k + raster.width : k};
      for (const std::size_t n : around)
        if (cells[n] && !seen[n]) seen[n] = 1, stack.push_back(n);
    }
    ++next;
  }
  return next;
}

void watershed(const Raster& raster, const Mask& free, const std::vector<std::int32_t>& d2, Labels& labels) {
  // Highest distance first; ties by raster index, so the result never depends on the heap.
  using Item = std::pair<std::int32_t, std::int64_t>;  // (d2, -index)
  std::priority_queue<Item> queue;
  const auto neighbours = [&](std::size_t k, std::size_t out[4]) {
    const int i = int(k % raster.width), j = int(k / raster.width);
    int n = 0;
    if (i > 0) out[n++] = k - 1;
    if (i + 1 < raster.width) out[n++] = k + 1;
    if (j > 0) out[n++] = k - raster.width;
    if (j + 1 < raster.height) out[n++] = k + raster.width;
    return n;
  };
  std::size_t around[4];
  for (std::size_t k = 0; k < raster.size(); ++k) {
    if (labels[k] <= 0) continue;
    const int n = neighbours(k, around);
    for (int a = 0; a < n; ++a)
      if (free[around[a]] && labels[around[a]] == 0) {
        queue.push({d2[k], -static_cast<std::int64_t>(k)});
        break;
      }
  }
  while (!queue.empty()) {
    const std::size_t k = static_cast<std::size_t>(-queue.top().second);
    queue.pop();
    const int n = neighbours(k, around);
    for (int a = 0; a < n; ++a) {
      const std::size_t m = around[a];
      if (!free[m] || labels[m] != 0) continue;
      labels[m] = labels[k];
      queue.push({d2[m], -static_cast<std::int64_t>(m)});
    }
  }
}

Polygon2 regionOutline(const Raster& raster, const Labels& labels, std::int32_t label) {
  // Directed cell edges with the region on their left, between lattice points (i, j).
  struct Edge {
    std::int64_t from, to;
    int dir;  // 0 +x, 1 +y, 2 -x, 3 -y
  };
  const std::int64_t stride = raster.width + 1;
  const auto at = [&](int i, int j) { return std::int64_t(j) * stride + i; };
  const auto in = [&](int i, int j) {
    return i >= 0 && j >= 0 && i < raster.width && j < raster.height && labels[raster.index(i, j)] == label;
  };
  std::vector<Edge> edges;
  for (int j = 0; j < raster.height; ++j)
    for (int i = 0; i < raster.width; ++i) {
      if (!in(i, j)) continue;
      if (!in(i, j - 1)) edges.push_back({at(i, j), at(i + 1, j), 0});
      if (!in(i + 1, j)) edges.push_back({at(i + 1, j), at(i + 1, j + 1), 1});
      if (!in(i, j + 1)) edges.push_back({at(i + 1, j + 1), at(i, j + 1), 2});
      if (!in(i - 1, j)) edges.push_back({at(i, j + 1), at(i, j), 3});
    }
  std::stable_sort(edges.begin(), edges.end(), [](const Edge& a, const Edge& b) { return a.from < b.from; });
  std::vector<bool> used(edges.size(), false);
  const auto leaving = [&](std::int64_t vertex, int incoming, std::size_t start) -> std::ptrdiff_t {
    auto it = std::lower_bound(edges.begin(), edges.end(), vertex, [](const Edge& e, std::int64_t v) { return e.from < v; });
    std::ptrdiff_t best = -1;
    int best_rank = 9;
    for (; it != edges.end() && it->from == vertex; ++it) {
      const std::ptrdiff_t e = it - edges.begin();
      if (used[static_cast<std::size_t>(e)] && static_cast<std::size_t>(e) != start) continue;
      // Left turn first: at a pinch (two region cells touching at a corner) the loop keeps to
      // its own cell, as 4-connectivity says.
      const int turn = (it->dir - incoming + 4) % 4;  // 1 left, 0 straight, 3 right
      const int rank = turn == 1 ? 0 : turn == 0 ? 1 : 2;
      if (rank < best_rank) best_rank = rank, best = e;
    }
    return best;
  };
  std::vector<std::pair<std::int64_t, std::int64_t>> best_loop;
  double best_area = 0.0;
  for (std::size_t s = 0; s < edges.size(); ++s) {
    if (used[s]) continue;
    std::vector<std::pair<std::int64_t, std::int64_t>> corners;
    std::size_t e = s;
    int previous_dir = edges[s].dir;
    do {
      used[e] = true;
      if (edges[e].dir != previous_dir || corners.empty())
        corners.emplace_back(edges[e].from % stride, edges[e].from / stride);
      previous_dir = edges[e].dir;
      const std::ptrdiff_t next = leaving(edges[e].to, edges[e].dir, s);
      if (next < 0) break;
      e = static_cast<std::size_t>(next);
    } while (e != s);
    // The start may be in the middle of a straight run: drop it then.
    if (corners.size() > 2 && edges[s].dir == previous_dir) corners.erase(corners.begin());
    double twice = 0.0;
    for (std::size_t k = 0, n = corners.size(); k < n; ++k) {
      const auto& a = corners[k];
      const auto& b = corners[(k + 1) % n];
      twice += double(a.first) * double(b.second) - double(b.first) * double(a.second);
    }
    if (twice > best_area) best_area = twice, best_loop = corners;
  }
  Polygon2 outline;
  for (const auto& [i, j] : best_loop) outline.push_back(raster.corner(int(i), int(j)));
  return outline;
}

}  // namespace bimloc::bim::detail
