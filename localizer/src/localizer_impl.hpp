// Localizer::Impl: the state one Localizer keeps between steps, shared by the files that
// implement its steps (localizer.cpp: the step, the search and the hand-over;
// localizer_storeys.cpp: the storey following; localizer_report.cpp: what a step reports, and
// the peers' step; localizer_guide.cpp: the places kept and the goal suggested). Private.
#pragma once

#include <bimloc/localizer.hpp>

#include <bimloc/geometry/planar_pose.hpp>

#include <bimloc/bim/standing_walls.hpp>

#include "peers/peer.hpp"
#include "pf/filter_access.hpp"
#include "storeys/altitude_mean.hpp"
#include "storeys/landing_rooms.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

namespace bimloc {
namespace detail {

inline constexpr double kDeg = M_PI / 180.0;

// The stages' seeds from the one seed: the same derivation the bench used before the
// localizer owned the loop, so runs keep their bytes.
inline LocalizerConfig seeded(LocalizerConfig c) {
  c.pf.seed = c.seed * 0x9E3779B97F4A7C15ull + 11;
  c.planes.seed = c.seed;
  c.pf.use_rooms = c.method != LocalizerMethod::PfNoRooms;
  return c;
}

// Weighted covariance of the particles' (x, y, yaw) about their weighted mean (localizer.cpp).
Eigen::Matrix3d particleCovariance(const pf::ParticleFilter& filter);

}  // namespace detail

struct Localizer::Impl {
  // The plan as the robot senses it: each storey with the walls of other storeys that stand in
  // its band (bim/standing_walls.hpp; empty with storeys.standing_walls false); every stage
  // reads `building`, which is this, or the plan as filed when it is off.
  bim::StandingWallsReport standing;
  bim::Building sensed;
  const bim::Building& building;
  // The plan as filed: a search over several storeys weighs each by the walls the plan files
  // under it. A wall standing in two storeys' bands is evidence for both alike, and on split
  // levels (Jesse.1) the standing walls make two storeys' maps nearly one: the walls as filed
  // are what the plan says tells its storeys apart (docs/multi_storey.md). One storey's search
  // (given, decided, arrived on) and its tracking use `building`.
  const bim::Building& filed;
  const bim::Building& mapFor(const std::vector<std::size_t>& candidates) const {
    return candidates.size() > 1 ? filed : building;
  }
  Eigen::Isometry3d T_base_lidar;
  LocalizerConfig config;
  std::vector<std::size_t> storeys;  // the candidates of the first search
  std::optional<storeys::AltitudeReading> altitude;  // the latest observeAltitude(), if any
  std::optional<double> altitude_reference_s;        // the first reading's stamp: its drift counts from there
  storeys::AltitudeMean altitude_mean;               // the readings averaged (storeys/altitude_mean.hpp)
  double odom_z = 0;                                 // the odometry's height on this step
  std::unique_ptr<pf::StoreyBank> bank;            // the current (or last) search (not for peers)
  std::unique_ptr<peers::PeerLocalizer> peer;      // methods Amcl, Ndt
  std::optional<Eigen::Isometry3d> peer_T_map_odom;  // the peer's, since it converged
  bool peer_converged = false;
  bool filter_active = true;                       // the filter runs on this step
  std::unique_ptr<sgraph::SGraphTracker> tracker;  // since the first hand-over
  std::optional<sgraph::SGraphResult> last_track;  // the tracker's last answer
  Eigen::Matrix3d track_covariance = Eigen::Matrix3d::Identity();  // of its last solved keyframe
  // The filter's particle covariance under its particles' version (describe(), every step).
  mutable std::optional<std::pair<std::uint64_t, Eigen::Matrix3d>> covariance_at;
  std::optional<double> convergence_stamp;
  std::optional<std::size_t> tracked_storey;
  int losses = 0;
  std::vector<std::string> warnings;
  // Storeys (issue 31). The stages see the odometry levelled: its z less z_shift_m, so that on
  // the storey the robot stands on it reads base_height_m, as on the start storey (the filter
  // puts the base at the storey's elevation + the odometry's z).
  storeys::StoreyFollower follower;
  std::optional<double> base_height_m;  // the odometry's z at the first step: base_link above the floor
  double z_shift_m = 0;
  std::optional<PlanarPose> last_odom;  // the last step's odometry: how far a turn may be skewed
  bool pending_search = false;      // the tracker lost the plan on the stairs: search once off them
  bool arrival_unconfirmed = false;  // the tracker started by an arrival has not matched the new storey's walls yet
  std::vector<StoreyLink> links;
  std::vector<StoreyGraph> graphs;  // the graphs of the storeys left
  std::vector<std::unique_ptr<sgraph::SGraphTracker>> retired;  // ... owned here
  // Where to look next (guide/): the places of the last weighing as map <- odom (which odometry
  // leaves fixed), each with its margin; the planner of the storey they are on; the goal kept
  // between plannings, in the odom frame.
  struct KeptPlace {
    PlanarPose T_map_odom = PlanarPose::Zero();
    double margin = 0;
  };
  std::vector<KeptPlace> places;
  std::size_t places_storey = 0;
  std::unique_ptr<guide::GoalPlanner> planner;
  std::size_t planner_storey = 0;
  std::optional<guide::LookGoal> goal;
  std::vector<KeptPlace> goal_places;  // the places the goal was planned for
  std::size_t goal_planned_count = 0;  // how many places there were when the goal was first planned
  // Set when a goal was reached with no place ruled out since it was planned: the place count
  // then. No new goal until the count falls below it.
  std::optional<std::size_t> spent_count;
  double goal_stamp_s = -1e300;
  double places_fitted_s = -1e300;  // when the places were last fitted (GuideConfig::places_interval_s)
  bool places_due = false;          // ... on this step: the kept places are replaced

