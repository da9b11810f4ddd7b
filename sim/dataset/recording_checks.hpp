// What a recording's readers drop, and why, so that garbage never passes in silence: points
// no lidar can have measured (non-finite, at the origin, out of the sensor's range), scans
// with no usable point, odometry samples that are no pose (non-finite, a quaternion that is
// zero or not of unit norm), and odometry jumps no base can make. The same checks for every
// kind of recording (dataset folder, ROS 1 bag, ROS 2 bag); `bimloc localize` sums them into
// its summary and report.json (docs/recording_checks.md).
#pragma once

#include "sim/dataset/dataset_reader.hpp"

#include <Eigen/Core>

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

// The lidar's measuring range: a return nearer than min_m or beyond max_m is no measurement.
// Default: the VLP-16 (the manual's 100 m; the ROS driver's 0.4 m minimum).
struct SensorRange {
  double min_m = 0.4;
  double max_m = 100.0;
};

// Points of the scans read, and the ones dropped by reason.
struct PointDrops {
  std::size_t read = 0;  // declared by the scans (width x height, or the PCD's POINTS)
  std::size_t non_finite = 0, at_origin = 0, below_min_range = 0, beyond_max_range = 0;
  std::size_t dropped() const { return non_finite + at_origin + below_min_range + beyond_max_range; }
  PointDrops& operator+=(const PointDrops& o);
};

// Keeps the points that a lidar can have measured (and their times, when `time_s` is not
// null and not empty); counts the others, with `before`: the points dropped before, by reason
// (decodeCloud's non-finite ones, a packet decoder's range filter; its `read` is not used).
PointDrops keepUsablePoints(std::vector<Eigen::Vector3f>& xyz, std::vector<double>* time_s, const SensorRange& range,
                            const PointDrops& before = {});

// PoseSampleDrops (dataset_reader.hpp): odometry (or ground-truth) samples that are no pose.

// The pose of a sample, or nothing (counted in `drops`) when it is not finite or its
// quaternion is zero or off unit norm by more than 1e-3.
std::optional<Eigen::Isometry3d> checkedPose(double x, double y, double z, double qx, double qy, double qz, double qw,
                                             PoseSampleDrops& drops);

// What a base can do between two odometry samples. The bound is a speed: 2 m or 45 deg
// between two samples at 50 Hz (100 m/s, 2250 deg/s: far beyond any ground robot, so only a
// teleport, a reset or a corrupt sample exceeds it), over the time between them, but never
// below the 50 Hz bound (no base has a smaller excursion for a shorter interval: a sample
// pair 1 ms apart with 1.5 m between them is no sign of anything wrong with the odometry rate).
struct MotionLimits {
  double max_step_m = 2.0;
  double max_step_deg = 45.0;
  double at_interval_s = 0.02;  // 50 Hz
};

struct OdometryJumps {
  std::size_t count = 0;
  double worst_m = 0, worst_deg = 0, worst_stamp_s = 0;  // the largest jump (by its share of the bound)
};

// Consecutive samples (sorted by stamp) whose translation or rotation exceeds the bound.
OdometryJumps findJumps(const std::vector<StampedPose>& samples, const MotionLimits& limits = {});

// Everything one recording's run dropped or found odd (ScenarioResult::recording).
struct RecordingChecks {
  std::size_t scans = 0;          // scans read
  std::size_t scans_skipped = 0;  // with no usable point: never given to the localizer
  std::vector<std::string> skipped_names;  // the first few skipped scans
  PointDrops points;
  PoseSampleDrops odometry;
  OdometryJumps odometry_jumps;
  PoseSampleDrops ground_truth;
  std::map<std::string, std::size_t> layout_warnings;  // checkCloudLayout's, with the scans they came from
  // One line per kind of problem found, with its counts: the warnings of the run.
  std::vector<std::string> warnings() const;
};

}  // namespace bimloc::sim
