// The odometry model's drift over many seeds against its analytic statistics.
#include "sim/odometry/odometry_model.hpp"

#include <gtest/gtest.h>

#include <cmath>

using namespace bimloc;

namespace {

Eigen::Isometry3d planarPose(double x, double y, double yaw) {
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.linear() = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  T.translation() = Eigen::Vector3d(x, y, 0.5);
  return T;
}

// Walks a straight line of `length` along x in `steps` increments; returns the final error
// of the odometry (in odom, relative to the truth) along and across the track.
Eigen::Vector2d straightLineError(const sim::OdometryConfig& c, std::uint64_t seed, double length, int steps) {
  sim::NoisyOdometry odom(c, seed);
  sim::OdometrySample last;
  for (int i = 0; i <= steps; ++i) last = odom.step(i * 0.02, planarPose(2.0 + length * i / steps, 3.0, 0.0));
  return last.T_odom_base.translation().head<2>() - Eigen::Vector2d(length, 0.0);
}

double stddev(const std::vector<double>& v) {
  double m = 0, s = 0;
  for (double x : v) m += x;
  m /= double(v.size());
  for (double x : v) s += (x - m) * (x - m);
  return std::sqrt(s / double(v.size() - 1));
}

}  // namespace

TEST(Odometry, PerfectPresetIsTheTruthInTheOdomFrame) {
  sim::NoisyOdometry odom(sim::odometryPreset("perfect"), 1);
  for (int i = 0; i < 500; ++i) {
    const double t = i * 0.02;
    const Eigen::Isometry3d truth = planarPose(1 + std::cos(t), 2 + std::sin(t), 0.3 + t);
    const auto s = odom.step(t, truth);
    const Eigen::Isometry3d expected = odom.T_map_odom_true().inverse() * truth;
    EXPECT_LT((s.T_odom_base.matrix() - expected.matrix()).norm(), 1e-9) << t;
  }
}

TEST(Odometry, IncrementNoiseMatchesTheAnalyticRandomWalk) {
  // Only alpha3: each increment's length gets sigma = sqrt(a3) * trans, independent, so
  // the along-track error after N steps has sigma sqrt(N * a3) * trans.
  sim::OdometryConfig c = sim::odometryPreset("perfect");
  c.alpha3 = 0.04;
  const int steps = 250;
  const double length = 5.0, trans = length / steps;
  std::vector<double> along;
  for (std::uint64_t seed = 0; seed < 2000; ++seed) along.push_back(straightLineError(c, seed, length, steps).x());
  // 2000 seeds: the sample sigma is within 5 % of the true one (3 standard errors).
  EXPECT_NEAR(stddev(along), std::sqrt(steps * c.alpha3) * trans, 0.05 * std::sqrt(steps * c.alpha3) * trans);
}

TEST(Odometry, ScaleBiasGrowsTheErrorWithDistance) {
  sim::OdometryConfig c = sim::odometryPreset("perfect");
  c.scale_bias_sigma = 0.02;
  for (const double length : {10.0, 40.0}) {
    std::vector<double> along;
    for (std::uint64_t seed = 0; seed < 400; ++seed) along.push_back(straightLineError(c, seed, length, 500).x());
    EXPECT_NEAR(stddev(along), c.scale_bias_sigma * length, 0.1 * c.scale_bias_sigma * length) << length;
  }
}

TEST(Odometry, PresetsDriftAsAdvertised) {
  // A 100 m walk: 25 m legs around a square, 90 deg turns. Mean final error / distance.
  const auto drift = [](const std::string& preset) {
    double sum = 0;
    const int seeds = 100;
    for (int seed = 0; seed < seeds; ++seed) {
      sim::NoisyOdometry odom(sim::odometryPreset(preset), static_cast<std::uint64_t>(seed));
      Eigen::Isometry3d truth = planarPose(0, 0, 0);
      sim::OdometrySample s = odom.step(0, truth);
      double t = 0, x = 0, y = 0, yaw = 0;
      for (int leg = 0; leg < 4; ++leg) {
        for (int i = 0; i < 1250; ++i) {  // 25 m at 0.8 m/s, 50 Hz
          x += 0.02 * std::cos(yaw), y += 0.02 * std::sin(yaw), t += 0.02;
          s = odom.step(t, planarPose(x, y, yaw));
        }
        for (int i = 0; i < 75; ++i) {  // 90 deg at 60 deg/s
          yaw += M_PI / 2 / 75, t += 0.02;
          s = odom.step(t, planarPose(x, y, yaw));
        }
      }
      const Eigen::Isometry3d truth_odom = odom.T_map_odom_true().inverse() * planarPose(x, y, yaw);
      sum += (s.T_odom_base.translation() - truth_odom.translation()).head<2>().norm() / 100.0;
    }
    return sum / seeds;
  };
  const double legged = drift("legged"), lidar = drift("lidar");
  EXPECT_GT(legged, 0.01);
  EXPECT_LT(legged, 0.02);
  EXPECT_GT(lidar, 0.003);
  EXPECT_LT(lidar, 0.008);
  EXPECT_THROW(sim::odometryPreset("wheels"), std::invalid_argument);
}
