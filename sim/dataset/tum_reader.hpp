// Reading a trajectory in the TUM RGB-D format ("timestamp tx ty tz qx qy qz qw" per line,
// '#' comments), as evo's file_interface.read_tum_trajectory_file reads it, but with an error
// at FILE:LINE for a bad line instead of a failed array conversion.
#pragma once

#include <Eigen/Geometry>

#include <string>
#include <vector>

namespace bimloc::sim {

struct TumTrajectory {
  std::string path;
  std::vector<double> stamps_s;             // strictly increasing
  std::vector<Eigen::Isometry3d> poses;     // rotation from the normalised quaternion
  std::vector<std::string> warnings;        // e.g. non-unit quaternions (normalised)
};

// Throws std::runtime_error "FILE:LINE: problem" for a line that is not 8 finite numbers, a
// zero quaternion or a stamp not after the previous one; "FILE: ..." for an unreadable file
// or one with no pose. A quaternion whose norm is off 1 by more than 1e-6 is normalised,
// with one warning per file (how many, and the first line).
TumTrajectory readTum(const std::string& path);

}  // namespace bimloc::sim
