// Wall planes from one lidar scan: the paper's "Observations" (as in S-Graphs: voxel grid,
// then sequential RANSAC plane segmentation). The particle filter matches the vertical planes
// against the walls of the room each particle stands in.
//
// Conventions: sensor frame (the scan's own frame), metres. A plane is n·p + d = 0 with
// |n| = 1 and n pointing TOWARDS the sensor origin, so d > 0 is the origin's distance to the
// plane. The geometric closest point of the plane to the origin is closest_point() = -d n.
// The paper's closest-point form (CP, after Geneva et al.) is Π = n_cp d_cp with a normal
// n_cp pointing away from the sensor and d_cp = distance > 0: here n_cp = -normal,
// d_cp = d, so Π = closest_point(). This is the same convention as the building model's wall
// faces (normals point out of the wall, into the room where the sensor is), so a face moved
// into the sensor frame compares directly (n_s = R^T n_w, d_s = d_w + n_w·t for T = (R, t)).
#pragma once

#include <Eigen/Core>
#include <limits>
#include <cstddef>
#include <cstdint>
#include <vector>

namespace bimloc::planes {

struct PlaneExtractionConfig {
  double voxel_size_m = 0.10;           // downsampling before RANSAC
  double min_range_m = 0.5;             // drop points closer than this (the robot's own body) and farther than max_range_m
  double max_range_m = 30.0;
  int ransac_iterations = 500;          // S-Graphs default
  double distance_threshold_m = 0.04;   // inlier band (S-Graphs uses 0.01 on clean data; simulated and real data need more)
  int min_inliers = 60;                 // after downsampling, near the sensor (below)
  // The lidar's angle between neighbouring rings (VLP-16: 2 deg). min_inliers voxels is a
  // surface's support where the rings are closer than a voxel; farther, each ring gives one
  // row of voxels, and the same surface fewer: the count asked of a plane is scaled by
  // voxel / (range tan(ring_spacing)), so that a wall is judged by its area whatever its range
  // (an end wall 18 m down a corridor of look-alike offices: about 40 voxels, dropped at 60,
  // and with it what tells the offices apart; docs/results/2026-11-29-session30.md). Such a
  // plane must still span two rings (one ring is a line) and min_extent_m. 0: min_inliers at
  // every range.
  double ring_spacing_deg = 2.0;
  double min_extent_m = 1.0;            // a plane must span at least this much (walls: horizontally)
  double vertical_tolerance_deg = 10;   // |n_z| < sin(tol) -> vertical (wall candidate)
  double horizontal_tolerance_deg = 10; // |n_z| > cos(tol) -> horizontal (floor/ceiling), reported apart
  int max_planes = 20;                  // walls + horizontals
  // Walls first, from the voxels of x-y columns (voxel_size_m square) whose returns span at least
  // this in height, by a vertical-plane RANSAC (a wall's support is still every free voxel in its
  // band); then the horizontals from the rest. 0: one sequential RANSAC over the whole scan for
  // both (the dense slabs of a dense lidar's rings then cut the walls of a cluttered room apart:
  // docs/realdata_room.md). With 0.3 every Planes test passes and whole real frames give their
  // walls (13-60 with min_inliers 20), but it is off by default: the extra clutter planes make one
  // filter test (DuplexFaces) score the truth below a wrong pose (docs/results/2026-11-26-h29real.md).
  double standing_height_m = 0.0;
  std::uint64_t seed = 0;               // RANSAC is seeded: same scan + seed -> same planes
};

struct ObservedPlane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitX();  // unit, pointing towards the sensor origin (so d >= 0)
  double d = 0;                                       // n·p + d = 0 in the sensor frame
  // The plane's point closest to the sensor; equals the paper's CP vector Π (see above).
  Eigen::Vector3d closest_point() const { return -d * normal; }
  // Covariance of the minimal parameters (azimuth, elevation, d) of minimalPlane(): the
  // inverse Gauss-Newton Hessian of the point-to-plane least squares over the support voxels,
  // times their residual variance about the plane (sum r^2 / (N - 3), floored at 1 mm^2).
  // Directions the points do not constrain (the azimuth of a horizontal plane) get pi^2.
  // It is the fit's own statistic, not a sensor model; on simulated VLP-16 scans (0.008 m
  // noise) it is calibrated to slightly cautious: the mean squared Mahalanobis error of the
  // walls found is 1.6 to 2.7 (3 would be exact), with 99% of them inside chi2(3)'s 99%.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  int inliers = 0;              // support voxels (after downsampling) within the fit's final band
  double extent_m = 0;          // span of the support along the plane's horizontal direction n × z
  double height_extent_m = 0;   // vertical span of the support
  // The centroid moved along the sensor's z to the middle of that span: the span reaches
  // height_extent_m / 2 above and below it. The centroid's own height is where the returns are
  // dense (the lower rings, nearer the sensor), not the middle: on the Duplex's walls and window
  // panes 2-4 m away, centroid -+ half the span sat 0.15-0.2 m lower than the support, enough to
  // put a pane's support below its window's sill, out of the opening that tells it from the
  // wall (docs/results/2026-11-27-h28duplex.md). Not finite: unknown.
  Eigen::Vector3d height_middle = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();  // of the raw returns the plane was fitted to
  // The point the support's heights are taken about, by the filter and the S-Graph alike:
  // height_middle where known, else the centroid (a plane not made by the extraction).
  Eigen::Vector3d heightMiddleOrCentroid() const { return height_middle.allFinite() ? height_middle : centroid; }
  // Where along the plane the support stands as a wall (points at several heights, not the one
  // height of a floor's or a slab's strip in its band): its length, and its middle at the
  // centroid's height and depth, so that it reaches wall_span_m / 2 either side of it. The
  // centroid, a mean of the returns, lies where they are dense, near the sensor: a wall seen from
  // 0.2 m off one end has it a metre or more from the middle. Not finite: unknown.
  double wall_span_m = 0;
  Eigen::Vector3d wall_span_middle = Eigen::Vector3d::Constant(std::numeric_limits<double>::quiet_NaN());
  double rms_m = 0;             // point-to-plane RMS residual of the support voxels
  bool vertical = false;
};

struct PlaneExtraction {
  std::vector<ObservedPlane> walls;        // vertical planes passing the inlier and extent tests
  std::vector<ObservedPlane> horizontals;  // floor / ceiling
  std::size_t input_points = 0, valid_points = 0;  // valid: finite and within the range limits
};

// Never throws for any input: an empty, all-NaN or too small scan gives no planes.
PlaneExtraction extractPlanes(const std::vector<Eigen::Vector3f>& points_sensor, const PlaneExtractionConfig& config = {});

// The minimal parametrisation the particle filter compares (paper, Eq. plane_error):
// (azimuth = atan2(n_y, n_x), elevation = asin(n_z), d).
Eigen::Vector3d minimalPlane(const Eigen::Vector3d& normal, double d);

}  // namespace bimloc::planes
