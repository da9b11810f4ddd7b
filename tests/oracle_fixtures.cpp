#include "oracle_fixtures.hpp"

#include "sgraph_fixtures.hpp"

#include <cmath>

namespace bimloc::test {

// A wall whose room-side face runs along a -> b at the given side (thickness 0.2 m, the axis
// 0.1 m behind the face), grown 0.2 m at both ends so that corners close.
void addWall(bim::Storey& s, Eigen::Vector2d a, Eigen::Vector2d b, const Eigen::Vector2d& offset) {
  const Eigen::Vector2d u = (b - a).normalized();
  a += offset - 0.2 * u, b += offset + 0.2 * u;
  s.walls.push_back(test::boxWall("W" + std::to_string(s.walls.size()), a, b, 0.2));
}

// The nearest face hit along the ray from p at heading a, within max_range.
std::optional<Eigen::Vector2d> castRay(const bim::Storey& s, const Eigen::Vector2d& p, double a, double max_range) {
  const Eigen::Vector2d d(std::cos(a), std::sin(a));
  double best = max_range;
  bool hit = false;
  for (const auto& w : s.walls)
    for (const auto& f : w.faces) {
      const Eigen::Vector2d f0 = f.start.head<2>(), e = f.end.head<2>() - f0;
      const double den = d.x() * e.y() - d.y() * e.x();
      if (std::abs(den) < 1e-12) continue;
      const Eigen::Vector2d w0 = f0 - p;
      const double t = (w0.x() * e.y() - w0.y() * e.x()) / den, u = (w0.x() * d.y() - w0.y() * d.x()) / den;
      if (u >= 0 && u <= 1 && t > 1e-6 && t < best) best = t, hit = true;
    }
  if (!hit) return std::nullopt;
  return p + best * d;
}

// Waypoints at 0.5 m/s, heading along each leg, a pose every 0.1 s (a 10 Hz lidar).
Walk walk(const std::vector<Eigen::Vector2d>& waypoints) {
  Walk w;
  double t = 0;
  for (std::size_t k = 0; k + 1 < waypoints.size(); ++k) {
    const Eigen::Vector2d a = waypoints[k], b = waypoints[k + 1];
    const double yaw = std::atan2(b.y() - a.y(), b.x() - a.x()), length = (b - a).norm();
    for (double s = 0; s < length; s += 0.05, t += 0.1) w.times.push_back(t), w.poses.emplace_back(a.x() + s * std::cos(yaw), a.y() + s * std::sin(yaw), yaw);
  }
  return w;
}

// One turn from `pose`: a ray a degree, range noise 1 cm, each return at the band's height and
// again above it (the ceiling's rows, which the oracle must drop). Lidar frame = base frame.
std::vector<Eigen::Vector3f> scanFrom(const bim::Storey& s, const Eigen::Vector3d& pose, double max_range, std::mt19937& rng) {
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<Eigen::Vector3f> points;
  for (int k = 0; k < 360; ++k) {
    const double a = pose.z() + k * M_PI / 180.0;
    const auto hit = castRay(s, pose.head<2>(), a, max_range);
    if (!hit) continue;
    const double range = (*hit - pose.head<2>()).norm() + noise(rng), local = k * M_PI / 180.0;
    points.emplace_back(static_cast<float>(range * std::cos(local)), static_cast<float>(range * std::sin(local)), 0.5f);
    points.emplace_back(static_cast<float>(range * std::cos(local)), static_cast<float>(range * std::sin(local)), 2.0f);
  }
  return points;
}

// The oracle's verdict on the walk: odometry exact, in an odom frame turned and moved from the map's.
std::vector<sim::oracle::Keyframe> oracleKeyframes(const bim::Storey& s, const Walk& w, double max_range,
                                                    const sim::oracle::OracleConfig& config, const bim::Storey* site) {
  std::mt19937 rng(7);
  const Eigen::Isometry3d T_odom_map = Eigen::Translation3d(3.0, -2.0, 0.0) * Eigen::AngleAxisd(0.7, Eigen::Vector3d::UnitZ());
  sim::oracle::KeyframeRecorder recorder(config, Eigen::Isometry3d::Identity(), kOracleBaseZ);
  for (std::size_t k = 0; k < w.poses.size(); ++k) {
    const Eigen::Vector3d& p = w.poses[k];
    const Eigen::Isometry3d T_map_base = Eigen::Translation3d(p.x(), p.y(), kOracleBaseZ) * Eigen::AngleAxisd(p.z(), Eigen::Vector3d::UnitZ());
    recorder.add(w.times[k], T_odom_map * T_map_base, [&] { return scanFrom(site ? *site : s, p, max_range, rng); });
  }
  return recorder.keyframes();
}

sim::oracle::OracleVerdict runOracle(const bim::Storey& s, const Walk& w, double max_range, const sim::oracle::OracleConfig& config,
                                     const bim::Storey* site) {
  return decideWhen(s, 0.0, oracleKeyframes(s, w, max_range, config, site), w.poses.front(), config);
}

sim::oracle::OracleConfig smallMargin() {
  sim::oracle::OracleConfig c;
  c.margin_m = 1.0;  // the test buildings stand alone: a metre around them is enough room for rivals
  return c;
}

}  // namespace bimloc::test
