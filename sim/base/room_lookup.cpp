#include "sim/base/room_lookup.hpp"

#include <bimloc/bim/geometry2d.hpp>

namespace bimloc::sim {

const bim::Room* lookUpRoom(const bim::Storey& storey, const std::string& name_or_id, std::string* problem) {
  for (const auto& r : storey.rooms)
    if (r.name == name_or_id || r.id == name_or_id) return &r;
  // A long name is a use ("Office"): fine when one room has it, a guess when several do.
  std::vector<const bim::Room*> uses;
  for (const auto& r : storey.rooms)
    if (r.long_name == name_or_id) uses.push_back(&r);
  if (uses.size() == 1) return uses.front();
  if (problem) {
    if (uses.empty()) {
      *problem = "unknown room '" + name_or_id + "' on storey '" + storey.name + "'; its rooms: " + roomList(storey);
    } else {
      std::string names;
      for (const auto* r : uses) names += (names.empty() ? "" : ", ") + r->name;
      *problem = "room '" + name_or_id + "' is ambiguous on storey '" + storey.name + "': " + std::to_string(uses.size()) +
                 " rooms have that long name (" + names + "); give the room's name";
    }
  }
  return nullptr;
}

std::string roomList(const bim::Storey& storey) {
  std::string out;
  for (const auto& r : storey.rooms)
    out += (out.empty() ? "" : ", ") + (r.name.empty() ? r.id : r.name) + (r.long_name.empty() ? "" : " (" + r.long_name + ")");
  return out.empty() ? "none" : out;
}

const bim::Room* roomAt(const bim::Storey& storey, const Eigen::Vector2d& p) {
  for (const auto& r : storey.rooms)
    if (bim::pointInPolygon(r.footprint, p)) return &r;
  return nullptr;
}

}  // namespace bimloc::sim
