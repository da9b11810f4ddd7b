// A wall's seen end (ParticleFilterConfig::match_wall_ends): where a scan's planes all run one way,
// no pair of them fixes a position along the walls, and only where the walls end does. The IFC
// 4.3 sample house (its walls all along y, its gables no walls) localized 0 of 6 starts for it.
// Truth is analytic: a house open at both ends built in code (walls only along y, as worldgen's
// open_house), the planes a lidar sees from a known pose from the walls' geometry
// (test::syntheticWalls), and an exhaustive grid of poses.
#include "face_index_fixtures.hpp"
#include "sgraph_fixtures.hpp"
#include "sim_fixtures.hpp"

#include "pf/hypotheses.hpp"
#include "pf/path_evidence.hpp"
#include "pf/room_index.hpp"
#include "sim/runner/room_scenarios.hpp"
#include "sim/runner/run_scenario.hpp"
#include "sim/world/world.hpp"

#include <bimloc/pf/particle_filter.hpp>

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

using namespace bimloc;
using pf::detail::Observation;
using pf::detail::Pose2;

namespace {

constexpr double kZ = 0.0;

// The open house: a west wall (inside face x = 0, y 0-7), an east wall in two steps (inside
// faces x = 4.0 for y 0-2.5, x = 5.4 for y 2.5-7) and a thin partition (faces x = 4.875 and
// 4.925, y 3.0-6.4). Nothing along x: the front (y = 0) and the back (y = 7) are open.
bim::Storey openHouse() {
  bim::Storey s;
  s.name = "open house";
  s.walls.push_back(test::boxWall("W", {-0.1, 0.0}, {-0.1, 7.0}, 0.2));
  s.walls.push_back(test::boxWall("EF", {4.1, 0.0}, {4.1, 2.5}, 0.2));
  s.walls.push_back(test::boxWall("EB", {5.5, 2.5}, {5.5, 7.0}, 0.2));
  s.walls.push_back(test::boxWall("P", {4.9, 3.0}, {4.9, 6.4}, 0.05));
  s.rooms.push_back(test::boxRoom("H01", 0.0, 0.0, 4.0, 2.5, {{"W", -1}, {"EF", -1}}));
  s.rooms.push_back(test::boxRoom("H02", 0.0, 2.5, 4.875, 7.0, {{"W", -1}}));
  return s;
}

const Eigen::Isometry3d kMount(Eigen::Translation3d(0.0, 0.0, 0.5));

// The scan from `truth` (noise-free but for the synthetic lidar's 1 cm), as the filter observes
// it: with each plane's standing span (the visible run of its face), flagged as the filter flags a
// scan whose planes all run one way.
std::vector<Observation> scanFrom(const bim::Storey& storey, const Pose2& truth) {
  Eigen::Isometry3d T_map_base = Eigen::Isometry3d::Identity();
  T_map_base.translate(Eigen::Vector3d(truth.x(), truth.y(), 0.0)).rotate(Eigen::AngleAxisd(truth.z(), Eigen::Vector3d::UnitZ()));
  std::mt19937_64 rng(34);
  test::SyntheticLidar lidar;
  lidar.spans = true;
  const auto walls = test::syntheticWalls(storey, {}, T_map_base * kMount, lidar, rng);
  auto observations = test::observations(walls, kMount);
  for (std::size_t k = 0; k < walls.size(); ++k) {
    const Eigen::Vector3d middle = kMount * walls[k].wall_span_middle;
    observations[k].wall_span_m = walls[k].wall_span_m, observations[k].span_middle_base = middle.head<2>();
    observations[k].end_scored = !pf::detail::positionFixedByPlanes(observations);
  }
  return observations;
}

// Observation `o` with its span running from `from` to `to` along its face (map y, the base at
// `pose`): what the extraction would give for a wall seen over that stretch.
Observation withSpan(Observation o, const Pose2& pose, double x, double from, double to) {
  const Eigen::Vector2d middle_map(x, 0.5 * (from + to));
  o.span_middle_base = Eigen::Rotation2Dd(-pose.z()) * (middle_map - pose.head<2>());
  o.wall_span_m = to - from;
  return o;
}

pf::detail::ObservationMatch matchAt(const Pose2& pose, const Observation& o, const pf::detail::RoomIndex& faces,
                                     const pf::ParticleFilterConfig& c) {
  pf::Particle p;
  p.x = pose.x(), p.y = pose.y(), p.yaw = pose.z(), p.room = faces.roomAt(p.x, p.y);
  std::vector<pf::detail::ObservationMatch> per;
  pf::detail::matchObservations(p, kZ, {o}, faces, c, &per, false);
  return per.at(0);
}

}  // namespace

