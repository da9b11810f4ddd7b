// Reads back a dataset in the plain-file form `bimloc simulate` writes (clouds/*.pcd with
// clouds/index.csv, odometry.tum, ground_truth.tum, metadata.json), so that `bimloc localize`
// runs on recordings, simulated or from a real robot converted to that form.
#pragma once

#include <Eigen/Geometry>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

struct StampedPose {
  double stamp_s = 0;
  Eigen::Isometry3d pose = Eigen::Isometry3d::Identity();
};

// Odometry (or ground-truth) samples that are no pose: dropped, by reason
// (recording_checks.hpp's checkedPose counts them; a TUM line with a non-finite stamp too).
struct PoseSampleDrops {
  std::size_t read = 0;
  std::size_t non_finite = 0, zero_quaternion = 0, not_unit_quaternion = 0;
  std::size_t dropped() const { return non_finite + zero_quaternion + not_unit_quaternion; }
};

struct DatasetScan {
  std::string file;  // path of the PCD
  double stamp_s = 0;
  std::size_t points = 0;  // as clouds/index.csv and the PCD's header say
};

struct RecordedDataset {
  std::string dir;
  Eigen::Isometry3d T_base_lidar = Eigen::Isometry3d::Identity();
  double turn_period_s = 0.1;
  std::string storey;  // as recorded, may be empty
  std::vector<DatasetScan> scans;
  std::vector<StampedPose> odometry;      // odom -> base_link
  std::vector<StampedPose> ground_truth;  // map -> base_link, empty when not recorded
  PoseSampleDrops odometry_drops, ground_truth_drops;  // samples read and dropped (no pose)
};

// Reads and checks the whole dataset before any of it is used: metadata.json of a supported
// version with a unit-quaternion mount, every indexed PCD present with a sound header that
// agrees with its size and with the index, finite and strictly increasing stamps in the index
// and in the TUM files, clouds and odometry (and ground truth, when recorded) overlapping in
// time. Throws std::runtime_error "FILE[:LINE]: problem" for the first thing wrong. A TUM sample
// that is no pose (non-finite, a quaternion zero or off unit norm) is not an error: it is
// dropped and counted in odometry_drops / ground_truth_drops, as the bag readers do; only a
// file of nothing else is refused.
RecordedDataset readDataset(const std::string& dir);
// x, y, z of every point of a PCD (v0.7, binary or ascii, float x y z fields).
std::vector<Eigen::Vector3f> readPcdPoints(const std::string& path);
// The pose of the sample nearest to t (samples sorted by stamp).
const StampedPose& nearest(const std::vector<StampedPose>& samples, double t);

}  // namespace bimloc::sim
