#include "sim/world/site_truth.hpp"

namespace bimloc::sim {

const WallTruth* SiteTruth::findWall(const std::string& id) const {
  for (const auto& w : walls)
    if (w.id == id) return &w;
  return nullptr;
}

nlohmann::json siteTruthJson(const SiteTruth& t) {
  nlohmann::json walls = nlohmann::json::array(), partitions = nlohmann::json::array(), doors = nlohmann::json::array(),
                 glass = nlohmann::json::array();
  for (const auto& w : t.walls)
    walls.push_back({{"id", w.id}, {"name", w.name}, {"storey", w.storey}, {"offset_m", w.offset_m},
                     {"angle_deg", w.angle_deg}, {"missing", w.missing}});
  for (const auto& p : t.partitions)
    partitions.push_back({{"storey", p.storey}, {"room", p.room}, {"start", {p.start.x(), p.start.y()}},
                          {"end", {p.end.x(), p.end.y()}}, {"thickness_m", p.thickness_m}, {"height_m", p.height_m}});
  for (const auto& d : t.doors)
    doors.push_back({{"id", d.id}, {"name", d.name}, {"storey", d.storey}, {"state", toString(d.state)}, {"wall_id", d.wall_id},
                     {"centre", {d.centre.x(), d.centre.y()}}});
  nlohmann::json clutter = nlohmann::json::array();
  for (const auto& c : t.clutter)
    clutter.push_back({{"storey", c.storey}, {"room", c.room}, {"centre", {c.centre.x(), c.centre.y(), c.centre.z()}},
                       {"yaw_deg", c.yaw_deg}, {"size_m", {c.size_m.x(), c.size_m.y(), c.size_m.z()}},
                       {"against_wall", c.against_wall}});
  nlohmann::json people = nlohmann::json::array();
  for (const auto& p : t.people) {
    nlohmann::json points = nlohmann::json::array();
    for (const auto& w : p.waypoints) points.push_back({w.x(), w.y()});
    people.push_back({{"storey", p.storey}, {"room", p.room}, {"waypoints", points}, {"speed_mps", p.speed_mps},
                      {"radius_m", p.radius_m}, {"height_m", p.height_m}, {"floor_z", p.floor_z}, {"phase_m", p.phase_m}});
  }
  const SiteSensor& e = t.sensor;
  const nlohmann::json sensor{{"glass_dropout", e.glass_dropout}, {"dark_fraction", e.dark_fraction},
                              {"dark_dropout", e.dark_dropout}, {"mixed_probability", e.mixed_probability},
                              {"mixed_jump_m", e.mixed_jump_m}, {"dark_elements", t.dark}};
  for (const auto& g : t.glass)
    glass.push_back({{"ifc_class", g.ifc_class}, {"pass_fraction", g.pass_fraction}, {"elements", g.elements}});
  return {{"preset", t.preset},   {"seed", t.seed},   {"walls", walls},         {"partitions", partitions},
          {"doors", doors},       {"glass", glass},   {"clutter", clutter}, {"people", people}, {"sensor", sensor}, {"warnings", t.warnings},
          {"convention", "a wall's point p is at c + R(angle_deg)(p - c) + offset_m n0 on the site: c the midpoint of its "
                         "axis, n0 its faces[0] normal, angle counter-clockwise about z"}};
}

}  // namespace bimloc::sim
