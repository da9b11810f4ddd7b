#include "sim/dataset/recording_checks.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bimloc::sim {
namespace {

std::string number(double v, int decimals) {
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", decimals, v);
  return buffer;
}

// "3 non-finite, 5 at the origin": the non-zero counts, or "" when all are zero.
std::string reasons(const std::vector<std::pair<std::size_t, std::string>>& counts) {
  std::string out;
  for (const auto& [n, why] : counts)
    if (n) out += (out.empty() ? "" : ", ") + std::to_string(n) + " " + why;
  return out;
}

std::string poseDrops(const PoseSampleDrops& d, const std::string& what) {
  if (!d.dropped()) return {};
  return what + ": " + std::to_string(d.dropped()) + " of " + std::to_string(d.read) + " samples dropped (" +
         reasons({{d.non_finite, "not finite"}, {d.zero_quaternion, "with a zero quaternion"},
                  {d.not_unit_quaternion, "with a quaternion not of unit norm"}}) +
         ")";
}

}  // namespace

PointDrops& PointDrops::operator+=(const PointDrops& o) {
  read += o.read, non_finite += o.non_finite, at_origin += o.at_origin;
  below_min_range += o.below_min_range, beyond_max_range += o.beyond_max_range;
  return *this;
}

PointDrops keepUsablePoints(std::vector<Eigen::Vector3f>& xyz, std::vector<double>* time_s, const SensorRange& range,
                            const PointDrops& before) {
  PointDrops d = before;
  d.read = xyz.size() + before.dropped();
  const bool timed = time_s && time_s->size() == xyz.size() && !time_s->empty();
  std::size_t kept = 0;
  for (std::size_t i = 0; i < xyz.size(); ++i) {
    const double r = xyz[i].cast<double>().norm();  // in double: a float's square may overflow
    if (!std::isfinite(r)) ++d.non_finite;
    else if (r <= 1e-6) ++d.at_origin;  // the "no return" of drivers that write zeros
    else if (r < range.min_m) ++d.below_min_range;
    else if (r > range.max_m) ++d.beyond_max_range;
    else {
      xyz[kept] = xyz[i];
      if (timed) (*time_s)[kept] = (*time_s)[i];
      ++kept;
    }
  }
  xyz.resize(kept);
  if (timed) time_s->resize(kept);
  return d;
}

std::optional<Eigen::Isometry3d> checkedPose(double x, double y, double z, double qx, double qy, double qz, double qw,
                                             PoseSampleDrops& drops) {
  ++drops.read;
  const Eigen::Quaterniond q(qw, qx, qy, qz);
  const double norm = q.norm();
  if (!std::isfinite(x) || !std::isfinite(y) || !std::isfinite(z) || !std::isfinite(norm)) {
    ++drops.non_finite;
    return std::nullopt;
  }
  if (norm == 0) {
    ++drops.zero_quaternion;
    return std::nullopt;
  }
  if (std::abs(norm - 1.0) > 1e-3) {
    ++drops.not_unit_quaternion;
    return std::nullopt;
  }
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, z);
  return T;
}

OdometryJumps findJumps(const std::vector<StampedPose>& samples, const MotionLimits& limits) {
  OdometryJumps jumps;
  double worst_share = 0;
  for (std::size_t i = 1; i < samples.size(); ++i) {
    const double dt = samples[i].stamp_s - samples[i - 1].stamp_s;
    const double scale = std::max(dt, limits.at_interval_s) / limits.at_interval_s;
    const Eigen::Isometry3d step = samples[i - 1].pose.inverse() * samples[i].pose;
    const double m = step.translation().norm();
    const double deg = Eigen::AngleAxisd(step.linear()).angle() * 180.0 / M_PI;
    const double share = std::max(m / (limits.max_step_m * scale), deg / (limits.max_step_deg * scale));
    if (share <= 1.0) continue;
    ++jumps.count;
    if (share > worst_share) worst_share = share, jumps.worst_m = m, jumps.worst_deg = deg, jumps.worst_stamp_s = samples[i].stamp_s;
  }
  return jumps;
}

std::vector<std::string> RecordingChecks::warnings() const {
  std::vector<std::string> out;
  if (scans_skipped) {
    std::string names;
    for (const auto& n : skipped_names) names += (names.empty() ? "" : "; ") + n;
    out.push_back(std::to_string(scans_skipped) + " of " + std::to_string(scans) +
                  " scans skipped: no usable point (" + names + (skipped_names.size() < scans_skipped ? "; ..." : "") + ")");
  }
  if (points.dropped())
    out.push_back(std::to_string(points.dropped()) + " of " + std::to_string(points.read) + " points dropped (" +
                  reasons({{points.non_finite, "not finite"}, {points.at_origin, "at the sensor's origin"},
                           {points.below_min_range, "below the sensor's min range"},
                           {points.beyond_max_range, "beyond the sensor's max range"}}) +
                  ")");
  if (auto w = poseDrops(odometry, "odometry"); !w.empty()) out.push_back(w);
  if (odometry_jumps.count)
    out.push_back("odometry: " + std::to_string(odometry_jumps.count) +
                  " jumps beyond what a base can do (2 m or 45 deg per 20 ms); the largest " + number(odometry_jumps.worst_m, 2) +
                  " m, " + number(odometry_jumps.worst_deg, 1) + " deg at stamp " + number(odometry_jumps.worst_stamp_s, 3) + " s");
  if (auto w = poseDrops(ground_truth, "ground truth"); !w.empty()) out.push_back(w);
  for (const auto& [w, n] : layout_warnings) out.push_back(w + " (" + std::to_string(n) + (n == 1 ? " scan)" : " scans)"));
  return out;
}

}  // namespace bimloc::sim