  Impl(const bim::Building& b, const Eigen::Isometry3d& mount, const LocalizerConfig& c)
      : sensed(c.storeys.standing_walls ? bim::withStandingWalls(b, {}, &standing) : bim::Building{}),
        building(c.storeys.standing_walls ? sensed : b), filed(b), T_base_lidar(mount), config(detail::seeded(c)),
        follower(building, c.storeys) {}

  bool usesTracker() const { return config.method == LocalizerMethod::SGraph; }
  bool lost() const { return tracker && tracker->state() == sgraph::TrackingState::Lost; }
  // Steps of Localizer::step, in order.
  bool wantsPoints(const Eigen::Isometry3d& T_odom_base) const;
  void track(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<planes::ObservedPlane>& walls, LocalizationResult& r);
  void search(const std::vector<planes::ObservedPlane>& walls, const pf::RangeProfile& profile, LocalizationResult& r);
  void handOver(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<planes::ObservedPlane>& walls, LocalizationResult& r);
  void searchAgain(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r);
  Eigen::Isometry3d levelled(const Eigen::Isometry3d& T_odom_base) const {
    Eigen::Isometry3d T = T_odom_base;
    T.translation().z() -= z_shift_m;
    return T;
  }
  void firstStep(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r);
  void follow(double stamp_s, const Eigen::Isometry3d& odom, LocalizationResult& r);
  void followSearch(double stamp_s, const Eigen::Isometry3d& odom, LocalizationResult& r);
  void arrive(const storeys::StoreyArrival& a, double stamp_s, const Eigen::Isometry3d& odom, LocalizationResult& r);
  void describe(LocalizationResult& r) const;
  void keepPlaces(const Eigen::Isometry3d& T_odom_base, const LocalizationResult& r);
  void suggestGoal(const Eigen::Isometry3d& T_odom_base, LocalizationResult& r);
  static bool samePlaces(const std::vector<KeptPlace>& a, const std::vector<KeptPlace>& b);
  void placeInRoom(LocalizationResult& r) const;
  void stepPeer(const Eigen::Isometry3d& T_odom_base, const PointSource& points_lidar, LocalizationResult& r);
};

}  // namespace bimloc
