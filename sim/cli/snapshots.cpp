#include "sim/cli/snapshots.hpp"

#include "sim/render/error_plot.hpp"
#include "sim/render/snapshot.hpp"

#include <bimloc/geometry/planar_pose.hpp>
#include <bimloc/sgraph/sgraph_tracker.hpp>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <mutex>

namespace bimloc::cli {
std::string fileSafe(const std::string& name) {
  std::string out;
  for (const char c : name) out += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  return out;
}

namespace {

// A plan wall where the graph estimates it: its axis moved along faces[0]'s normal by the
// offset and turned about its centre by the angle (the wall node's parameters).
sim::SnapshotGraph::Segment estimatedWall(const bim::Wall& wall, const sgraph::WallDeviation* deviation) {
  const Eigen::Vector2d a = wall.start.head<2>(), b = wall.end.head<2>();
  if (!deviation) return {a, b, wall.thickness_m};
  const Eigen::Vector2d e = wall.faces[0].plane.n.head<2>().normalized();
  const double angle = deviation->angle_deg * M_PI / 180.0;
  const Eigen::Rotation2Dd turn(std::isfinite(angle) ? angle : 0.0);
  const double offset = std::isfinite(deviation->offset_m) ? deviation->offset_m : 0.0;
  const Eigen::Vector2d c = 0.5 * (a + b) + offset * (e.allFinite() ? e : Eigen::Vector2d::Zero());
  const Eigen::Vector2d half = turn * (0.5 * (b - a));
  return {c - half, c + half, std::max(0.0, wall.thickness_m + deviation->thickness_change_m)};
}

// Where a room's edge meets a wall: the wall point nearest the room node. A wall's midpoint
// may lie rooms away (a corridor wall runs along several offices).
Eigen::Vector2d nearestOn(const sim::SnapshotGraph::Segment& s, const Eigen::Vector2d& p) {
  const Eigen::Vector2d ab = s.end - s.start;
  const double t = std::clamp(ab.dot(p - s.start) / std::max(ab.squaredNorm(), 1e-12), 0.0, 1.0);
  return s.start + t * ab;
}

}  // namespace

sim::SnapshotGraph snapshotGraph(const sgraph::SGraphTracker& tracker, const bim::Storey& storey) {
  sim::SnapshotGraph g;
  for (const auto& k : tracker.keyframes()) g.keyframes.push_back(planarPose(k.T_map_base));
  std::map<int, sgraph::WallDeviation> deviations;
  for (const auto& d : tracker.wallDeviations())
    if (d.wall >= 0 && static_cast<std::size_t>(d.wall) < storey.walls.size()) deviations[d.wall] = d;
  for (const auto& [index, d] : deviations) g.matched_walls.push_back(estimatedWall(storey.walls[index], &d));
  for (const auto& p : tracker.newPlanes()) g.new_planes.push_back({p.start, p.end, 0.0});
  for (const auto& room : tracker.rooms()) {
    sim::SnapshotGraph::Room r{room.centre, {}};
    for (const int w : room.walls) {
      if (w < 0 || static_cast<std::size_t>(w) >= storey.walls.size()) continue;  // a new plane's node
      const auto it = deviations.find(w);
      const auto wall = estimatedWall(storey.walls[w], it == deviations.end() ? nullptr : &it->second);
      r.wall_points.push_back(nearestOn(wall, room.centre));
    }
    g.rooms.push_back(std::move(r));
  }
  return g;
}

sim::SnapshotHook snapshotWriter(const sim::World& world, const sim::Scenario& scenario, const std::string& out_dir,
                                 const std::string& title) {
  const std::string dir = (std::filesystem::path(out_dir) / fileSafe(scenario.name)).string();
  const bim::Building* building = &world.building();
  int index = 0;
  return [dir, building, name = title.empty() ? scenario.name : title, index](const sim::SnapshotMoment& m) mutable {
    std::filesystem::create_directories(dir);
    sim::SnapshotScene scene;
    // The filter's storey: with storey auto, the leading one (the truth may be on another).
    scene.storey = &building->storeys.at(m.storey);
    scene.truth = planarPose(m.truth);
    scene.title = name;
    scene.time_s = m.time_s;
    scene.phase = m.phase;
    if (m.filter) {
      double max_lw = -1e300;
      for (const auto& p : m.filter->particles()) max_lw = std::max(max_lw, p.log_weight);
      for (const auto& p : m.filter->particles()) scene.particles.push_back({p.x, p.y, p.yaw, std::exp(p.log_weight - max_lw)});
      scene.estimate = planarPose(m.estimate ? *m.estimate : m.filter->T_map_base());
      scene.legend_extra = {{"particles", std::to_string(m.filter->particles().size())},
                            {"converged", m.filter->converged() ? "yes" : "no"}};
    } else if (m.estimate) {  // a peer (AMCL, NDT): its estimate only
      scene.estimate = planarPose(*m.estimate);
    }
    scene.legend_extra.push_back({"storey", scene.storey->name});
    if (m.tracker) {
      scene.graph = snapshotGraph(*m.tracker, *scene.storey);
      scene.legend_extra.push_back({"tracker", sgraph::toString(m.tracker->state())});
    }
    char file[64];
    std::snprintf(file, sizeof file, "%d_%s.png", index++, m.phase.c_str());
    sim::renderSnapshot(scene, dir + "/" + file);
  };
}

void writeErrorPlot(const std::string& out_dir, const std::string& scenario_name, const sim::ScenarioResult& result,
                    const std::string& title) {
  if (result.error_series.empty()) return;  // the run never stepped: nothing to plot
  sim::ErrorPlotData data;
  data.title = (title.empty() ? scenario_name : title) + ": localization error";
  data.convergence_time_s = result.convergence_time_s;
  for (const auto& e : result.error_series) {
    using S = LocalizationState;
    const auto state = e.state == S::Searching ? sim::ErrorPlotState::Searching
                       : e.state == S::Lost    ? sim::ErrorPlotState::Lost
                                               : sim::ErrorPlotState::Tracking;
    data.samples.push_back({e.time_s, e.position_m, e.yaw_deg, state});
    if (&e != &result.error_series.front() && e.true_storey != (&e - 1)->true_storey) data.storey_change_times_s.push_back(e.time_s);
  }
  const std::string dir = (std::filesystem::path(out_dir) / fileSafe(scenario_name)).string();
  std::filesystem::create_directories(dir);
  sim::renderErrorPlot(data, dir + "/errors.png");
}

}  // namespace bimloc::cli
