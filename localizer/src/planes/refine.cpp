// The plane of the surface that dominates a RANSAC band. RANSAC's plane through three points
// may lean to take in points of other surfaces: the reveals and head of a doorway, the voxels
// that straddle a corner (their centroids sit off both surfaces), the foot of a wall in a
// floor's band. Least squares over the whole band keeps that lean; trimmed least squares,
// repeated with a band scaled by the residuals' own robust spread, lets the dense surface win
// whatever the sensor's noise.
#include "band_count.hpp"
#include "plane_steps.hpp"
#include "select.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::planes::detail {
namespace {

constexpr int kRefineIterations = 5;
constexpr double kCoreSigmas = 2.5;          // ~99% of Gaussian noise stays in
constexpr double kMadToSigma = 1.4826;       // median absolute deviation -> standard deviation
constexpr double kMinCoreBand_m = 0.005;     // noise-free data: the band must not collapse

}  // namespace

Indices withinBand(const Cloud& cloud, const Indices& indices, const PlaneFit& fit, double band_m) {
  Indices kept;
  for (const int i : indices)
    if (std::abs(fit.normal.dot(cloud[i].cast<double>()) + fit.d) <= band_m) kept.push_back(i);
  return kept;
}

RefinedPlane refinePlane(const Cloud& cloud, const Indices& indices, double max_band_m) {
  RefinedPlane r{fitPlane(cloud, indices), indices, max_band_m};
  if (indices.size() < 3) return r;
  std::vector<double> residuals(indices.size());
  std::vector<std::uint64_t> scratch;
  for (int k = 0; k < kRefineIterations; ++k) {
    for (std::size_t i = 0; i < indices.size(); ++i)
      residuals[i] = std::abs(r.fit.normal.dot(cloud[indices[i]].cast<double>()) + r.fit.d);
    // The median (the upper one of an even count), as nth_element finds it (select.hpp).
    const double median = kthSmallest(residuals, residuals.size() / 2, scratch);
    const double band = std::clamp(kCoreSigmas * kMadToSigma * median, kMinCoreBand_m, max_band_m);
    Indices core;
    core.reserve(indices.size());
    for (std::size_t i = 0; i < indices.size(); ++i)
      if (residuals[i] <= band) core.push_back(indices[i]);
    if (core.size() < 3 || core == r.core) break;
    r.core = std::move(core);
    r.band_m = band;
    r.fit = fitPlane(cloud, r.core);
  }
  return r;
}

PackedCloud::PackedCloud(const Cloud& cloud) {
  x.reserve(cloud.size()), y.reserve(cloud.size()), z.reserve(cloud.size());
  for (const auto& p : cloud) x.push_back(p.x()), y.push_back(p.y()), z.push_back(p.z());
}

Indices pointsNearPlane(const Cloud& cloud, const PackedCloud& packed, const PlaneFit& fit, double band_m,
                        const Eigen::Vector3d* along, double along_min_m, double along_max_m) {
  // The band in float, as n.dot(p) + d of Eigen's 3-vectors (band_count.hpp), every point;
  // then, for a wall, where each point in it lies along the wall.
  Indices near;
  const Eigen::Vector3f n = fit.normal.cast<float>();
  indicesInBand(packed.x.data(), packed.y.data(), packed.z.data(), packed.x.size(), n.x(), n.y(), n.z(), static_cast<float>(fit.d),
                static_cast<float>(band_m), near);
  if (!along) return near;
  std::size_t kept = 0;
  for (const int i : near) {
    const double u = along->dot(cloud[static_cast<std::size_t>(i)].cast<double>());
    if (u >= along_min_m && u <= along_max_m) near[kept++] = i;
  }
  near.resize(kept);
  return near;
}

}  // namespace bimloc::planes::detail
