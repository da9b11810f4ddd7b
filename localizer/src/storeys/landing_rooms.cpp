#include "landing_rooms.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::storeys {
namespace {

// The distance from p to a room's footprint (0 inside).
double distanceToRoom(const bim::Room& room, const Eigen::Vector2d& p) {
  if (room.footprint.size() < 3) return std::numeric_limits<double>::infinity();
  if (bim::pointInPolygon(room.footprint, p)) return 0.0;
  double best = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < room.footprint.size(); ++i)
    best = std::min(best, bim::distanceToSegment(p, room.footprint[i], room.footprint[(i + 1) % room.footprint.size()]));
  return best;
}

}  // namespace

std::vector<std::string> landingRooms(const bim::Building& building, const std::vector<std::size_t>& storeys, bool up, double reach_m) {
  std::vector<std::string> names;
  bool any = false;
  for (const bim::StairFlight& f : building.stairs) {
    const int arrives = up ? f.top_storey : f.bottom_storey;
    if (arrives < 0 || std::find(storeys.begin(), storeys.end(), static_cast<std::size_t>(arrives)) == storeys.end()) continue;
    any = true;
    const Eigen::Vector2d end = (up ? f.top : f.bottom).head<2>();
    bool covered = false;
    for (const bim::Room& room : building.storeys.at(static_cast<std::size_t>(arrives)).rooms) {
      const std::string& key = room.id.empty() ? room.name : room.id;  // the id first: names repeat
      if (key.empty() || distanceToRoom(room, end) > reach_m) continue;
      covered = true;
      if (std::find(names.begin(), names.end(), key) == names.end()) names.push_back(key);
    }
    if (!covered) return {};
  }
  return any ? names : std::vector<std::string>{};
}

}  // namespace bimloc::storeys
