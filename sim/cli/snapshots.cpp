#include "sim/cli/snapshots.hpp"

#include "sim/render/snapshot.hpp"

#include <bimloc/geometry/planar_pose.hpp>

#include <cmath>
#include <filesystem>
#include <mutex>

namespace bimloc::cli {
std::string fileSafe(const std::string& name) {
  std::string out;
  for (const char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  return out;
}

sim::SnapshotHook snapshotWriter(const sim::World& world, const sim::Scenario& scenario, const std::string& out_dir) {
  const std::string dir = (std::filesystem::path(out_dir) / fileSafe(scenario.name)).string();
  const bim::Building* building = &world.building();
  int index = 0;
  return [dir, building, name = scenario.name, index](const sim::SnapshotMoment& m) mutable {
    std::filesystem::create_directories(dir);
    sim::SnapshotScene scene;
    // The filter's storey: with storey auto, the leading one (the truth may be on another).
    scene.storey = &building->storeys.at(m.storey);
    double max_lw = -1e300;
    for (const auto& p : m.filter->particles()) max_lw = std::max(max_lw, p.log_weight);
    for (const auto& p : m.filter->particles()) scene.particles.push_back({p.x, p.y, p.yaw, std::exp(p.log_weight - max_lw)});
    scene.truth = planarPose(m.truth);
    scene.estimate = planarPose(m.filter->T_map_base());
    scene.title = name;
    scene.time_s = m.time_s;
    scene.phase = m.phase;
    scene.legend_extra = {{"particles", std::to_string(m.filter->particles().size())},
                          {"converged", m.filter->converged() ? "yes" : "no"},
                          {"storey", scene.storey->name}};
    char file[64];
    std::snprintf(file, sizeof file, "%d_%s.png", index++, m.phase.c_str());
    sim::renderSnapshot(scene, dir + "/" + file);
  };
}

}  // namespace bimloc::cli
