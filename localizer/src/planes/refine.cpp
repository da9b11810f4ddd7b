// The plane of the surface that dominates a RANSAC band. RANSAC's plane through three points
// may lean to take in points of other surfaces: the reveals and head of a doorway, the voxels
// that straddle a corner (their centroids sit off both surfaces), the foot of a wall in a
// floor's band. Least squares over the whole band keeps that lean; trimmed least squares,
// repeated with a band scaled by the residuals' own robust spread, lets the dense surface win
// whatever the sensor's noise.
#include "plane_steps.hpp"

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
  std::vector<double> residuals(indices.size()), sorted;
  for (int k = 0; k < kRefineIterations; ++k) {
    for (std::size_t i = 0; i < indices.size(); ++i)
      residuals[i] = std::abs(r.fit.normal.dot(cloud[indices[i]].cast<double>()) + r.fit.d);
    sorted = residuals;
    std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
    const double band = std::clamp(kCoreSigmas * kMadToSigma * sorted[sorted.size() / 2], kMinCoreBand_m, max_band_m);
    Indices core;
    for (std::size_t i = 0; i < indices.size(); ++i)
      if (residuals[i] <= band) core.push_back(indices[i]);
    if (core.size() < 3 || core == r.core) break;
    r.core = std::move(core);
    r.band_m = band;
    r.fit = fitPlane(cloud, r.core);
  }
  return r;
}

Indices pointsNearPlane(const Cloud& cloud, const PlaneFit& fit, double band_m, const Eigen::Vector3d* along,
                        double along_min_m, double along_max_m) {
  Indices near;
  const Eigen::Vector3f n = fit.normal.cast<float>();
  const float d = static_cast<float>(fit.d), band = static_cast<float>(band_m);
  for (std::size_t i = 0; i < cloud.size(); ++i) {
    if (std::abs(n.dot(cloud[i]) + d) > band) continue;
    if (along) {
      const double u = along->dot(cloud[i].cast<double>());
      if (u < along_min_m || u > along_max_m) continue;
    }
    near.push_back(static_cast<int>(i));
  }
  return near;
}

}  // namespace bimloc::planes::detail
