#include "association.hpp"

#include "plane_factor.hpp"

#include <algorithm>
#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <cmath>
#include <limits>

namespace bimloc::sgraph::detail {
namespace {

constexpr double kDeg = M_PI / 180.0;
constexpr double kMaxWallTiltDeg = 15.0;   // an observed plane tilted more than this from vertical is not a wall
constexpr double kMaxNormalAngleDeg = 30.0;  // quick rejection before the gate
constexpr double kInfinity = std::numeric_limits<double>::infinity();

// Widens a new plane's seen extent with an observation's centroid and horizontal extent.
void extend(WallNode& node, const Eigen::Vector2d& centroid, double extent_m) {
  const Eigen::Vector2d c = node.face[0].centre, t(-node.face[0].e.y(), node.face[0].e.x());
  const double u = (centroid - c).dot(t), half = 0.5 * std::max(0.0, extent_m);
  const double lo = std::min((node.start[0] - c).dot(t), u - half), hi = std::max((node.end[0] - c).dot(t), u + half);
  node.start[0] = c + lo * t;
  node.end[0] = c + hi * t;
}

// A one-faced node on the observed plane, through the point of it nearest the centroid.
WallNode planeNode(const ScanObservation& o, const Eigen::Isometry3d& T_map_lidar) {
  WallNode node;
  node.kind = WallNode::Kind::New;
  node.faces = 1;
  const Eigen::Vector3d n_s(std::cos(o.minimal[1]) * std::cos(o.minimal[0]), std::cos(o.minimal[1]) * std::sin(o.minimal[0]),
                            std::sin(o.minimal[1]));
  const Eigen::Vector3d n_m = T_map_lidar.linear() * n_s;
  const Eigen::Vector2d e = n_m.head<2>().normalized();
  const double d_m = o.minimal[2] - e.dot(T_map_lidar.translation().head<2>());  // d' = d - n'·t (n' horizontal)
  node.face[0].e = e;
  node.face[0].centre = o.centroid_map - (e.dot(o.centroid_map) + d_m) * e;
  node.face[0].h = 0;
  node.face[0].side = 1;
  node.start[0] = node.end[0] = node.face[0].centre;
  extend(node, o.centroid_map, o.extent_m);
  return node;
}

Eigen::Isometry3d mapLidar(const Keyframe& kf) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  const Eigen::Matrix3d Rz = Eigen::AngleAxisd(kf.pose[2], Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.linear() = Rz * kf.A;
  T.translation() = Eigen::Vector3d(kf.pose[0], kf.pose[1], kf.z_map) + Rz * kf.b;
  return T;
}

}  // namespace

Eigen::Matrix3d sqrtInformation(const Eigen::Matrix3d& covariance) {
  const Eigen::Matrix3d information = covariance.inverse();
  const Eigen::LLT<Eigen::Matrix3d> llt(0.5 * (information + information.transpose()));
  return llt.matrixL().transpose();
}

std::vector<ScanObservation> prepareObservations(const Keyframe& kf, const std::vector<planes::ObservedPlane>& walls,
                                                 const SGraphConfig& c, SGraphResult& result) {
  std::vector<ScanObservation> out;
  const Eigen::Isometry3d T_map_lidar = mapLidar(kf);
  const Eigen::Vector3d floors(c.plane_sigma_azimuth_deg * kDeg, c.plane_sigma_elevation_deg * kDeg, c.plane_sigma_d_m);
  for (std::size_t i = 0; i < walls.size(); ++i) {
    const planes::ObservedPlane& w = walls[i];
    const int index = static_cast<int>(i);
    auto reject = [&](const std::string& why) {
      PlaneAssociation a;
      a.observation = index;
      a.kind = PlaneAssociation::Kind::Rejected;
      result.associations.push_back(a);
      result.warnings.push_back("keyframe " + std::to_string(kf.id) + ", observed wall " + std::to_string(index) + ": " + why +
                                ", not used");
    };
    if (!w.normal.allFinite() || !std::isfinite(w.d) || w.normal.norm() < 0.5) {
      reject("not a finite plane");
      continue;
    }
    if (!w.centroid.allFinite()) {
      reject("its centroid is not finite");
      continue;
    }
    double d = w.d / w.normal.norm();
    Eigen::Vector3d n = w.normal.normalized();
    if (d < 0) n = -n, d = -d;  // the convention: the normal towards the sensor
    const Eigen::Vector3d n_map = T_map_lidar.linear() * n;
    if (std::abs(n_map.z()) > std::sin(kMaxWallTiltDeg * kDeg)) {
      reject("not vertical in the map");
      continue;
    }
    ScanObservation o;
    o.index = index;
    o.minimal = planes::minimalPlane(n, d);
    Eigen::Matrix3d fit = 0.5 * (w.covariance + w.covariance.transpose());
    if (!fit.allFinite() || Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(fit).eigenvalues().minCoeff() < -1e-12) {
      result.warnings.push_back("keyframe " + std::to_string(kf.id) + ", observed wall " + std::to_string(index) +
                                ": its covariance is not a covariance; the configured sigmas alone are used");
      fit.setZero();
    }
    o.covariance = fit + floors.cwiseAbs2().asDiagonal().toDenseMatrix();
    o.normal_map = n_map.head<2>().normalized();
    const Eigen::Vector3d centroid_map = T_map_lidar * w.centroid;
    o.centroid_map = centroid_map.head<2>();
    o.z_map = (T_map_lidar * w.heightMiddleOrCentroid()).z();
    o.extent_m = std::isfinite(w.extent_m) ? w.extent_m : 0.0;
    const Eigen::Vector3d span_middle = T_map_lidar * w.wall_span_middle;
    if (span_middle.allFinite() && std::isfinite(w.wall_span_m) && w.wall_span_m > 0.0)
      o.span_middle_map = span_middle.head<2>(), o.span_m = w.wall_span_m;
    o.height_extent_m = std::isfinite(w.height_extent_m) ? w.height_extent_m : 0.0;
    o.axis = std::abs(o.normal_map.x()) >= std::abs(o.normal_map.y()) ? bim::WallAxis::X : bim::WallAxis::Y;
    out.push_back(o);
  }
  return out;
}

double matchDistance2(const WallNode& node, int k, const Keyframe& kf, const ScanObservation& o, const SGraphConfig& c) {
  if (node.axis(k) != o.axis) return kInfinity;  // the paper's classes: x walls with x walls
  // A face inside another wall's body is seen by no sensor: matched, it explains the real face
  // a wall's thickness in front of it, and the robot slides by that thickness (as in the filter).
  if (node.kind == WallNode::Kind::Plan && node.buried[static_cast<std::size_t>(k)]) return kInfinity;
  if (node.normal(k).dot(o.normal_map) < std::cos(kMaxNormalAngleDeg * kDeg)) return kInfinity;
  double predicted[3];
  PlaneFactor::predict(node.face[k], kf.A, kf.b, kf.pose.data(), node.params.data(), predicted);
  const Eigen::Vector3d e(wrapAngle(predicted[0] - o.minimal[0]), predicted[1] - o.minimal[1], predicted[2] - o.minimal[2]);
  Eigen::Matrix3d S = o.covariance;
  S(0, 0) += std::pow(c.association_sigma_azimuth_deg * kDeg, 2);
  S(2, 2) += std::pow(c.association_sigma_d_m, 2);
  const double m2 = e.dot(S.ldlt().solve(e));
  if (!(m2 < c.association_gate_mahalanobis2)) return kInfinity;
  // The observed wall's points must lie along the face, not beside its end.
  const double u = node.along(k, o.centroid_map);
  if (u < -c.segment_margin_m || u > node.length(k) + c.segment_margin_m) return kInfinity;
  // ... and not in a hole of it. The support's box (where it stands along the face -+ half its
  // span, its heights about their middle) inside an opening grown by the margin the pose and
  // the extents' estimate need. Not the centroid -+ half the extents: the centroid lies where
  // the returns are dense, near the sensor and at the rings' heights, and the pane filling the
  // Duplex's living-room window (4.85 m wide) "overflowed" it by 0.015 m along: matched to the
  // wall's face 0.37 m before it, it held a pose 0.34 m off in the S-Graph for 11 s (A102 seed
  // 1, docs/results/2026-11-27-h28duplex.md). The filter's rule has been by the span since.
  const bool span_known = o.span_m > 0.0;
  const double m = span_known ? node.along(k, o.span_middle_map) : u, hu = 0.5 * (span_known ? o.span_m : o.extent_m);
  const double hz = 0.5 * o.height_extent_m;
  if (node.kind == WallNode::Kind::Plan &&
      bim::insideOpening(node.openings[static_cast<std::size_t>(k)], m - hu, m + hu, o.z_map - hz, o.z_map + hz, c.opening_margin_m))
    return kInfinity;
  return m2;
}

void associate(Graph& g, Keyframe& kf, const std::vector<ScanObservation>& observations, const SGraphConfig& c,
               SGraphResult& result) {
  const Eigen::Isometry3d T_map_lidar = mapLidar(kf);
  for (const ScanObservation& o : observations) {
    PlaneAssociation a;
    a.observation = o.index;
    int best_node = -1, best_face = 0;
    double best = kInfinity;
    for (std::size_t n = 0; n < g.nodes.size(); ++n) {
      const WallNode& node = g.nodes[n];
      if (!node.active) continue;
      for (int k = 0; k < node.faces; ++k) {
        const double m2 = matchDistance2(node, k, kf, o, c);
        if (m2 < best) best = m2, best_node = static_cast<int>(n), best_face = k;
      }
    }
    PlaneMeasurement m;
    m.minimal = o.minimal;
    m.sqrt_information = sqrtInformation(o.covariance);
    m.centroid_map = o.centroid_map;
    m.extent_m = o.extent_m;
    m.observation = o.index;
    if (best_node >= 0) {
      WallNode& node = g.nodes[static_cast<std::size_t>(best_node)];
      m.node = best_node;
      m.face = best_face;
      kf.planes.push_back(m);
      ++node.observations;
      node.last_keyframe = kf.id;
      a.mahalanobis2 = best;
      if (node.kind == WallNode::Kind::Plan) {
        a.kind = PlaneAssociation::Kind::PlanWall, a.wall = node.wall, a.face = best_face;
        ++result.plan_walls_matched;
      } else {
        a.kind = PlaneAssociation::Kind::NewPlane, a.new_plane = node.new_id;
        extend(node, o.centroid_map, o.extent_m);
        ++result.new_planes_matched;
      }
      result.associations.push_back(a);
      continue;
    }
    // Unmatched: a sighting of a candidate, or a candidate of its own.
    a.kind = PlaneAssociation::Kind::Candidate;
    result.associations.push_back(a);
    Candidate* best_candidate = nullptr;
    best = kInfinity;
    for (Candidate& cand : g.candidates) {
      const double m2 = matchDistance2(cand.plane, 0, kf, o, c);
      if (m2 < best) best = m2, best_candidate = &cand;
    }
    if (best_candidate == nullptr) {
      g.candidates.push_back({planeNode(o, T_map_lidar), {}, -1});
      best_candidate = &g.candidates.back();
    }
    if (best_candidate->last_keyframe == kf.id) continue;  // one sighting per keyframe
    best_candidate->sightings.emplace_back(kf.id, m);
    best_candidate->last_keyframe = kf.id;
    extend(best_candidate->plane, o.centroid_map, o.extent_m);
  }

  // Candidates seen often enough become new planes, with the sightings of the window's keyframes.
  for (std::size_t i = 0; i < g.candidates.size();) {
    Candidate& cand = g.candidates[i];
    if (static_cast<int>(cand.sightings.size()) < c.new_plane_min_sightings) {
      const bool stale = kf.id - cand.last_keyframe > c.candidate_max_age_keyframes;
      if (stale) g.candidates.erase(g.candidates.begin() + static_cast<std::ptrdiff_t>(i));
      else ++i;
      continue;
    }
    WallNode node = cand.plane;
    node.new_id = g.next_new_plane_id++;
    const int index = static_cast<int>(g.nodes.size());
    for (auto& [id, m] : cand.sightings) {
      for (Keyframe& w : g.window) {
        if (w.id != id) continue;
        m.node = index;
        m.face = 0;
        w.planes.push_back(m);
        ++node.observations;
        node.last_keyframe = std::max(node.last_keyframe, id);
      }
    }
    for (const auto& [id, m] : cand.sightings) {  // this keyframe's sighting is now on the new plane
      if (id != kf.id) continue;
      for (PlaneAssociation& a : result.associations) {
        if (a.observation != m.observation) continue;
        a.kind = PlaneAssociation::Kind::NewPlane;
        a.new_plane = node.new_id;
        ++result.new_planes_matched;
      }
    }
    g.nodes.push_back(std::move(node));
    ++result.new_planes_created;
    g.candidates.erase(g.candidates.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

}  // namespace bimloc::sgraph::detail