TEST(WallEnds, PlanesThirtyToOneHundredFiftyDegreesApartFixAPositionParallelOnesDoNot) {
  const auto at = [](std::initializer_list<double> azimuths_deg) {
    std::vector<Observation> obs;
    for (double a : azimuths_deg) {
      Observation o;
      o.azimuth_base = a * M_PI / 180.0;
      o.normal_base = Eigen::Vector3d(std::cos(o.azimuth_base), std::sin(o.azimuth_base), 0.0);
      obs.push_back(o);
    }
    return pf::detail::positionFixedByPlanes(obs);
  };
  EXPECT_FALSE(at({}));
  EXPECT_FALSE(at({10.0}));
  EXPECT_FALSE(at({0.0, 180.0, 0.0, -180.0}));  // two walls of a corridor, both sides
  EXPECT_FALSE(at({0.0, 20.0, 175.0}));
  EXPECT_TRUE(at({0.0, 20.0, 165.0}));  // 20 and 165: 145 degrees apart
  EXPECT_TRUE(at({0.0, 35.0}));
  EXPECT_TRUE(at({0.0, 90.0}));
  EXPECT_TRUE(at({170.0, -100.0}));  // 90 degrees across the wrap
}

TEST(WallEnds, ARunPastTheLineEndCostsItsSquareInSigmaDWhereThePlanesRunOneWay) {
  // The west wall's inside face (x = 0, y 0-7) seen from (2, 4), its span from y = 1 to 7 + over.
  const bim::Storey s = openHouse();
  const pf::detail::RoomIndex faces(s, /*use_rooms=*/false);
  pf::ParticleFilterConfig c;
  c.use_rooms = false;
  const Pose2 pose(2.0, 4.0, 0.3);
  const Observation plane = test::planeSeenFrom(pose, {1.0, 0.0}, 0.0, {0.0, 4.0});
  for (const double over : {0.0, 0.1, 0.2, 0.4}) {
    Observation o = withSpan(plane, pose, 0.0, 1.0, 7.0 + over);
    o.end_scored = true;
    const auto scored = matchAt(pose, o, faces, c);
    EXPECT_EQ(scored.face, 1) << over;
    EXPECT_NEAR(scored.m2, std::pow(over / c.sigma_d_m, 2), 1e-4) << over;
    // Where the scan's planes fix the position (end_scored false), or with the rule off, the run is
    // free within the wall-line margin.
    o.end_scored = false;
    EXPECT_NEAR(matchAt(pose, o, faces, c).m2, 0.0, 1e-4) << over;
    o.end_scored = true;
    pf::ParticleFilterConfig off = c;
    off.match_wall_ends = false;
    EXPECT_NEAR(matchAt(pose, o, faces, off).m2, 0.0, 1e-4) << over;
  }
  // Past the margin (0.5 m), not the face at all: the wall-line rule, as before.
  Observation far = withSpan(plane, pose, 0.0, 1.0, 7.6);
  far.end_scored = true;
  EXPECT_EQ(matchAt(pose, far, faces, c).face, -1);
  // Short of the end, no cost: something may hide the rest of the wall.
  Observation short_run = withSpan(plane, pose, 0.0, 1.5, 5.0);
  short_run.end_scored = true;
  EXPECT_NEAR(matchAt(pose, short_run, faces, c).m2, 0.0, 1e-4);
}

TEST(WallEnds, EveryFitOfAScanOfParallelWallsIsProposedFromItsEnds) {
  // Brute force (as test_proposals): every pose of a 0.05 m grid over the house, at the two
  // headings the walls allow (the truth's and turned about), scored as the search scores a fit.
  // Every peak of the grid within the evidence bar of its best must be within the same-place
  // radius of a candidate the search proposed; and the search must vouch (its fits include the
  // truth).
  const bim::Storey storey = openHouse();
  const pf::ParticleFilterConfig config;
  for (const Pose2& truth : {Pose2(2.0, 4.0, 0.3), Pose2(1.2, 1.1, -2.0), Pose2(3.1, 5.6, 1.4)}) {
    const auto observations = scanFrom(storey, truth);
    ASSERT_GE(observations.size(), 2u);
    ASSERT_FALSE(pf::detail::positionFixedByPlanes(observations)) << "the house's planes all run along y";
    pf::detail::PathEvidence evidence(storey, config);
    const Pose2 odom = Pose2::Zero();
    evidence.addScan(odom, kZ, observations);
    ASSERT_TRUE(evidence.proposeEveryFit(observations, kZ, odom, truth)) << "the search's fits must include the true place";
    const std::vector<Pose2> candidates = evidence.candidatePoses(odom);
    const pf::detail::RoomIndex& faces = evidence.everyFace();
    const pf::ParticleFilterConfig& model = evidence.scanModel();
    const auto score = [&](const Pose2& p) {
      pf::Particle particle;
      particle.x = p.x(), particle.y = p.y(), particle.yaw = p.z(), particle.room = faces.roomAt(p.x(), p.y());
      return pf::detail::matchObservations(particle, kZ, observations, faces, model, nullptr, false).log_likelihood;
    };
    // The grid, per heading: 117 x 141 poses 0.05 m apart.
    constexpr int nx = 117, ny = 141;
    std::vector<Pose2> poses;
    std::vector<double> scores;
    double best = -1e300;
    for (const double yaw : {truth.z(), pf::detail::wrapAngle(truth.z() + M_PI)})
      for (int ix = 0; ix < nx; ++ix)
        for (int iy = 0; iy < ny; ++iy) {
          poses.emplace_back(-0.2 + 0.05 * ix, 0.05 * iy, yaw);
          scores.push_back(score(poses.back()));
          best = std::max(best, scores.back());
        }
    EXPECT_GE(best, score(truth) - 1.0) << "the grid holds a pose as good as the truth, about";
    // The places: the grid's peaks (no neighbour of the same heading scores higher), as in
    // test_proposals; the poses around a peak are the slopes of its basin, not places.
    int near_best = 0;
    for (int h = 0; h < 2; ++h)
      for (int ix = 0; ix < nx; ++ix)
        for (int iy = 0; iy < ny; ++iy) {
          const std::size_t k = static_cast<std::size_t>((h * nx + ix) * ny + iy);
          if (scores[k] < best - config.evidenceMargin()) continue;
          bool peak = true;
          for (int dx = -1; dx <= 1 && peak; ++dx)
            for (int dy = -1; dy <= 1 && peak; ++dy) {
              const int jx = ix + dx, jy = iy + dy;
              if ((dx || dy) && jx >= 0 && jx < nx && jy >= 0 && jy < ny)
                peak = scores[static_cast<std::size_t>((h * nx + jx) * ny + jy)] <= scores[k];
            }
          if (!peak) continue;
          ++near_best;
          const Pose2& p = poses[k];
          const bool covered = std::any_of(candidates.begin(), candidates.end(), [&](const Pose2& c) {
            return pf::detail::near(p, c, pf::detail::kSamePlaceM, pf::detail::kSamePlaceRad);
          });
          EXPECT_TRUE(covered) << "grid peak " << p.transpose() << " scores " << scores[k] << " (best " << best << "), truth "
                               << truth.transpose();
        }
    EXPECT_GT(near_best, 0);
  }
}

