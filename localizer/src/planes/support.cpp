// Which of a RANSAC plane's inliers are one surface. RANSAC keeps every point within its band,
// so one plane may hold two coplanar walls (the inner faces of an exterior wall on both sides
// of a partition, a corridor wall cut by doorways) or a strip of another surface. The wall
// kept is the largest connected run along the wall; the other inliers go back to the pool
// and may become planes of their own.
#include "plane_steps.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <iterator>
#include <utility>

namespace bimloc::planes::detail {

Eigen::Vector3d planeHorizontal(const Eigen::Vector3d& normal) {
  Eigen::Vector3d h = normal.cross(Eigen::Vector3d::UnitZ());
  if (h.norm() < 1e-6) h = Eigen::Vector3d::UnitX() - normal.x() * normal;  // horizontal plane
  return h.normalized();
}

std::vector<Indices> runsAlong(const Cloud& cloud, const Indices& indices, const Eigen::Vector3d& direction,
                               double gap_m) {
  std::vector<std::pair<double, int>> along;
  along.reserve(indices.size());
  for (const int i : indices) along.emplace_back(direction.dot(cloud[i].cast<double>()), i);
  std::sort(along.begin(), along.end());  // ties by index: the result depends on the points only

  std::vector<Indices> runs;
  for (std::size_t begin = 0, k = 1; k <= along.size(); ++k) {
    if (k < along.size() && along[k].first - along[k - 1].first <= gap_m) continue;
    Indices run;
    run.reserve(k - begin);
    for (std::size_t j = begin; j < k; ++j) run.push_back(along[j].second);
    std::sort(run.begin(), run.end());
    runs.push_back(std::move(run));
    begin = k;
  }
  return runs;
}

const Indices* largestRun(const std::vector<Indices>& runs) {
  const Indices* best = nullptr;
  for (const auto& run : runs)
    if (!best || run.size() > best->size()) best = &run;
  return best;
}

const Indices* runOverlapping(const std::vector<Indices>& runs, const Indices& reference) {
  const Indices* best = nullptr;
  std::size_t best_shared = 0;
  for (const auto& run : runs) {
    Indices shared;
    std::set_intersection(run.begin(), run.end(), reference.begin(), reference.end(), std::back_inserter(shared));
    if (shared.size() > best_shared) best = &run, best_shared = shared.size();
  }
  return best;
}

}  // namespace bimloc::planes::detail
