// The HDL-style NDT peer: its branch-and-bound against exhaustive search over the same grid,
// PCL's NDT against a known transform of the map cloud, the peer behind bimloc::Localizer on a
// simulated walk (against the ground truth), and bad input.
#include "peers/ndt/branch_and_bound.hpp"
#include "peers/ndt/map_cloud.hpp"
#include "peers/ndt/ndt_tracker.hpp"
#include "planes/plane_steps.hpp"
#include "sim/scenario/scenario.hpp"
#include "sim/simulation/simulator.hpp"
#include "sim/world/world.hpp"
#include "localizer_walk.hpp"
#include "sim_fixtures.hpp"
#include "test_support.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/localizer.hpp>

#include <gtest/gtest.h>

#include <fstream>
#include <random>

namespace {

using namespace bimloc;
using namespace bimloc::peers;

// A map slice of random wall segments (points every 5 cm) in a 20 x 15 m box outline.
Cloud2 randomWalls(std::mt19937& rng, int segments) {
  std::uniform_real_distribution<double> ux(0, 20), uy(0, 15);
  Cloud2 out;
  const auto segment = [&out](Eigen::Vector2d a, Eigen::Vector2d b) {
    const int n = static_cast<int>((b - a).norm() / 0.05) + 1;
    for (int i = 0; i <= n; ++i) out.push_back((a + (b - a) * (static_cast<double>(i) / n)).cast<float>());
  };
  segment({0, 0}, {20, 0}), segment({20, 0}, {20, 15}), segment({20, 15}, {0, 15}), segment({0, 15}, {0, 0});
  for (int s = 0; s < segments; ++s) segment({ux(rng), uy(rng)}, {ux(rng), uy(rng)});
  return out;
}

// What a robot at `pose` sees of the map within `range`: the points in its frame, with noise
// and a share of outliers.
Cloud2 scanFrom(const Cloud2& map, const Eigen::Vector3d& pose, double range, std::mt19937& rng) {
  std::normal_distribution<double> noise(0, 0.03);
  std::uniform_real_distribution<double> u(-range, range);
  std::uniform_int_distribution<int> pick(0, 9);
  const double c = std::cos(pose.z()), s = std::sin(pose.z());
  Cloud2 out;
  for (const auto& p : map) {
    const double dx = p.x() - pose.x(), dy = p.y() - pose.y();
    if (std::hypot(dx, dy) > range || pick(rng) > 2) continue;
    out.emplace_back(c * dx + s * dy + noise(rng), -s * dx + c * dy + noise(rng));
  }
  for (int i = 0; i < 20; ++i) out.emplace_back(u(rng), u(rng));  // clutter not in the map
  return out;
}

void expectSame(const GridPose& a, const GridPose& b, const std::string& what) {
  EXPECT_EQ(a.score, b.score) << what;
  EXPECT_EQ(a.yaw, b.yaw) << what;
  EXPECT_EQ(a.x, b.x) << what;
  EXPECT_EQ(a.y, b.y) << what;
}

}  // namespace

TEST(NdtGlobal, BranchAndBoundReturnsTheExhaustiveSearchsPoseAndRunnerUp) {
  std::mt19937 rng(7);
  int found_truth = 0;
  for (int trial = 0; trial < 8; ++trial) {
    const Cloud2 map = randomWalls(rng, 2 + trial % 4);
    const double resolution = trial % 2 ? 0.5 : 0.4;
    const OccupancyGrid grid = OccupancyGrid::fromPoints(map, resolution, 1.0);
    const GridPyramid pyramid(grid, 3 + trial % 4);
    SearchGrid g{&grid, &pyramid, 24 + 6 * (trial % 3)};
    // A true pose on the search's lattice, so that the search can find it.
    std::uniform_int_distribution<int> ux(4, grid.width - 5), uy(4, grid.height - 5), uyaw(0, g.yaw_count - 1);
    const GridPose truth{uyaw(rng), ux(rng), uy(rng)};
    const Cloud2 scan = scanCells(scanFrom(map, g.pose(truth), 8.0, rng), resolution);
    const std::string what = "trial " + std::to_string(trial);
    const SearchResult bnb = branchAndBound(g, scan), brute = exhaustiveSearch(g, scan);
    expectSame(bnb.best, brute.best, what);
    EXPECT_LT(bnb.nodes, brute.nodes) << what;  // it pruned
    found_truth += bnb.best.yaw == truth.yaw && std::abs(bnb.best.x - truth.x) <= 1 && std::abs(bnb.best.y - truth.y) <= 1;
    const Exclusion near{bnb.best, 1.0, 20.0 * M_PI / 180.0};
    expectSame(branchAndBound(g, scan, &near).best, exhaustiveSearch(g, scan, &near).best, what + " runner-up");
    // Pure clutter: scores tie everywhere, the tie order decides; both must agree.
    std::uniform_real_distribution<float> u(-6, 6);
    Cloud2 noise;
    for (int i = 0; i < 12; ++i) noise.emplace_back(u(rng), u(rng));
    expectSame(branchAndBound(g, scanCells(noise, resolution)).best, exhaustiveSearch(g, scanCells(noise, resolution)).best, what + " noise");
  }
  EXPECT_GE(found_truth, 6);  // and the best pose is mostly the true one (a few maps are symmetric)
}

