// The storey not known: StoreyBank on its own (one storey is the filter itself; storeys that
// are copies of each other are never told apart), then `storey: auto` in the loop on the
// two-storey world, where it must find the storey and the pose, and on a recorded dataset.
#include "sim_fixtures.hpp"
#include "test_support.hpp"

#include "sim/runner/run_scenario.hpp"
#include "sim/simulation/simulator.hpp"
#include "sim/world/world.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/pf/storey_bank.hpp>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <fstream>
#include <functional>

using namespace bimloc;

namespace {

const sim::World& twoStorey() {
  static const sim::World world = sim::World::fromPlan(std::string(BIMLOC_WORLDS_DIR) + "/two_storey.ifc");
  return world;
}

// A generated-style scenario: a random start in `room` of `storey`, a tour to `to`.
sim::Scenario tour(const std::string& world, const std::string& storey, const std::string& room, const std::string& to,
                   double duration_s, std::uint64_t seed) {
  sim::Scenario s;
  s.file = s.world = world;
  s.storey = storey;
  s.name = room;
  s.seed = seed;
  s.start.kind = sim::StartConfig::Kind::RandomInRoom;
  s.start.room = room;
  s.motion.kind = sim::MotionConfig::Kind::Tour;
  s.motion.rooms = {to};
  s.duration_s = duration_s;
  s.odometry = sim::odometryPreset("legged");
  return s;
}

// The scenario's scans and odometry, as the runner feeds them: odometry at mid-turn, then an
// update every turn, with the scan's wall planes only when `wants` says so after the predict.
struct Loop {
  std::function<void(const Eigen::Isometry3d&)> predict;
  std::function<bool()> wants;
  std::function<void(const std::vector<planes::ObservedPlane>&)> update;
};

void replay(const sim::Scenario& s, const sim::World& world, const Loop& loop) {
  const sim::Simulator sim(s, world);
  const auto odometry = sim.odometry();
  for (std::size_t i = 0; i < sim.turnCount(); ++i) {
    const auto scan = sim.turn(i);
    const double t = scan.stamp_s + 0.5 * sim.lidar().turnPeriod_s();
    const auto k = std::min<std::size_t>(static_cast<std::size_t>(std::llround(t * s.odometry.rate_hz)), odometry.size() - 1);
    loop.predict(odometry[k].T_odom_base);
    std::vector<Eigen::Vector3f> points;
    for (const auto& p : scan.points) points.emplace_back(p.x, p.y, p.z);
    loop.update(loop.wants() ? planes::extractPlanes(points).walls : std::vector<planes::ObservedPlane>{});
  }
}

// The site office twice: a copy 3 m up, everything in it 3 m up (the filter matches a face only
// at the heights its wall has: a copy whose walls stayed below would differ from the original,
// by its heights).
bim::Building twinOffices() {
  bim::Building twins;
  twins.storeys.push_back(test::officeWorld().building().storeys[0]);
  twins.storeys.push_back(twins.storeys[0]);
  bim::Storey& copy = twins.storeys[1];
  copy.elevation_m += 3.0;
  copy.name = "copy";
  const Eigen::Vector3d up(0, 0, 3.0);
  for (bim::Wall& w : copy.walls) {
    w.start += up, w.end += up;
    for (bim::WallFace& f : w.faces) f.start += up, f.end += up;
  }
  for (bim::Room& r : copy.rooms) r.floor_z += 3.0;
  for (Eigen::Vector3f& v : copy.mesh.vertices) v.z() += 3.0f;
  return twins;
}

}  // namespace

