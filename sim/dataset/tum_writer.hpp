// A trajectory in the TUM RGB-D format ("timestamp tx ty tz qx qy qz qw", one pose per
// line), as evo and the TUM tools read it.
#pragma once

#include <Eigen/Geometry>

#include <cstdint>
#include <fstream>
#include <string>

namespace bimloc::sim {

class TumWriter {
 public:
  // Opens `path` and writes `comment` as the first line, prefixed by "# ".
  TumWriter(std::string path, const std::string& comment);
  void add(std::uint64_t stamp_ns, const Eigen::Isometry3d& pose);
  void close();  // throws std::runtime_error naming the path if anything failed
  std::size_t size() const { return count_; }

 private:
  std::string path_;
  std::ofstream out_;
  std::size_t count_ = 0;
};

// The pose's rotation, normalised, with w >= 0: q and -q are the same rotation, and one sign
// makes equal poses print (and serialise) equally.
Eigen::Quaterniond canonicalRotation(const Eigen::Isometry3d& pose);

// One TUM line for a pose (without the newline), rotation as canonicalRotation().
std::string tumLine(std::uint64_t stamp_ns, const Eigen::Isometry3d& pose);

}  // namespace bimloc::sim