TEST(NdtGlobal, TheMapSliceOfASampledBoxIsItsOutline) {
  // A 6 x 4 x 3 m box sampled every 0.1 m, sliced at 1-1.4 m: points on the four walls only.
  const Cloud3 map = sampleMesh(test::boxRoom({6, 4, 3}), 0.1);
  ASSERT_GT(map.size(), 2u * (6 * 4 + 6 * 3 + 4 * 3) * 100 * 0.9);  // about area / spacing^2
  const Cloud2 slice = sliceBand(map, 1.0, 1.4);
  ASSERT_FALSE(slice.empty());
  for (const auto& p : slice) {
    const double to_wall = std::min({std::abs(p.x()), std::abs(p.x() - 6), std::abs(p.y()), std::abs(p.y() - 4)});
    EXPECT_LT(to_wall, 1e-4);
  }
  // No gap along the walls wider than the spacing.
  const OccupancyGrid grid = OccupancyGrid::fromPoints(slice, 0.5, 0.0);
  EXPECT_EQ(grid.occupiedCount(), 2 * 13 + 2 * 7);  // 6.0 / 0.5 + 1 cells by 4.0 / 0.5 + 1, its rim
}

TEST(NdtTracking, RecoversAKnownTransformOfTheMapCloud) {
  const bim::Storey& storey = test::officeWorld().building().storeys.front();
  NdtConfig config;
  const Cloud3 map = sampleMesh(storey.mesh, config.map_spacing_m);
  const NdtTracker tracker(map, config);
  ASSERT_TRUE(tracker.ready());
  // A "scan": the map within 8 m of a spot in R101, on the voxel grid, seen from a lidar at a
  // known pose: p_lidar = T^-1 p_map. NDT from the identity must find T.
  const bim::Room* room = storey.findRoom("R101");
  ASSERT_NE(room, nullptr);
  const Eigen::Vector3f center(static_cast<float>(room->centre.x()), static_cast<float>(room->centre.y()), static_cast<float>(storey.elevation_m + 1.2));
  Eigen::Isometry3d T = Eigen::Isometry3d::Identity();
  T.translation() = center.cast<double>() + Eigen::Vector3d(0.3, -0.2, 0.05);
  T.linear() = Eigen::AngleAxisd(4.0 * M_PI / 180.0, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  Cloud3 near;
  for (const auto& p : map)
    if ((p - center).norm() < 8.0f) near.push_back((T.inverse() * p.cast<double>()).cast<float>());
  const Cloud3 scan = planes::detail::voxelDownsample(near, config.downsample_m);
  Eigen::Isometry3d guess = Eigen::Isometry3d::Identity();
  guess.translation() = center.cast<double>();
  const NdtAlignment a = tracker.align(scan, guess);
  const Eigen::Isometry3d error = T.inverse() * a.T_map_lidar;
  EXPECT_LT(error.translation().norm(), 0.02) << error.translation().transpose() << " after " << a.iterations << " iterations";
  EXPECT_LT(Eigen::AngleAxisd(error.linear()).angle() * 180.0 / M_PI, 0.5);
  EXPECT_TRUE(a.good) << a.fitness_m2 << " " << a.inlier_fraction;
  EXPECT_LT(a.fitness_m2, 0.01);
}

namespace {

using Step = test::WalkStep;

std::unique_ptr<test::SimulatedWalk> walk(double duration_s) { return test::officeWalk(duration_s, "ndt"); }

std::vector<Step> runNdt(const test::SimulatedWalk& w) {
  LocalizerConfig config;
  config.method = LocalizerMethod::Ndt;
  return test::walkThrough(w, config);
}

double error(const Step& s) { return test::positionError(s); }
double yawError(const Step& s) { return std::abs(wrapAngle(yawOf(s.result.T_map_base.linear()) - yawOf(s.truth.linear()))); }

}  // namespace

TEST(NdtPeer, ConvergesOnTheWalkAndTracksWithinDecimetresDeterministically) {
  const auto w = walk(40);
  const auto steps = runNdt(*w);
  std::size_t at = steps.size();
  for (std::size_t i = 0; i < steps.size(); ++i)
    if (steps[i].result.state == LocalizationState::Converged) {
      at = i;
      break;
    }
  ASSERT_LT(at, steps.size()) << "never converged";
  // Not a false convergence (the bench's rule: 0.5 m, 10 deg), and it keeps the pose.
  EXPECT_LT(error(steps[at]), 0.5);
  EXPECT_LT(yawError(steps[at]), 10.0 * M_PI / 180.0);
  int tracked = 0, close = 0;
  for (std::size_t i = at; i < steps.size(); ++i) {
    ASSERT_TRUE(steps[i].result.peer);
    EXPECT_EQ(steps[i].result.peer->method, "ndt");
    if (steps[i].result.state != LocalizationState::Tracking) continue;
    ++tracked;
    close += error(steps[i]) < 0.2 && yawError(steps[i]) < 3.0 * M_PI / 180.0;
  }
  EXPECT_GT(tracked, 0);
  EXPECT_GE(close, 0.95 * tracked) << close << " of " << tracked;
  // Same input, same bytes.
  const auto again = runNdt(*w);
  ASSERT_EQ(again.size(), steps.size());
  for (std::size_t i = 0; i < steps.size(); ++i) {
    ASSERT_EQ(again[i].result.state, steps[i].result.state) << i;
    ASSERT_TRUE(again[i].result.T_map_base.matrix() == steps[i].result.T_map_base.matrix()) << i;
  }
}

namespace {

// A one-storey plan whose mesh is `mesh` (no walls or rooms needed by the peer).
bim::Building planOf(const bim::TriangleMesh& mesh) {
  bim::Building b;
  bim::Storey s;
  s.name = "0";
  s.mesh = mesh;
  b.storeys.push_back(s);
  return b;
}

std::vector<LocalizationResult> feed(const bim::Building& plan, const std::function<std::vector<Eigen::Vector3f>(int)>& scan, int turns) {
  LocalizerConfig config;
  config.method = LocalizerMethod::Ndt;
  config.storey = "0";
  Localizer localizer(plan, test::pose(0, 0, 0, 0.0), config);
  std::vector<LocalizationResult> out;
  for (int i = 0; i < turns; ++i) out.push_back(localizer.step(0.1 * i, test::pose(1.0 + 0.05 * i, 1.0, 0.02 * i, 0.5), [&] { return scan(i); }));
  return out;
}

bool warned(const std::vector<LocalizationResult>& steps, const std::string& part) {
  for (const auto& r : steps)
    for (const auto& w : r.warnings)
      if (w.find(part) != std::string::npos) return true;
  return false;
}

// A box room's ranges from (1 + 0.05 i, 1, 0.5 + mount) in a 6 x 4 x 3 box: 16 rings of 360 points.
std::vector<Eigen::Vector3f> boxScan(int i) {
  std::vector<Eigen::Vector3f> out;
  const Eigen::Vector3d origin(1.0 + 0.05 * i, 1.0, 0.5), size(6, 4, 3);
  const double yaw = 0.02 * i;
  for (int ring = 0; ring < 16; ++ring)
    for (int k = 0; k < 360; ++k) {
      const double el = (-15.0 + 2.0 * ring) * M_PI / 180.0, az = k * M_PI / 180.0;
      const Eigen::Vector3d dir_lidar(std::cos(el) * std::cos(az), std::cos(el) * std::sin(az), std::sin(el));
      const Eigen::Vector3d dir_map = Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()) * dir_lidar;
      out.push_back((dir_lidar * test::boxRange(size, origin, dir_map)).cast<float>());
    }
  return out;
}

}  // namespace