TEST(WallEnds, EndsSeenOnBothSidesFixThePoseAlongTheWalls) {
  const bim::Storey storey = openHouse();
  const Pose2 truth(2.0, 4.0, 0.3), odom = Pose2::Zero();
  const auto verdictOf = [&](const std::vector<Observation>& observations, const pf::ParticleFilterConfig& config) {
    pf::detail::PathEvidence evidence(storey, config);
    evidence.addScan(odom, kZ, observations);
    evidence.propose(truth, odom);
    return evidence.verdict(odom);
  };
  // The west wall's inside face seen whole (both its ends), and the partition's: fixed.
  const Observation west = test::planeSeenFrom(truth, {1.0, 0.0}, 0.0, {0.0, 4.0});
  const Observation partition = test::planeSeenFrom(truth, {-1.0, 0.0}, 4.875, {4.875, 4.5});
  std::vector<Observation> whole = {withSpan(west, truth, 0.0, 0.0, 7.0), withSpan(partition, truth, 4.875, 3.0, 6.4)};
  for (auto& o : whole) o.end_scored = true;
  const pf::ParticleFilterConfig config;
  const auto fixed = verdictOf(whole, config);
  ASSERT_TRUE(fixed.has_best);
  EXPECT_LT((fixed.best.head<2>() - truth.head<2>()).norm(), 0.05);
  EXPECT_TRUE(fixed.pose_fixed);
  // Seen short of their ends towards +y (something hid the rest): one side pinned only.
  std::vector<Observation> one_side = {withSpan(west, truth, 0.0, 0.0, 5.5), withSpan(partition, truth, 4.875, 3.0, 5.0)};
  for (auto& o : one_side) o.end_scored = true;
  EXPECT_FALSE(verdictOf(one_side, config).pose_fixed);
  // With the rule off, planes all one way fix nothing (the verdict before session 34).
  pf::ParticleFilterConfig off = config;
  off.match_wall_ends = false;
  EXPECT_FALSE(verdictOf(whole, off).pose_fixed);
}

TEST(WallEnds, TheOpenHouseLocalizesFromItsWallEndsAndNotWithout) {
  // The generated open_house (worlds/): every start, two seeds, in the loop (Embree VLP-16, the
  // legged base's noisy odometry). Each must localize, none falsely; without the rule none can.
  const sim::World world = sim::World::fromPlan(std::string(BIMLOC_WORLDS_DIR) + "/open_house.ifc");
  sim::RoomScenarioOptions options;
  options.plan = std::string(BIMLOC_WORLDS_DIR) + "/open_house.ifc";
  options.duration_s = 15.0;
  options.seeds = 2;
  const auto scenarios = sim::roomScenarios(world, options);
  ASSERT_EQ(scenarios.size(), 4u);
  for (bool ends : {true, false}) {
    for (auto scenario : scenarios) {
      scenario.localizer["pf"]["match_wall_ends"] = ends;
      const sim::ScenarioResult r = sim::runScenario(scenario, world);
      EXPECT_FALSE(r.false_convergence) << scenario.name;
      if (ends) {
        EXPECT_TRUE(r.converged) << scenario.name;
        EXPECT_LT(r.convergence_time_s.value_or(1e9), 5.0) << scenario.name;
      } else {
        EXPECT_FALSE(r.converged) << scenario.name << " localized with planes that all run one way";
      }
    }
  }
}
