// Plane association (paper, "Plane Association"): each observed wall of a keyframe against
// the wall faces of its class (x / y by the dominant normal component), by the Mahalanobis
// distance of the paper's Eq. (plane error) in (azimuth, elevation, d) under a gate, and only
// where the observed plane's points lie along the face (as the particle filter does). The
// unmatched become candidates, and a candidate seen in enough keyframes a new plane.
#pragma once

#include "graph.hpp"

#include <bimloc/planes/plane_extraction.hpp>

#include <vector>

namespace bimloc::sgraph::detail {

// An observed wall, checked and moved into the map at the keyframe's (predicted) pose.
struct ScanObservation {
  int index = -1;  // in the scan
  Eigen::Vector3d minimal = Eigen::Vector3d::Zero();  // (azimuth, elevation, d), lidar frame
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();  // the fit's plus the config's floors
  Eigen::Vector2d normal_map = Eigen::Vector2d::UnitX();
  Eigen::Vector2d centroid_map = Eigen::Vector2d::Zero();
  double extent_m = 0;
  double z_map = 0;            // the middle of the support's heights in the map (not the centroid's)
  // Where along the plane the support stands as a wall (planes::ObservedPlane::wall_span_*): the
  // openings rule's, as the filter's (pf/measurement.cpp). span_m 0: unknown, the centroid -+
  // half the extent stand for it.
  Eigen::Vector2d span_middle_map = Eigen::Vector2d::Zero();
  double span_m = 0;
  double height_extent_m = 0;  // the support's vertical span
  bim::WallAxis axis = bim::WallAxis::X;
};

// The scan's walls that can be used; the others are Rejected in `result`, with a warning.
std::vector<ScanObservation> prepareObservations(const Keyframe& kf, const std::vector<planes::ObservedPlane>& walls,
                                                 const SGraphConfig& config, SGraphResult& result);

// Squared Mahalanobis distance between an observation and face k of a node seen from the
// keyframe, with the prediction's uncertainty added; infinity when the class or the extent
// rule it out, or when its points lie in one of the face's openings (a window's glass, a
// door leaf: parallel to the face, behind it, and not the wall).
double matchDistance2(const WallNode& node, int k, const Keyframe& kf, const ScanObservation& o, const SGraphConfig& config);

// Associates the keyframe's observations: measurements on kf.planes (and, for new planes
// promoted from candidates, on the window's keyframes that saw them), one entry per
// observation in result.associations.
void associate(Graph& g, Keyframe& kf, const std::vector<ScanObservation>& observations, const SGraphConfig& config,
               SGraphResult& result);

// The square-root information (upper triangular W, W'W = inverse) of a covariance.
Eigen::Matrix3d sqrtInformation(const Eigen::Matrix3d& covariance);

}  // namespace bimloc::sgraph::detail
