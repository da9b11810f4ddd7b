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
  for (const auto& g : t.glass)
    glass.push_back({{"ifc_class", g.ifc_class}, {"pass_fraction", g.pass_fraction}, {"elements", g.elements}});
  return {{"preset", t.preset},   {"seed", t.seed},   {"walls", walls},         {"partitions", partitions},
          {"doors", doors},       {"glass", glass},   {"clutter", clutter}, {"warnings", t.warnings},
          {"convention", "a wall's point p is at c + R(angle_deg)(p - c) + offset_m n0 on the site: c the midpoint of its "
                         "axis, n0 its faces[0] normal, angle counter-clockwise about z"}};
}

}  // namespace bimloc::sim
