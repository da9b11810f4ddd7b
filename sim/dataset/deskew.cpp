#include "sim/dataset/deskew.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim {

namespace {

// interpolatePose over many times of one turn: the two samples around the last time, and their
// rotations as quaternions, kept while the next time falls between the same two (a turn's
// 1800 firings fall between a few samples). The same arithmetic, so the same pose to the bit.
class PoseInterpolator {
 public:
  explicit PoseInterpolator(const std::vector<StampedPose>& samples) : samples_(samples) {}

  Eigen::Isometry3d at(double t) {
    // lower_bound's answer: the first sample not before t (the one kept, when the one before it is before t).
    const bool kept = after_ != samples_.end() && after_ != samples_.begin() && after_->stamp_s >= t && std::prev(after_)->stamp_s < t;
    if (!kept) {
      after_ = std::lower_bound(samples_.begin(), samples_.end(), t, [](const StampedPose& s, double v) { return s.stamp_s < v; });
      if (after_ == samples_.begin()) return samples_.front().pose;
      if (after_ == samples_.end()) return samples_.back().pose;
      qa_ = Eigen::Quaterniond(std::prev(after_)->pose.linear());
      qb_ = Eigen::Quaterniond(after_->pose.linear());
      // What Eigen's slerp computes from the two rotations alone, kept with them.
      dot_ = qa_.dot(qb_);
      abs_dot_ = std::abs(dot_);
      if (!(abs_dot_ >= kSlerpOne)) theta_ = std::acos(abs_dot_), sin_theta_ = std::sin(theta_);
    }
    const StampedPose& a = *std::prev(after_);
    const StampedPose& b = *after_;
    const double f = (t - a.stamp_s) / (b.stamp_s - a.stamp_s);
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = (1 - f) * a.pose.translation() + f * b.pose.translation();
    T.linear() = slerp(f).toRotationMatrix();
    return T;
  }

 private:
  // Eigen's QuaternionBase::slerp (Eigen 3.4, Quaternion.h), step by step with its acos and
  // sin of the pair kept: the same operations on the same numbers, so the same rotation to the
  // bit (tests/test_same_bits.cpp holds it to Eigen's), at two sines a time instead of four
  // transcendental calls.
  static constexpr double kSlerpOne = 1.0 - Eigen::NumTraits<double>::epsilon();
  Eigen::Quaterniond slerp(double f) const {
    double scale0 = 1.0 - f, scale1 = f;
    if (!(abs_dot_ >= kSlerpOne)) {
      scale0 = std::sin((1.0 - f) * theta_) / sin_theta_;
      scale1 = std::sin(f * theta_) / sin_theta_;
    }
    if (dot_ < 0.0) scale1 = -scale1;
    return Eigen::Quaterniond(scale0 * qa_.coeffs() + scale1 * qb_.coeffs());
  }

  const std::vector<StampedPose>& samples_;
  std::vector<StampedPose>::const_iterator after_ = samples_.end();
  Eigen::Quaterniond qa_, qb_;
  double dot_ = 0, abs_dot_ = 0, theta_ = 0, sin_theta_ = 1;
};

// A float time's rounding below its cycle's start, as a fraction of the cycle (a float's
// relative precision at a 0.1 s turn is 1e-8 s, a 5e-4 of a 55 us cycle's start: this covers it).
constexpr double kCycleRounding = 1e-2;

}  // namespace

Eigen::Isometry3d interpolatePose(const std::vector<StampedPose>& samples, double t) { return PoseInterpolator(samples).at(t); }

void deskew(std::vector<Eigen::Vector3f>& points, const std::vector<double>& time_s, double stamp_s, double reference_s,
            const std::vector<StampedPose>& odometry, const Eigen::Isometry3d& T_base_lidar, double cycle_s) {
  if (odometry.empty() || time_s.size() != points.size()) return;
  PoseInterpolator odom(odometry);
  const Eigen::Isometry3d T_ref_odom = (odom.at(reference_s) * T_base_lidar).inverse();
  // The driver gives the points of one firing the same time: one transform per distinct time.
  double cached_time = std::nan("");
  Eigen::Isometry3f T_ref_point = Eigen::Isometry3f::Identity();
  for (std::size_t i = 0; i < points.size(); ++i) {
    // The cycle's start: times are floats (a driver's), a hair below c cycle_s at worst, and
    // the last firing of a cycle is 0.63 of it past its start.
    const double time = cycle_s > 0.0 ? std::floor(time_s[i] / cycle_s + kCycleRounding) * cycle_s : time_s[i];
    if (!(time == cached_time)) {
      cached_time = time;
      T_ref_point = (T_ref_odom * odom.at(stamp_s + time) * T_base_lidar).cast<float>();
    }
    points[i] = T_ref_point * points[i];
  }
}

std::vector<Eigen::Vector3f> deskewedTurn(const LidarScan& scan, const std::vector<StampedPose>& odometry, double reference_s,
                                          const Eigen::Isometry3d& T_base_lidar, double cycle_s) {
  std::vector<Eigen::Vector3f> points;
  points.reserve(scan.points.size());
  for (const auto& p : scan.points) points.emplace_back(p.x, p.y, p.z);
  if (odometry.empty()) return points;
  std::vector<double> time_s;
  time_s.reserve(scan.points.size());
  for (const auto& p : scan.points) time_s.push_back(p.time);
  deskew(points, time_s, scan.stamp_s, reference_s, odometry, T_base_lidar, cycle_s);
  return points;
}

}  // namespace bimloc::sim