TEST(StoreyBank, CandidatesAreStoreysWithWallsAndRoomsAndShareTheParticlesByRoomArea) {
  const bim::Building& building = twoStorey().building();
  ASSERT_EQ(pf::StoreyBank::candidateStoreys(building), (std::vector<std::size_t>{0, 1}));
  pf::ParticleFilterConfig config;
  pf::StoreyBank bank(building, {0, 1}, sim::Vlp16Config{}.T_base_lidar, config);
  const auto report = bank.update({});
  ASSERT_EQ(report.candidates.size(), 2u);
  double area[2] = {0, 0};
  for (int s = 0; s < 2; ++s)
    for (const auto& r : building.storeys[static_cast<std::size_t>(s)].rooms) area[s] += r.area_m2;
  int total = 0;
  for (const auto& c : report.candidates) {
    total += c.particles;
    EXPECT_NEAR(c.particles, config.particles * area[c.storey] / (area[0] + area[1]), 1.0) << c.storey;
    EXPECT_FALSE(c.converged);
  }
  EXPECT_NEAR(total, config.particles, 1);
  EXPECT_FALSE(report.decided);
  EXPECT_FALSE(bank.storey());
  // A prior room leaves out the storeys that do not have it.
  config.prior_rooms = {"U02"};
  EXPECT_EQ(pf::StoreyBank(building, {0, 1}, sim::Vlp16Config{}.T_base_lidar, config).storeys(), (std::vector<std::size_t>{1}));
  config.prior_rooms = {"Nowhere"};
  EXPECT_THROW(pf::StoreyBank(building, {0, 1}, sim::Vlp16Config{}.T_base_lidar, config), std::invalid_argument);
}

TEST(StoreyBank, OneStoreyIsExactlyTheParticleFilterOfThatStorey) {
  const sim::World& world = twoStorey();
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  pf::ParticleFilterConfig config;
  config.seed = 5;
  pf::ParticleFilter filter(world.building().storeys[1], mount, config);
  pf::StoreyBank bank(world.building(), {1}, mount, config);
  bool decided_with_filter = true;
  Loop loop;
  loop.predict = [&](const Eigen::Isometry3d& odom) {
    filter.predict(odom);
    bank.predict(odom);
  };
  loop.wants = [&] { return filter.wantsObservations() && bank.wantsObservations(); };
  loop.update = [&](const std::vector<planes::ObservedPlane>& walls) {
    const auto a = filter.update(walls);
    const auto b = bank.update(walls);
    EXPECT_EQ(a.weighed, b.filter.weighed);
    EXPECT_EQ(a.path_margin, b.filter.path_margin);
    EXPECT_TRUE(filter.T_map_base().isApprox(bank.T_map_base(), 0.0));
    decided_with_filter = decided_with_filter && b.decided == filter.converged() && bank.converged() == filter.converged();
  };
  replay(tour(world.building().file, "1", "U02", "U04", 20.0, 2), world, loop);
  EXPECT_TRUE(decided_with_filter);
  EXPECT_TRUE(bank.converged());  // U02 to U04 localizes on the first floor (tested in the loop below too)
  EXPECT_EQ(bank.storey(), std::optional<std::size_t>(1));
}

