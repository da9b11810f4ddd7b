#include "sim/runner/room_scenarios.hpp"

#include <algorithm>
#include <map>

namespace bimloc::sim {

std::vector<Scenario> roomScenarios(const World& world, const RoomScenarioOptions& o) {
  const std::size_t storey = world.storeyIndex(o.storey);
  const auto& rooms = world.building().storeys[storey].rooms;
  std::map<std::string, int> name_count;
  for (const auto& r : rooms) ++name_count[r.name];
  const auto label = [&](const bim::Room& r) { return name_count[r.name] == 1 && !r.name.empty() ? r.name : r.id; };
  // The tour: out to the largest room (usually the corridor or the living room), then to the
  // room farthest from the start.
  std::size_t largest = 0;
  for (std::size_t i = 1; i < rooms.size(); ++i)
    if (rooms[i].area_m2 > rooms[largest].area_m2) largest = i;
  std::vector<Scenario> out;
  for (std::size_t i = 0; i < rooms.size(); ++i) {
    std::size_t farthest = i;
    for (std::size_t j = 0; j < rooms.size(); ++j)
      if (j != largest && (rooms[j].centre - rooms[i].centre).norm() > (rooms[farthest].centre - rooms[i].centre).norm())
        farthest = j;
    for (int k = 0; k < o.seeds; ++k) {
      Scenario s;
      s.file = o.plan;
      s.world = o.plan;
      s.storey = std::to_string(storey);
      s.seed = o.first_seed + static_cast<std::uint64_t>(k);
      s.name = label(rooms[i]) + " seed " + std::to_string(s.seed) + (o.method == "pf" ? "" : " (" + o.method + ")");
      s.start.kind = StartConfig::Kind::RandomInRoom;
      s.start.room = label(rooms[i]);
      s.motion.kind = MotionConfig::Kind::Tour;
      s.motion.skip_unreachable_rooms = true;
      s.motion.explore_after_tour = true;
      if (largest != i) s.motion.rooms.push_back(label(rooms[largest]));
      if (farthest != i && farthest != largest) s.motion.rooms.push_back(label(rooms[farthest]));
      if (s.motion.rooms.empty()) s.motion.kind = MotionConfig::Kind::RandomWalk, s.motion.walk_room = s.start.room;
      s.duration_s = o.duration_s;
      s.odometry = odometryPreset("legged");
      s.localizer = {{"method", o.method}};
      s.expect.max_convergence_time_s = o.duration_s;
      out.push_back(std::move(s));
    }
  }
  return out;
}

Scenario stayInRoom(Scenario s) {
  s.motion.kind = MotionConfig::Kind::RandomWalk;
  s.motion.rooms.clear();
  s.motion.walk_room = s.start.room;
  return s;
}

}  // namespace bimloc::sim
