#include "localizer_walk.hpp"

#include "sim/world/world.hpp"
#include "sim_fixtures.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

namespace bimloc::test {

namespace {

std::unique_ptr<SimulatedWalk> walkIn(const sim::World& world, const std::string& file, const std::string& room, const std::string& tour,
                                   double duration_s, const std::string& tag) {
  const std::string path = tempDir(tag) + "/walk.yaml";
  std::ofstream(path) << "world: " << BIMLOC_WORLDS_DIR << "/" << file << "\n"
                      << "start: {random_in_room: " << room << "}\nmotion: {type: tour, rooms: [" << tour << "]}\n"
                      << "odometry: {preset: legged}\nduration_s: " << duration_s << "\nseed: 1\n";
  auto w = std::make_unique<SimulatedWalk>();
  w->world = &world;
  w->scenario = sim::loadScenario(path);
  w->sim = std::make_unique<sim::Simulator>(w->scenario, world);
  w->odometry = w->sim->odometry();
  return w;
}

}  // namespace

std::unique_ptr<SimulatedWalk> officeWalk(double duration_s, const std::string& tag) {
  return walkIn(officeWorld(), "site_office.ifc", "S100", "C100, R108, C100, R101, C100, R105", duration_s, tag);
}

std::unique_ptr<SimulatedWalk> apartmentWalk(const std::string& room, const std::string& tour, double duration_s, const std::string& tag) {
  static const sim::World world = sim::World::fromPlan(std::string(BIMLOC_WORLDS_DIR) + "/apartment.ifc");
  return walkIn(world, "apartment.ifc", room, tour, duration_s, tag);
}

std::vector<WalkStep> walkThrough(const SimulatedWalk& w, LocalizerConfig config, const std::function<bool(double)>& blind) {
  config.storey = "0";
  Localizer localizer(w.world->building(), w.scenario.sensor.T_base_lidar, config);
  std::vector<WalkStep> steps;
  const double half = 0.5 * w.sim->lidar().turnPeriod_s();
  for (std::size_t i = 0; i < w.sim->turnCount(); ++i) {
    const double t = w.sim->turnStamp(i) + half;
    const auto k = std::min(static_cast<std::size_t>(std::llround(t * w.scenario.odometry.rate_hz)), w.odometry.size() - 1);
    const bool withheld = blind && blind(t);
    const auto points = [&] {
      std::vector<Eigen::Vector3f> out;
      if (withheld) return out;
      for (const auto& p : w.sim->turn(i).points) out.emplace_back(p.x, p.y, p.z);
      return out;
    };
    const Eigen::Isometry3d& odom = w.odometry[k].T_odom_base;
    steps.push_back({localizer.step(t, odom, Localizer::PointSource(points)), w.sim->trajectory().T_map_base(t), odom});
  }
  return steps;
}

double positionError(const WalkStep& s) { return (s.result.T_map_base.translation() - s.truth.translation()).head<2>().norm(); }

}  // namespace bimloc::test