TEST(StoreyBank, StoreysThatAreCopiesOfEachOtherAreNeverToldApart) {
  // The site office twice, 3 m apart: every place of one storey has its twin on the other,
  // with the same walls. The filters may converge, each on its storey; the storey must not
  // be decided, however decisive the path within a storey.
  const bim::Building twins = twinOffices();
  pf::StoreyBank bank(twins, {0, 1}, sim::Vlp16Config{}.T_base_lidar, {});
  bool any_filter_converged = false;
  Loop loop;
  loop.predict = [&](const Eigen::Isometry3d& odom) { bank.predict(odom); };
  loop.wants = [&] { return bank.wantsObservations(); };
  loop.update = [&](const std::vector<planes::ObservedPlane>& walls) {
    const auto report = bank.update(walls);
    for (const auto& c : report.candidates) any_filter_converged = any_filter_converged || c.converged;
    EXPECT_FALSE(report.decided);
    if (report.storey_margin) {
      EXPECT_LT(*report.storey_margin, pf::ParticleFilterConfig{}.evidenceMargin());
    }
  };
  replay(tour(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc", "0", "S100", "C100", 25.0, 1), test::officeWorld(), loop);
  EXPECT_TRUE(any_filter_converged);  // S100 -> C100 converges on one storey (the test is not vacuous)
  EXPECT_FALSE(bank.converged());
  EXPECT_FALSE(bank.T_map_odom());
}

TEST(StoreyBank, EvidenceFromOutsideTheWallsTellsCopiesApartByItsLogLikelihoodRatio) {
  // The twins of the test above: the walls give no margin between the storeys. An altitude's
  // log-likelihood ratio (setStoreyLogLikelihoods) adds to it in the same units: 10 for the
  // true storey passes the bar (8.34), 5 does not; the storey it decides is the one it favours.
  const bim::Building twins = twinOffices();
  const Eigen::Isometry3d mount = sim::Vlp16Config{}.T_base_lidar;
  pf::StoreyBank strong(twins, {0, 1}, mount, {}), weak(twins, {0, 1}, mount, {});
  strong.setStoreyLogLikelihoods({0.0, -10.0});
  weak.setStoreyLogLikelihoods({0.0, -5.0});
  std::optional<double> strong_margin;
  Loop loop;
  loop.predict = [&](const Eigen::Isometry3d& odom) { strong.predict(odom), weak.predict(odom); };
  loop.wants = [&] { return strong.wantsObservations() || weak.wantsObservations(); };
  loop.update = [&](const std::vector<planes::ObservedPlane>& walls) {
    const auto a = strong.update(walls);
    if (a.decided && !strong_margin) strong_margin = a.storey_margin;
    const auto b = weak.update(walls);
    EXPECT_FALSE(b.decided) << "a ratio of 5 is under the bar";
  };
  replay(tour(std::string(BIMLOC_WORLDS_DIR) + "/site_office.ifc", "0", "S100", "C100", 25.0, 1), test::officeWorld(), loop);
  ASSERT_TRUE(strong.converged());
  EXPECT_EQ(strong.storey(), std::optional<std::size_t>(0));
  ASSERT_TRUE(strong_margin);
  // The walls' margin between twins is about 0: the ratio carries the decision.
  EXPECT_GE(*strong_margin, pf::ParticleFilterConfig{}.evidenceMargin());
  EXPECT_LE(*strong_margin, 10.0 + 1e-9);
  EXPECT_FALSE(weak.converged());
}

TEST(StoreyBank, StoreyAutoOnTheTwoStoreyWorldFindsTheStoreyAndThePose) {
  // The runner with `storey: auto`: the simulator runs on the true storey, the localizer
  // considers both. A wrong storey would be a false convergence.
  const sim::World& world = twoStorey();
  for (const auto& [storey, room, to] : {std::tuple{"First floor", "U02", "U04"}, std::tuple{"Ground floor", "G03", "G01"}}) {
    sim::Scenario s = tour(world.building().file, "auto", room, to, 25.0, 1);
    s.localizer = {{"storey", "auto"}};
    sim::checkScenarioAgainstWorld(s, world);
    const sim::ScenarioResult r = sim::runScenario(s, world);
    EXPECT_TRUE(r.storey_auto);
    EXPECT_EQ(r.storey, storey);
    ASSERT_TRUE(r.converged) << room;
    EXPECT_EQ(r.found_storey, std::optional<std::string>(storey)) << room;
    EXPECT_FALSE(r.false_convergence) << room;
    EXPECT_LT(r.position_error_m, 0.3) << room;
    EXPECT_LT(r.yaw_error_deg, 3.0) << room;
    ASSERT_TRUE(r.storey_margin) << room;
    EXPECT_GE(*r.storey_margin, pf::ParticleFilterConfig{}.evidenceMargin()) << room;
  }
}

TEST(StoreyBank, LocalizeWithStoreyAutoOnARecordedDatasetReportsTheStoreyFound) {
  // `bimloc simulate` records the true storey (the start room's, with storey: auto); `bimloc
  // localize --storey auto` is not told it and is scored against it.
  const std::string dir = test::tempDir("storey-auto");
  const std::string scenario = dir + "/upstairs.yaml";
  std::ofstream(scenario) << "world: " << BIMLOC_WORLDS_DIR << "/two_storey.ifc\nstorey: auto\n"
                          << "start: {random_in_room: U02}\nmotion: {type: tour, rooms: [U04]}\nduration_s: 25\nseed: 1\n";
  const auto simulated = test::runBimloc("simulate '" + scenario + "' --out '" + dir + "/data'");
  ASSERT_EQ(simulated.exit_code, 0) << simulated.err;
  const auto r = test::runBimloc("localize '" + dir + "/data' --plan '" + BIMLOC_WORLDS_DIR + "/two_storey.ifc' --storey auto --json");
  const auto j = nlohmann::json::parse(r.out)["scenarios"][0];
  EXPECT_EQ(j["storey"], "First floor");
  EXPECT_TRUE(j["storey_auto"]);
  EXPECT_TRUE(j["converged"]) << r.out;
  EXPECT_EQ(j["found_storey"], "First floor") << r.out;
  EXPECT_FALSE(j["false_convergence"]);
}
