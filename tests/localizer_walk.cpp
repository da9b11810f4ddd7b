#include "localizer_walk.hpp"

#include "sim/world/world.hpp"
#include "sim_fixtures.hpp"
#include "test_support.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>

namespace bimloc::test {

std::unique_ptr<OfficeWalk> officeWalk(double duration_s, const std::string& tag) {
  const std::string path = tempDir(tag) + "/walk.yaml";
  std::ofstream(path) << "world: " << BIMLOC_WORLDS_DIR << "/site_office.ifc\n"
                      << "start: {random_in_room: S100}\nmotion: {type: tour, rooms: [C100, R108, C100, R101, C100, R105]}\n"
                      << "odometry: {preset: legged}\nduration_s: " << duration_s << "\nseed: 1\n";
  auto w = std::make_unique<OfficeWalk>();
  w->scenario = sim::loadScenario(path);
  w->sim = std::make_unique<sim::Simulator>(w->scenario, officeWorld());
  w->odometry = w->sim->odometry();
  return w;
}

std::vector<WalkStep> walkThrough(const OfficeWalk& w, LocalizerConfig config, const std::function<bool(double)>& blind) {
  config.storey = "0";
  Localizer localizer(officeWorld().building(), w.scenario.sensor.T_base_lidar, config);
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
