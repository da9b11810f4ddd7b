// The paper's whole pipeline behind one call: what a robot (or the bench) does with each lidar
// turn. Walls are extracted from the points (planes/), the room-aware particle filter finds the
// robot in the plan (pf/; paper, "Localization using Particle Filter"), and once it has
// converged the S-Graph tracks it (sgraph/; paper, "S-Graph based Localization"). When the
// tracker loses the plan, the filter searches again around the last pose.
//
//   bimloc::Localizer localizer(building, T_base_lidar, config);
//   for each turn:  auto r = localizer.step(stamp_s, T_odom_base, points_lidar);
//                   if (r.T_map_odom) publish(*r.T_map_odom);   // REP 105: map -> odom
//
// Frames (REP 105): map = the plan's frame, odom, base_link, and the lidar (T_base_lidar, the
// mount). The points are in the lidar frame, as the sensor gives them.
#pragma once

#include <bimloc/bim/building.hpp>
#include <bimloc/guide/look_goal.hpp>
#include <bimloc/peers/amcl_config.hpp>
#include <bimloc/peers/ndt_config.hpp>
#include <bimloc/peers/peer_report.hpp>
#include <bimloc/pf/storey_bank.hpp>
#include <bimloc/planes/plane_extraction.hpp>
#include <bimloc/sgraph/sgraph_tracker.hpp>
#include <bimloc/storeys/storey_follower.hpp>

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bimloc {

enum class LocalizerMethod {
  SGraph,     // the paper: the filter, then the S-Graph tracks
  Pf,         // the filter, which then tracks with its own particles
  PfNoRooms,  // the filter without the room factor (the paper's ablation), tracking likewise
  Amcl,       // peer: ROS-style AMCL on a 2D slice of the storey mesh (the paper's baseline)
  Ndt,        // peer: HDL-style NDT, branch-and-bound global search then scan-to-map NDT
};
bool isPeer(LocalizerMethod method);  // Amcl or Ndt: needs a known storey, no wall planes
const char* toString(LocalizerMethod method);
std::optional<LocalizerMethod> methodFromString(const std::string& name);  // "sgraph", "pf", "pf-no-rooms", "amcl", "ndt"

struct LocalizerConfig {
  LocalizerMethod method = LocalizerMethod::SGraph;
  // The storey the robot is on (name, GlobalId, index, or Building::storeyLabel where a name is
  // several storeys'); empty: unknown, every storey with walls and rooms is considered and the
  // scans decide (pf::StoreyBank).
  std::string storey;
  // Seeds every stage (RANSAC, particles): the stages' own `seed` fields are replaced from it,
  // so one number reproduces a run byte for byte.
  std::uint64_t seed = 0;
  planes::PlaneExtractionConfig planes;
  pf::ParticleFilterConfig pf;  // pf.use_rooms follows `method`
  sgraph::SGraphConfig sgraph;
  peers::AmclConfig amcl;  // method Amcl only
  peers::NdtConfig ndt;    // method Ndt only
  // While searching with several places left: where to look next (LocalizationResult::goal).
  guide::GuideConfig guide;
  // Search again after a loss of track: the filter's particles start within this of the last
  // tracked pose (1 sigma; the tracker drifted at most a few keyframes of odometry before it
  // said lost), the heading within relocalize_sigma_yaw_deg.
  double relocalize_sigma_m = 2.0;
  double relocalize_sigma_yaw_deg = 30.0;
  // Following the robot across storeys (issue 31): its height (the odometry's z, an altitude
  // when observeAltitude is given one) and the plan's stairs say when it arrived on another
  // storey; the tracker goes on there. With an altitude, the first search leaves out the
  // storeys it rules out (storey unknown).
  storeys::StoreyFollowConfig storeys;
  // The points given to step() are de-skewed: every point moved into the lidar frame at the
  // step's stamp with the odometry over the turn (a driver's or LIO's de-skew; the bench's
  // loop and `bimloc localize` with a per-point time field). The free-space evidence then
  // leaves the turn's skew out, but for the odometry's own error over it (range_profile.hpp).
  bool points_deskewed = false;
};

enum class LocalizationState {
  Searching,  // the filter has not converged yet: T_map_base is its best guess, T_map_odom unset
  Converged,  // the filter converged on this step: T_map_odom is known from now on
  Tracking,   // after convergence: the S-Graph (or the filter, for the pf methods) tracks
  Lost,       // the tracker lost the plan; the filter searches again around the last pose
};
const char* toString(LocalizationState state);

// The robot arrived on another storey, and the localizer followed it: the link between the
// storeys' graphs (the pose carried across, by the odometry along the flight).
struct StoreyLink {
  std::size_t from_storey = 0, to_storey = 0;
  int flight = -1;  // the flight it came by (index into Building::stairs), -1 when the plan has none there
  double stamp_s = 0;
  Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();  // carried onto the new storey
};

struct LocalizationResult {
  LocalizationState state = LocalizationState::Searching;
  double stamp_s = 0;
  Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();
  std::optional<Eigen::Isometry3d> T_map_odom;  // once converged (kept, dead reckoning, while lost)
  // Covariance of (x, y, yaw) of T_map_base in the map frame: the particles' spread from the
  // filter; the S-Graph's marginal covariance of its newest keyframe while it tracks.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Identity();
  std::optional<std::size_t> storey;  // index into Building::storeys, once decided
  std::size_t leading_storey = 0;     // the decided storey, else the one leading the search
  int room = -1;                      // index into the storey's rooms of T_map_base, -1 outside every room
  std::string room_name;
  std::optional<double> convergence_stamp_s;  // the stamp of the (first) convergence
  int losses = 0;                             // losses of track so far
  bool used_points = false;                   // this step extracted planes from the points
  int walls_observed = 0;                     // wall planes extracted this step
  // What each stage said on this step: the filter while it runs (searching, pf tracking, or
  // searching again after a loss), the S-Graph while it tracks.
  std::optional<pf::StoreyBankReport> filter;
  std::optional<sgraph::SGraphResult> sgraph;
  std::optional<peers::PeerReport> peer;  // methods Amcl and Ndt: every step
  std::optional<StoreyLink> arrival;   // this step moved the localizer to another storey
  std::vector<std::string> warnings;  // this step's, from every stage
  // While searching (the paper's method and its ablations, on the leading storey), when the path
  // evidence fits two or more places: the places (map pose of the base now, best first, with the
  // evidence margin of the best over each: 0 for the best), as of the last refresh (a weighing at
  // most every config.guide.places_interval_s; moved on by the odometry since), and, with
  // config.guide.enabled, a goal from which their scans would differ most (guide/look_goal.hpp;
  // unset when nothing within reach tells them apart). Empty and unset otherwise.
  std::vector<guide::Place> places;
  std::optional<guide::LookGoal> goal;
};

class Localizer {
 public:
  // The building must outlive the localizer. Throws std::invalid_argument when the storey is
  // not in the plan, or no storey can hold the robot (walls and rooms), or a peer method
  // (Amcl, Ndt) is asked to choose among several storeys.
  Localizer(const bim::Building& building, const Eigen::Isometry3d& T_base_lidar, const LocalizerConfig& config);
  ~Localizer();
  Localizer(Localizer&&) noexcept;

  // One lidar turn: its stamp (the time its planes are best explained at, e.g. mid-turn), the
  // odometry pose odom <- base_link at that time, and its points in the lidar frame.
  LocalizationResult step(double stamp_s, const Eigen::Isometry3d& T_odom_base, const std::vector<Eigen::Vector3f>& points_lidar);
  // The same, with the points read only when this step uses them: most turns are not weighed
  // (the robot has not moved enough), so a reader of recorded scans can skip loading them.
  using PointSource = std::function<std::vector<Eigen::Vector3f>()>;
  LocalizationResult step(double stamp_s, const Eigen::Isometry3d& T_odom_base, const PointSource& points_lidar);

  // An altitude reading (a barometer, or any altimeter): the base's height above the plan's
  // z = 0, with its 1-sigma. Optional; it holds for the steps after it, until the next one.
  // What it is for (issue 31): storeys it rules out are not searched, and a climb is confirmed.
  void observeAltitude(double stamp_s, double altitude_m, double sigma_m);
  const LocalizerConfig& config() const;
  const pf::StoreyBank* filter() const;                  // the current (or last) search; null for the peers
  const sgraph::SGraphTracker* tracker() const;          // while (or since) the S-Graph tracks; null before
  // One graph per storey: the S-Graph of each storey the robot left, with the link it left
  // by, oldest first (the current storey's graph is tracker()).
  struct StoreyGraph {
    std::size_t storey = 0;
    const sgraph::SGraphTracker* tracker = nullptr;
    StoreyLink left_by;
  };
  std::vector<StoreyGraph> storeyGraphs() const;
  const std::vector<StoreyLink>& storeyLinks() const;    // every arrival so far
  const std::vector<std::string>& warnings() const;      // from the construction (the plan, the config)

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc
