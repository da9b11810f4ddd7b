#include "sim/dataset/tum_writer.hpp"

#include "sim/dataset/dataset_clock.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <stdexcept>

namespace bimloc::sim {

Eigen::Quaterniond canonicalRotation(const Eigen::Isometry3d& pose) {
  Eigen::Quaterniond q(pose.linear());
  q.normalize();
  if (q.w() < 0) q.coeffs() = -q.coeffs();
  return q;
}

std::string tumLine(std::uint64_t stamp_ns, const Eigen::Isometry3d& pose) {
  const Eigen::Quaterniond q = canonicalRotation(pose);
  const Eigen::Vector3d t = pose.translation();
  // %.9g keeps nanometres on a building's scale and 1e-9 on unit quaternion components.
  char text[256];
  std::snprintf(text, sizeof text, "%s %.9g %.9g %.9g %.9g %.9g %.9g %.9g", formatStampS(stamp_ns).c_str(), t.x(),
                t.y(), t.z(), q.x(), q.y(), q.z(), q.w());
  return text;
}

TumWriter::TumWriter(std::string path, const std::string& comment) : path_(std::move(path)) {
  out_.open(path_, std::ios::trunc);
  if (!out_) throw std::runtime_error(path_ + ": cannot create: " + std::strerror(errno));
  out_ << "# " << comment << "\n";
}

void TumWriter::add(std::uint64_t stamp_ns, const Eigen::Isometry3d& pose) {
  out_ << tumLine(stamp_ns, pose) << '\n';
  if (!out_) throw std::runtime_error(path_ + ": write failed");
  ++count_;
}

void TumWriter::close() {
  if (!out_.is_open()) return;
  out_.close();
  if (!out_) throw std::runtime_error(path_ + ": write failed");
}

}  // namespace bimloc::sim