TEST(NdtPeer, BadInputWarnsAndStaysNotLocalized) {
  // A storey whose slice holds no obstacle: only a floor.
  bim::TriangleMesh floor;
  floor.vertices = {{-5, -5, 0}, {5, -5, 0}, {5, 5, 0}, {-5, 5, 0}};
  floor.triangles = {{0, 1, 2}, {0, 2, 3}};
  auto steps = feed(planOf(floor), boxScan, 10);
  EXPECT_TRUE(warned(steps, "no obstacle in the map slice")) << steps.front().warnings.size();
  for (const auto& r : steps) {
    EXPECT_EQ(r.state, LocalizationState::Searching);
    EXPECT_FALSE(r.used_points);
  }
  // An empty scan band: every point far below the lidar.
  const auto plan = planOf(test::boxRoom({6, 4, 3}));
  steps = feed(plan, [](int) { return std::vector<Eigen::Vector3f>(500, Eigen::Vector3f(1, 1, -0.45f)); }, 10);
  EXPECT_TRUE(warned(steps, "no point in the band"));
  for (const auto& r : steps) EXPECT_EQ(r.state, LocalizationState::Searching);
  // NaN points among good ones: dropped with a warning; the pose stays finite, and once
  // converged it is the true one (the box's 180-degree twin is told apart by where the robot
  // stood in it: the scan's cells are not symmetric on the grid).
  steps = feed(plan, [](int i) {
    auto s = boxScan(i);
    for (std::size_t k = 0; k < s.size(); k += 7) s[k] = Eigen::Vector3f::Constant(std::numeric_limits<float>::quiet_NaN());
    return s;
  }, 30);
  EXPECT_TRUE(warned(steps, "non-finite"));
  for (std::size_t i = 0; i < steps.size(); ++i) {
    const auto& r = steps[i];
    EXPECT_TRUE(r.T_map_base.matrix().allFinite());
    ASSERT_TRUE(r.peer);
    if (!r.peer->converged) continue;
    EXPECT_LT((r.T_map_base.translation() - test::pose(1.0 + 0.05 * i, 1.0, 0.02 * i, 0.5).translation()).head<2>().norm(), 0.3) << i;
  }
}
