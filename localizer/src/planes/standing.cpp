// Walls before floors, on the points that stand up. In a cluttered room seen by a dense lidar
// (docs/realdata_room.md), each near-horizontal ring lies in a slab a few centimetres thick over
// desks and floor that holds more voxels than any wall strip between the clutter: sequential
// RANSAC over the whole scan takes those slabs first, and their bands cut the walls apart. A
// wall, unlike a slab, a floor or a table top, has returns at several heights in one x-y column,
// whatever the range and the number of rings: the column test keeps it and drops the slabs.
// On those points a wall is a line in x-y: two points fix its candidate plane, and the second is
// drawn near the first, so that a wall holding a few percent of the points is still drawn.
#include "plane_steps.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <unordered_map>

namespace bimloc::planes::detail {
namespace {

struct ColumnSpan {
  float lo, hi;
};

std::int64_t standingColumnKey(const Eigen::Vector3f& p, double cell_m) {
  const auto ix = std::int64_t(std::floor(p.x() / cell_m)), iy = std::int64_t(std::floor(p.y() / cell_m));
  return (ix << 32) ^ (iy & 0xffffffff);
}

std::int64_t neighbourCellKey(int ix, int iy) { return (std::int64_t(ix) << 32) ^ (std::int64_t(iy) & 0xffffffff); }

}  // namespace

Indices standingVoxels(const Cloud& voxels, const Cloud& raw, double cell_m, double min_height_m) {
  std::unordered_map<std::int64_t, ColumnSpan> columns;
  columns.reserve(raw.size() / 4 + 1);
  for (const auto& p : raw) {
    auto [it, fresh] = columns.try_emplace(standingColumnKey(p, cell_m), ColumnSpan{p.z(), p.z()});
    if (!fresh) it->second.lo = std::min(it->second.lo, p.z()), it->second.hi = std::max(it->second.hi, p.z());
  }
  Indices out;
  for (int i = 0; i < int(voxels.size()); ++i) {
    // A voxel's centroid lies in the column of its returns, or (straddling a column's edge) in
    // a neighbour's: a voxel in no column of returns is dropped, as it stands on nothing.
    const auto it = columns.find(standingColumnKey(voxels[i], cell_m));
    if (it != columns.end() && it->second.hi - it->second.lo >= min_height_m) out.push_back(i);
  }
  return out;
}

std::optional<RansacPlane> ransacVerticalPlane(const Cloud& cloud, const Indices& pool, int iterations,
                                               double threshold_m, double radius_m, std::uint32_t seed) {
  if (pool.size() < 2 || iterations < 1 || !(threshold_m > 0) || !(radius_m > 0)) return std::nullopt;
  // The pool by x-y cells of radius_m: the second point of a sample comes from the first's
  // cell or a neighbouring one, and within radius_m of it.
  std::unordered_map<std::int64_t, Indices> cells;
  auto cellOf = [radius_m](const Eigen::Vector3f& p) {
    return std::pair<int, int>(int(std::floor(p.x() / radius_m)), int(std::floor(p.y() / radius_m)));
  };
  for (const int i : pool) {
    const auto [cx, cy] = cellOf(cloud[i]);
    cells[neighbourCellKey(cx, cy)].push_back(i);
  }
  std::vector<float> px, py;
  px.reserve(pool.size()), py.reserve(pool.size());
  for (const int i : pool) px.push_back(cloud[i].x()), py.push_back(cloud[i].y());

  std::mt19937 rng(seed);
  std::uniform_int_distribution<std::size_t> pick(0, pool.size() - 1);
  Indices near;
  double best_a = 0, best_b = 0, best_d = 0;
  std::size_t best_count = 0;
  const float t = static_cast<float>(threshold_m);
  for (int it = 0; it < iterations; ++it) {
    const int i = pool[pick(rng)];
    const Eigen::Vector2f p = cloud[i].head<2>();
    const auto [cx, cy] = cellOf(cloud[i]);
    near.clear();
    for (int dx = -1; dx <= 1; ++dx)
      for (int dy = -1; dy <= 1; ++dy) {
        const auto found = cells.find(neighbourCellKey(cx + dx, cy + dy));
        if (found == cells.end()) continue;
        for (const int j : found->second) {
          const float dist = (cloud[j].head<2>() - p).norm();
          // Closer than a voxel: the two points' direction is noise.
          if (dist <= radius_m && dist > 2 * threshold_m) near.push_back(j);
        }
      }
    if (near.empty()) continue;
    const int j = near[std::uniform_int_distribution<std::size_t>(0, near.size() - 1)(rng)];
    const Eigen::Vector2f dir = (cloud[j].head<2>() - p).normalized();
    const float a = -dir.y(), b = dir.x(), d = -(a * p.x() + b * p.y());
    std::size_t count = 0;
    for (std::size_t k = 0; k < px.size(); ++k) count += std::abs(a * px[k] + b * py[k] + d) < t;
    if (count > best_count) best_count = count, best_a = a, best_b = b, best_d = d;
  }
  if (best_count == 0) return std::nullopt;
  RansacPlane plane;
  plane.normal = Eigen::Vector3d(best_a, best_b, 0).normalized();
  plane.d = best_d / Eigen::Vector2d(best_a, best_b).norm();
  for (std::size_t k = 0; k < px.size(); ++k)
    if (std::abs(plane.normal.x() * px[k] + plane.normal.y() * py[k] + plane.d) < threshold_m) plane.inliers.push_back(pool[k]);
  std::sort(plane.inliers.begin(), plane.inliers.end());
  return plane;
}

}  // namespace bimloc::planes::detail
