// Which of a RANSAC plane's inliers are one surface. RANSAC keeps every point within its band,
// so one plane may hold two coplanar walls (the inner faces of an exterior wall on both sides
// of a partition, a corridor wall cut by doorways) or a strip of another surface. The wall
// kept is the largest connected run along the wall; the other inliers go back to the pool
// and may become planes of their own.
#include "plane_steps.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <iterator>
#include <utility>

namespace bimloc::planes::detail {

Eigen::Vector3d planeHorizontal(const Eigen::Vector3d& normal) {
  Eigen::Vector3d h = normal.cross(Eigen::Vector3d::UnitZ());
  if (h.norm() < 1e-6) h = Eigen::Vector3d::UnitX() - normal.x() * normal;  // horizontal plane
  return h.normalized();
}

std::vector<Indices> runsAlongBySorting(const Cloud& cloud, const Indices& indices, const Eigen::Vector3d& direction,
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

namespace {
// Buckets beyond this many (a plane tens of kilometres long, or gap_m tiny): sort instead.
constexpr double kMaxRunBuckets = 1 << 16;
}  // namespace

std::vector<Indices> runsAlong(const Cloud& cloud, const Indices& indices, const Eigen::Vector3d& direction, double gap_m) {
  // The same runs without sorting: the positions in buckets gap_m wide. Where each bucket's
  // points span no more than gap_m (computed as the sort compares them: no neighbour in it is
  // further apart), a run can only end between two buckets, and it does where the next
  // occupied bucket's least position is more than gap_m past this one's greatest: those two are
  // neighbours in the sorted order, and their difference is the one the sort would test. The
  // indices given ascending (RANSAC's inliers, a band of the pool), each run's come out ascending.
  std::vector<double> u(indices.size());
  double lo = INFINITY, hi = -INFINITY;
  bool finite = true;
  for (std::size_t k = 0; k < indices.size(); ++k) {
    u[k] = direction.dot(cloud[indices[k]].cast<double>());
    finite &= std::isfinite(u[k]);
    lo = std::min(lo, u[k]), hi = std::max(hi, u[k]);
  }
  if (indices.empty() || !finite || !(gap_m > 0.0) || !std::isfinite(hi - lo) || (hi - lo) / gap_m > kMaxRunBuckets ||
      !std::is_sorted(indices.begin(), indices.end()))
    return runsAlongBySorting(cloud, indices, direction, gap_m);
  const std::size_t n = static_cast<std::size_t>((hi - lo) / gap_m) + 1;
  std::vector<double> least(n, INFINITY), most(n, -INFINITY);
  std::vector<std::size_t> bucket(indices.size());
  for (std::size_t k = 0; k < indices.size(); ++k) {
    const std::size_t b = std::min(n - 1, static_cast<std::size_t>((u[k] - lo) / gap_m));
    bucket[k] = b;
    least[b] = std::min(least[b], u[k]), most[b] = std::max(most[b], u[k]);
  }
  std::vector<int> run_of(n, -1);
  int runs_count = 0;
  double last = 0;
  for (std::size_t b = 0; b < n; ++b) {
    if (!(least[b] <= most[b])) continue;  // empty
    if (most[b] - least[b] > gap_m) return runsAlongBySorting(cloud, indices, direction, gap_m);
    if (runs_count == 0 || least[b] - last > gap_m) ++runs_count;
    run_of[b] = runs_count - 1;
    last = most[b];
  }
  std::vector<Indices> runs(static_cast<std::size_t>(runs_count));
  for (std::size_t k = 0; k < indices.size(); ++k) runs[static_cast<std::size_t>(run_of[bucket[k]])].push_back(indices[k]);
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
