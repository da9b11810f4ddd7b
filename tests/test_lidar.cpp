// The VLP-16 model against the manual's geometry and against analytic ranges in a box room,
// standing still and turning (motion distortion).
#include "sim_fixtures.hpp"

#include "sim/dataset/deskew.hpp"
#include "sim/lidar/vlp16.hpp"
#include "sim/odometry/odometry_model.hpp"
#include "sim/world/world.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

using namespace bimloc;

namespace {

const Eigen::Vector3d kBox(10, 8, 3);

sim::Vlp16Config noiseFree() {
  sim::Vlp16Config c;
  c.range_noise_sigma_m = 0.0;
  c.T_base_lidar = Eigen::Isometry3d::Identity();
  return c;
}

// Distance from p to the nearest face of the box [0, size] (inside or out).
double boxFaceDistance(const Eigen::Vector3d& size, const Eigen::Vector3d& p) {
  double d = 1e9;
  for (int k = 0; k < 3; ++k) d = std::min({d, std::abs(p[k]), std::abs(size[k] - p[k])});
  return d;
}

// The base standing (or turning at yaw_rate) at the box's centre, 1.2 m above the floor.
std::function<Eigen::Isometry3d(double)> turningBase(double yaw_rate) {
  return [yaw_rate](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    T.translation() = Eigen::Vector3d(5, 4, 1.2);
    T.linear() = Eigen::AngleAxisd(yaw_rate * t, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  };
}

// The firing instant of a point, from its time field, and the laser's direction in the
// sensor frame at that instant (clockwise spin from +x).
Eigen::Vector3d laserDirection(const sim::LidarPoint& p, double rpm) {
  const double el = (-15.0 + 2.0 * p.ring) * M_PI / 180.0;
  const double yaw = -2 * M_PI * rpm / 60.0 * p.time;
  return {std::cos(el) * std::cos(yaw), std::cos(el) * std::sin(yaw), std::sin(el)};
}

double laserOffset(std::uint16_t ring) {
  for (int k = 0; k < 16; ++k)
    if (sim::vlp16Ring(k) == ring) return sim::vlp16VerticalOffsetM(k);
  return 0.0;
}

}  // namespace

TEST(Vlp16, ManualGeometry) {
  std::set<double> angles;
  for (int k = 0; k < 16; ++k) {
    angles.insert(sim::vlp16ElevationDeg(k));
    EXPECT_DOUBLE_EQ(sim::vlp16ElevationDeg(k), -15.0 + 2.0 * sim::vlp16Ring(k));
  }
  EXPECT_EQ(angles.size(), 16u);
  EXPECT_DOUBLE_EQ(sim::vlp16ElevationDeg(0), -15.0);
  EXPECT_DOUBLE_EQ(sim::vlp16ElevationDeg(1), 1.0);
  EXPECT_NEAR(sim::vlp16VerticalOffsetM(0), 0.0112, 1e-12);
  EXPECT_NEAR(sim::vlp16VerticalOffsetM(15), -0.0112, 1e-12);
  for (const auto& [rpm, step] : {std::pair{300.0, 0.1}, {600.0, 0.2}, {1200.0, 0.4}}) {
    sim::Vlp16Config c;
    c.rpm = rpm;
    const sim::Vlp16 lidar(c);
    EXPECT_NEAR(lidar.azimuthStepDeg(), step, 0.002) << rpm;  // the manual's rounded 0.1 / 0.2 / 0.4 deg
    EXPECT_EQ(lidar.cyclesPerTurn(), static_cast<int>(60.0 / rpm / 55.296e-6)) << rpm;
  }
}

TEST(Vlp16, EveryReturnInABoxRoomIsAnalyticAndCarriesItsFiringTime) {
  const sim::World world = sim::World::fromMesh(test::boxRoomFile(kBox.cast<float>()));
  const sim::Vlp16 lidar(noiseFree());
  const auto scan = lidar.scan(world, 0, turningBase(0.0), 0.0, 1, 0);
  // A closed room: no misses, so exactly 16 points per cycle (1808 cycles at 600 rpm).
  EXPECT_EQ(lidar.cyclesPerTurn(), 1808);
  ASSERT_EQ(scan.points.size(), 16u * 1808u);
  for (std::size_t i = 0; i < scan.points.size(); ++i) {
    const auto& p = scan.points[i];
    const int cycle = static_cast<int>(i / 16), firing = static_cast<int>(i % 16);
    EXPECT_NEAR(p.time, cycle * 55.296e-6 + firing * 2.304e-6, 1e-7);
    EXPECT_EQ(p.ring, sim::vlp16Ring(firing));
    const Eigen::Vector3d d = laserDirection(p, 600.0);
    const Eigen::Vector3d o(0, 0, laserOffset(p.ring));
    const Eigen::Vector3d local(p.x, p.y, p.z);
    const double range = (local - o).norm();
    ASSERT_NEAR(range, test::boxRange(kBox, Eigen::Vector3d(5, 4, 1.2) + o, d), 1e-3);
    EXPECT_GE(p.intensity, 0.0f);
    EXPECT_LE(p.intensity, 255.0f);
  }
}

TEST(Vlp16, TheHeadYawKeptPerCycleCastsTheRaysOfTheYawComputedAtEachCycle) {
  // The oracle: each ray's direction with the head's yaw computed afresh at its cycle (cos and
  // sin of -omega t_cycle, as the scan did before it kept them per sensor), then the firings'
  // turn and the elevation, in the same operations: the same floats, turn after turn.
  const sim::World world = sim::World::fromMesh(test::boxRoomFile(kBox.cast<float>()));
  for (const double rpm : {600.0, 300.0}) {
    auto config = noiseFree();
    config.rpm = rpm;
    const sim::Vlp16 lidar(config);
    const double omega = 2.0 * M_PI * rpm / 60.0;
    for (const std::uint64_t turn : {0ull, 7ull}) {
      sim::RayRecord rays;
      lidar.scan(world, 0, turningBase(0.3), 0.1 * static_cast<double>(turn), 1, turn, &rays);
      const auto cycles = static_cast<std::size_t>(lidar.cyclesPerTurn());
      ASSERT_EQ(rays.directions.size(), cycles * 16u);
      for (std::size_t c = 0; c < cycles; ++c) {
        const double t_cycle = static_cast<double>(c) * sim::kVlp16CyclePeriod_s;
        const Eigen::Isometry3d T = turningBase(0.3)(0.1 * static_cast<double>(turn) + t_cycle) * config.T_base_lidar;
        const Eigen::Matrix3f R = T.linear().cast<float>();
        const double c_yaw = std::cos(-omega * t_cycle), s_yaw = std::sin(-omega * t_cycle);
        for (int k = 0; k < 16; ++k) {
          const double el = sim::vlp16ElevationDeg(k) * M_PI / 180.0;
          const double cf = std::cos(-omega * k * sim::kVlp16FiringPeriod_s), sf = std::sin(-omega * k * sim::kVlp16FiringPeriod_s);
          const double cc = c_yaw * cf - s_yaw * sf, ss = s_yaw * cf + c_yaw * sf;
          const Eigen::Vector3f local(float(std::cos(el) * cc), float(std::cos(el) * ss), float(std::sin(el)));
          const Eigen::Vector3f want = R * local;
          ASSERT_EQ(rays.directions[c * 16 + static_cast<std::size_t>(k)], want) << "rpm " << rpm << " turn " << turn << " cycle " << c << " laser " << k;
        }
      }
    }
  }
}

TEST(Vlp16, TurningBaseGivesThePredictedSkewAndTheSwitchRemovesIt) {
  const sim::World world = sim::World::fromMesh(test::boxRoomFile(kBox.cast<float>()));
  const double yaw_rate = 1.0;  // rad/s: the base turns 0.1 rad (5.7 deg) during the turn
  auto config = noiseFree();
  const auto skewed = sim::Vlp16(config).scan(world, 0, turningBase(yaw_rate), 0.0, 1, 0);
  config.motion_distortion = false;
  const auto still = sim::Vlp16(config).scan(world, 0, turningBase(yaw_rate), 0.0, 1, 0);
  double max_skew_effect = 0.0;
  for (const auto& p : skewed.points) {
    const Eigen::Vector3d o(0, 0, laserOffset(p.ring));
    const double range = (Eigen::Vector3d(p.x, p.y, p.z) - o).norm();
    // Analytic: the point fired at time t left the sensor while the base had turned by yaw_rate * t.
    const Eigen::Vector3d d_world = Eigen::AngleAxisd(yaw_rate * p.time, Eigen::Vector3d::UnitZ()) * laserDirection(p, 600.0);
    ASSERT_NEAR(range, test::boxRange(kBox, Eigen::Vector3d(5, 4, 1.2) + o, d_world), 1e-3);
    max_skew_effect = std::max(max_skew_effect, std::abs(range - test::boxRange(kBox, Eigen::Vector3d(5, 4, 1.2) + o,
                                                                             laserDirection(p, 600.0))));
  }
  EXPECT_GT(max_skew_effect, 0.2);  // the skew is real: tens of centimetres at the room's corners
  for (const auto& p : still.points) {
    const Eigen::Vector3d o(0, 0, laserOffset(p.ring));
    ASSERT_NEAR((Eigen::Vector3d(p.x, p.y, p.z) - o).norm(),
                test::boxRange(kBox, Eigen::Vector3d(5, 4, 1.2) + o, laserDirection(p, 600.0)), 1e-3);
  }
}

TEST(Vlp16, NoiseDropoutAndRangeLimitsBehaveAsConfigured) {
  const sim::World world = sim::World::fromMesh(test::boxRoomFile(kBox.cast<float>()));
  auto config = noiseFree();
  config.range_noise_sigma_m = 0.02;
  config.dropout_probability = 0.25;
  const auto scan = sim::Vlp16(config).scan(world, 0, turningBase(0.0), 0.0, 7, 3);
  const double kept = double(scan.points.size()) / (16 * 1808);
  EXPECT_NEAR(kept, 0.75, 0.01);
  double sum = 0, sum2 = 0;
  for (const auto& p : scan.points) {
    const Eigen::Vector3d o(0, 0, laserOffset(p.ring));
    const double e = (Eigen::Vector3d(p.x, p.y, p.z) - o).norm() -
                     test::boxRange(kBox, Eigen::Vector3d(5, 4, 1.2) + o, laserDirection(p, 600.0));
    sum += e, sum2 += e * e;
  }
  const double n = double(scan.points.size());
  EXPECT_NEAR(sum / n, 0.0, 0.001);
  EXPECT_NEAR(std::sqrt(sum2 / n - (sum / n) * (sum / n)), 0.02, 0.001);
  // Same seed and turn: the same scan; another turn index: another noise draw.
  const auto again = sim::Vlp16(config).scan(world, 0, turningBase(0.0), 0.0, 7, 3);
  ASSERT_EQ(again.points.size(), scan.points.size());
  EXPECT_EQ(again.points[100].x, scan.points[100].x);
  config.max_range_m = 4.0;
  for (const auto& p : sim::Vlp16(config).scan(world, 0, turningBase(0.0), 0.0, 7, 3).points)
    EXPECT_LE(std::sqrt(p.x * p.x + p.y * p.y + p.z * p.z), 4.0 + 0.02);
}

// The bench's loop de-skews each turn with the base's noisy odometry (run_scenario.cpp,
// dataset/deskew.hpp): a base turning at 1 rad/s while walking 0.5 m/s, in a box room. Placed
// with the true mid-turn pose, the de-skewed points lie on the box's faces within the range
// noise (and the odometry's error over one turn); the turn as cast does not.
TEST(Vlp16, DeskewWithTheNoisyOdometryPutsATurningWalkingBasesTurnBackOnTheWalls) {
  const sim::World world = sim::World::fromMesh(test::boxRoomFile(kBox.cast<float>()));
  const double yaw_rate = 1.0, speed = 0.5, t0 = 1.0;
  const auto truth = [&](double t) {  // an arc from (3, 3) heading +x
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    const double a = yaw_rate * t;
    T.translation() = Eigen::Vector3d(3 + speed / yaw_rate * std::sin(a), 3 + speed / yaw_rate * (1 - std::cos(a)), 1.2);
    T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  };
  sim::Vlp16Config config;  // range noise 0.008 m
  config.T_base_lidar = Eigen::Translation3d(0.1, 0.0, 0.25) * Eigen::Isometry3d::Identity();
  const sim::Vlp16 lidar(config);
  const auto scan = lidar.scan(world, 0, truth, t0, 7, 0);
  // The legged preset's odometry at 50 Hz from the start: the only motion the de-skew knows.
  sim::NoisyOdometry model(sim::odometryPreset("legged"), 11, 0.0);
  std::vector<sim::StampedPose> odometry;
  for (int k = 0; k <= 60; ++k) odometry.push_back({k / 50.0, model.step(k / 50.0, truth(k / 50.0)).T_odom_base});
  const double reference = t0 + 0.06;  // a reading's stamp (k = 53), near the turn's middle
  // Placed in the box with the truth at the reference: odom -> map is the odometry's own error there.
  const Eigen::Isometry3d T_map_lidar = truth(reference) * config.T_base_lidar;
  const auto onWalls = [&](const std::vector<Eigen::Vector3f>& points) {
    std::vector<double> d;
    for (const auto& p : points) d.push_back(boxFaceDistance(kBox, T_map_lidar * p.cast<double>()));
    std::sort(d.begin(), d.end());
    return std::make_pair(d[d.size() / 2], d[d.size() * 99 / 100]);  // median, p99
  };
  const auto raw = onWalls(sim::deskewedTurn(scan, {}, reference, config.T_base_lidar));
  const auto fixed = onWalls(sim::deskewedTurn(scan, odometry, reference, config.T_base_lidar));
  // 3 sigma of the range noise, plus the odometry's error over 0.06 s (legged: a few mm).
  EXPECT_LT(fixed.second, 0.03) << "p99 " << fixed.second;
  EXPECT_LT(fixed.first, 0.01) << "median " << fixed.first;
  // As cast, the first and last firings are 0.05 rad and 2.5 cm off the reference pose: at
  // 5 m, a quarter of a metre off the walls.
  EXPECT_GT(raw.second, 0.15) << "p99 " << raw.second;
  EXPECT_GT(raw.second, 5 * fixed.second);
}

// The bench's de-skew with one pose per firing cycle (h28speed8, deskew.hpp): the simulator
// casts a cycle's 16 firings from the base's pose at the cycle's start, so with the true
// motion (sampled every 0.25 ms) and no range noise, the cycle's pose puts every point back on
// the walls to float precision; a pose per firing's own time moves each by the turn over up
// to 34.6 us (2 rad/s: 69 urad, 0.5 mm at 7 m).
TEST(Vlp16, DeskewPerCycleUndoesTheSimulatorsMotionExactly) {
  const sim::World world = sim::World::fromMesh(test::boxRoomFile(kBox.cast<float>()));
  const double yaw_rate = 2.0, speed = 0.5, t0 = 1.0;
  const auto truth = [&](double t) {
    Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
    const double a = yaw_rate * t;
    T.translation() = Eigen::Vector3d(3 + speed / yaw_rate * std::sin(a), 3 + speed / yaw_rate * (1 - std::cos(a)), 1.2);
    T.linear() = Eigen::AngleAxisd(a, Eigen::Vector3d::UnitZ()).toRotationMatrix();
    return T;
  };
  sim::Vlp16Config config;
  config.range_noise_sigma_m = 0.0;
  config.T_base_lidar = Eigen::Translation3d(0.1, 0.0, 0.25) * Eigen::Isometry3d::Identity();
  const sim::Vlp16 lidar(config);
  const auto scan = lidar.scan(world, 0, truth, t0, 7, 0);
  std::vector<sim::StampedPose> odometry;
  for (int k = 0; k <= 480; ++k) odometry.push_back({t0 - 0.01 + k * 0.00025, truth(t0 - 0.01 + k * 0.00025)});
  const double reference = t0 + 0.05;
  const Eigen::Isometry3d T_map_lidar = truth(reference) * config.T_base_lidar;
  const auto worst = [&](const std::vector<Eigen::Vector3f>& points) {
    double w = 0;
    for (const auto& p : points) w = std::max(w, boxFaceDistance(kBox, T_map_lidar * p.cast<double>()));
    return w;
  };
  const double per_cycle = worst(sim::deskewedTurn(scan, odometry, reference, config.T_base_lidar, sim::kVlp16CyclePeriod_s));
  const double per_firing = worst(sim::deskewedTurn(scan, odometry, reference, config.T_base_lidar));
  RecordProperty("per_cycle_worst_m", std::to_string(per_cycle));
  RecordProperty("per_firing_worst_m", std::to_string(per_firing));
  EXPECT_LT(per_cycle, 5e-5) << "per cycle " << per_cycle;
  EXPECT_GT(per_firing, 1e-4) << "per firing " << per_firing;
  EXPECT_LT(per_firing, 1e-3) << "per firing " << per_firing;  // sub-millimetre: why the cycle's pose is enough
}
