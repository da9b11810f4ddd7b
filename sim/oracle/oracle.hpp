// The information-limit oracle (issue 28 §1, docs/oracle.md): it knows the truth and answers
// from what time the scans so far rule out every place of the storey but the true one.
// Independent of the localizer's code: its own model of the scans (a height band of points
// against the plan's wall faces), its own search (every start pose of the storey on a grid,
// branch-and-bound) and a likelihood-ratio test with a stated false-alarm rate.
#pragma once

#include "sim/oracle/oracle_config.hpp"
#include "sim/oracle/wall_field.hpp"

#include <bimloc/bim/building.hpp>

#include <Eigen/Geometry>
#include <functional>
#include <optional>
#include <vector>

namespace bimloc::sim::oracle {

// A scan the path keeps: its time, the odometry then (x, y, yaw) and its points in the band,
// projected to the base frame's xy.
struct Keyframe {
  double time_s = 0;
  Eigen::Vector3d odom = Eigen::Vector3d::Zero();
  std::vector<Eigen::Vector2f> points;
};

// Turn by turn, what the oracle keeps of a run: keyframes (bounded: a few hundred points each).
class KeyframeRecorder {
 public:
  // base_above_floor_m: the base frame's height above the floor (the band is above the floor).
  KeyframeRecorder(const OracleConfig& config, const Eigen::Isometry3d& T_base_lidar, double base_above_floor_m);
  // One turn at time_s; `points` (lidar frame) is called only when the turn becomes a keyframe.
  void add(double time_s, const Eigen::Isometry3d& T_odom_base, const std::function<std::vector<Eigen::Vector3f>()>& points);
  const std::vector<Keyframe>& keyframes() const { return keyframes_; }

 private:
  OracleConfig config_;
  Eigen::Isometry3d T_base_lidar_;
  double z_low_, z_high_;  // the band in the base frame
  std::vector<Keyframe> keyframes_;
};

// The band points of one scan (lidar frame) in the base frame's xy, subsampled as configured.
std::vector<Eigen::Vector2f> bandPoints(const std::vector<Eigen::Vector3f>& lidar_points, const Eigen::Isometry3d& T_base_lidar,
                                        double z_low_base, double z_high_base, const OracleConfig& config);

struct OracleVerdict {
  // The first keyframe's time at which the scans so far rule every rival place out (the test's
  // first crossing, checked every few keyframes); unset when no check does.
  std::optional<double> decidable_at_s;
  double threshold = 0;  // nats: log L(truth) - log L(best rival) needed to rule a rival out
  double rival_places = 0;  // the places the threshold's union bound counts
  double seconds = 0;       // the oracle's wall time
  int keyframes = 0, checks = 0;
  std::size_t points = 0, nodes = 0, cells = 0;
  // With every scan of the run, some rival place explains them better than the truth by the
  // threshold: the test rules the TRUE place out. On a site that is its plan that is the test's
  // false alarm (rate at most alpha); on a site that differs from its plan it says the plain
  // model (every point within the sensor's noise of a plan wall) does not hold there, so neither
  // does its limit: a localizer that decided by it would decide falsely.
  bool truth_ruled_out = false;

  // The robust answer (docs/oracle.md): the same question with one site deviation allowed, a
  // rival ruled out only when it stays so with any one plan wall's points dropped. Never before
  // decidable_at_s; unset when that is, or when no check rules every rival out robustly.
  std::optional<double> decidable_robust_at_s;
  double robust_seconds = 0;  // its wall time, beside `seconds`
  double cpu_seconds = 0, robust_cpu_seconds = 0;  // the thread's CPU time: the plain answer's, the robust one's
  int robust_checks = 0;
  std::size_t robust_nodes = 0, robust_cells = 0;
};

// The threshold ln(M / alpha) for M rival places on free_area_m2 (docs/oracle.md).
double decisionThreshold(double free_area_m2, const OracleConfig& config, double* places = nullptr);

// The storey as the oracle's map: its own rooms and walls, then every other storey's walls, of
// which the band (wallSegmentsInBand) keeps those that stand where a robot on this storey
// senses walls. A plan files each wall under one storey; a split level's stand beside another's
// floor (Jesse.1), and the lidar sees them whichever storey the file names.
bim::Storey withEveryWall(const bim::Building& building, std::size_t storey);

// The verdict for a run on `storey` whose base started at truth_start (x, y, yaw) and kept
// `keyframes`; floor_z: the floor's world z under the start (the band is above it). With
// config.robust, also the robust answer.
OracleVerdict decideWhen(const bim::Storey& storey, double floor_z, const std::vector<Keyframe>& keyframes,
                         const Eigen::Vector3d& truth_start, const OracleConfig& config = {});

// The same verdict on the storey's walls as the band cuts them (wallSegmentsInBand) and each
// segment's wall: what decideWhen calls; a bench can replay a run's keyframes on it.
OracleVerdict decideOnWalls(const std::vector<Segment2>& walls, const std::vector<int>& wall_of, const std::vector<Keyframe>& keyframes,
                            const Eigen::Vector3d& truth_start, const OracleConfig& config = {});

}  // namespace bimloc::sim::oracle
