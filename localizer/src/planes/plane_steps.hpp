// The steps of the plane extraction, each a function of plain data. PCL is included only by
// the .cpp file that calls it (downsample.cpp).
#pragma once

#include <bimloc/planes/plane_extraction.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <vector>

namespace bimloc::planes::detail {

using Cloud = std::vector<Eigen::Vector3f>;
using Indices = std::vector<int>;

// Finite points with min_range_m <= |p| <= max_range_m.
Cloud validPoints(const Cloud& points, double min_range_m, double max_range_m);

// pcl::VoxelGrid: one centroid per occupied voxel, in a deterministic order.
Cloud voxelDownsample(const Cloud& points, double voxel_size_m);

// One RANSAC plane over cloud[pool] (pcl::SampleConsensusModelPlane + RandomSampleConsensus,
// step for step, sampling seeded by `seed`): the plane with the most points within
// threshold_m, and those points.
struct RansacPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double d = 0;
  Indices inliers;  // indices into cloud, ascending
};
std::optional<RansacPlane> ransacPlane(const Cloud& cloud, const Indices& pool, int iterations, double threshold_m,
                                       std::uint32_t seed);

// standing.cpp. The voxels whose x-y column (cell_m square) holds returns spanning at least
// min_height_m in z: walls, shelves and doors, not floors, table tops or a ring's slab.
Indices standingVoxels(const Cloud& voxels, const Cloud& raw, double cell_m, double min_height_m);
// One vertical plane by RANSAC over cloud[pool] in x-y: two points a sample, the second within
// radius_m of the first; the plane with the most points within threshold_m, and those points.
std::optional<RansacPlane> ransacVerticalPlane(const Cloud& cloud, const Indices& pool, int iterations,
                                               double threshold_m, double radius_m, std::uint32_t seed);

// A least-squares plane (PCA: the normal is the direction of least variance of the points).
struct PlaneFit {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double d = 0;
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
};
PlaneFit fitPlane(const Cloud& cloud, const Indices& support);

// The in-plane horizontal direction n × z (unit); for a horizontal plane, x projected on it.
Eigen::Vector3d planeHorizontal(const Eigen::Vector3d& normal);

// `indices` cut wherever two neighbours along `direction` are more than gap_m apart, in order
// along it (each run ascending). Along a wall's horizontal direction: one wall per run, not two
// coplanar walls a doorway or a room apart. Vertical gaps are ignored on purpose: a far wall's
// scan rings are further apart than any useful tolerance, and coplanar walls are never stacked.
// Without sorting where it can (buckets gap_m wide); runsAlongBySorting sorts the positions: the
// same runs.
std::vector<Indices> runsAlong(const Cloud& cloud, const Indices& indices, const Eigen::Vector3d& direction,
                               double gap_m);
std::vector<Indices> runsAlongBySorting(const Cloud& cloud, const Indices& indices, const Eigen::Vector3d& direction,
                                        double gap_m);
// The run with the most points; the run sharing the most points with `reference` (null if none).
const Indices* largestRun(const std::vector<Indices>& runs);
const Indices* runOverlapping(const std::vector<Indices>& runs, const Indices& reference);

// The points of `indices` within band_m of the plane.
Indices withinBand(const Cloud& cloud, const Indices& indices, const PlaneFit& fit, double band_m);

// Robust least squares (refine.cpp): the fit over `indices` is repeated over the points within
// 2.5 robust standard deviations (1.4826 x the median absolute residual, clamped to
// [5 mm, max_band_m]) of the previous fit, until those points no longer change.
struct RefinedPlane {
  PlaneFit fit;
  Indices core;       // the points kept by the last iteration
  double band_m = 0;  // and the band that kept them
};
RefinedPlane refinePlane(const Cloud& cloud, const Indices& indices, double max_band_m);

// A cloud coordinate by coordinate (x, y, z each contiguous): what a band test over every point
// reads eight at a time (band_count.hpp).
struct PackedCloud {
  explicit PackedCloud(const Cloud& cloud);
  std::vector<float> x, y, z;
};

// The raw returns within band_m of a plane and, if `along` is given (a wall), whose position
// along it lies in [along_min_m, along_max_m]. `packed`: the same cloud, packed.
Indices pointsNearPlane(const Cloud& cloud, const PackedCloud& packed, const PlaneFit& fit, double band_m,
                        const Eigen::Vector3d* along, double along_min_m, double along_max_m);

// The full description of a fitted plane over its support: normal towards the origin,
// extents, RMS, covariance of the minimal parameters (see ObservedPlane); `vertical` unset.
ObservedPlane describePlane(const Cloud& cloud, const Indices& support, const PlaneFit& fit);

// PCL's console level from bimloc::verbose() (bimloc/verbosity.hpp), before each use of PCL.
void applyPclVerbosity();

}  // namespace bimloc::planes::detail
