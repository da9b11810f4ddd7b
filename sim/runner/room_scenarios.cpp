#include "sim/runner/room_scenarios.hpp"

#include <bimloc/pf/storey_bank.hpp>

#include <algorithm>
#include <map>
#include <stdexcept>

namespace bimloc::sim {
namespace {

Scenario base(const RoomScenarioOptions& o, std::size_t storey, bool storey_auto, int k) {
  Scenario s;
  s.file = o.plan;
  s.world = o.plan;
  s.storey = std::to_string(storey);  // the simulator's: the truth
  s.seed = o.first_seed + static_cast<std::uint64_t>(k);
  s.motion.kind = MotionConfig::Kind::Tour;
  s.motion.skip_unreachable_rooms = true;
  s.motion.explore_after_tour = true;
  s.duration_s = o.duration_s;
  s.odometry = odometryPreset("legged");
  s.localizer = {{"method", o.method}};
  if (storey_auto) s.localizer["storey"] = "auto";
  s.expect.max_convergence_time_s = o.duration_s;
  return s;
}

void storeyScenarios(const World& world, const RoomScenarioOptions& o, std::size_t storey, bool storey_auto,
                     const std::string& prefix, std::vector<Scenario>& out) {
  const auto& rooms = world.building().storeys[storey].rooms;
  std::map<std::string, int> name_count;
  for (const auto& r : rooms) ++name_count[r.name];
  const auto label = [&](const bim::Room& r) { return name_count[r.name] == 1 && !r.name.empty() ? r.name : r.id; };
  const std::string suffix = o.method == "sgraph" ? "" : " (" + o.method + ")";
  // The tour: out to the largest room (usually the corridor or the living room), then to the
  // room farthest from the start.
  std::size_t largest = 0;
  for (std::size_t i = 1; i < rooms.size(); ++i)
    if (rooms[i].area_m2 > rooms[largest].area_m2) largest = i;
  const auto farthestFrom = [&](const Eigen::Vector2d& p) {
    std::size_t farthest = rooms.size();
    for (std::size_t j = 0; j < rooms.size(); ++j)
      if (j != largest && (farthest == rooms.size() || (rooms[j].centre - p).norm() > (rooms[farthest].centre - p).norm()))
        farthest = j;
    return farthest;
  };
  if (o.starts == "outside") {
    // Where the start is drawn is not known here: the tour goes to the largest room, then to
    // the room farthest from it.
    const std::size_t farthest = rooms.empty() ? 0 : farthestFrom(rooms[largest].centre);
    for (int k = 0; k < o.seeds; ++k) {
      Scenario s = base(o, storey, storey_auto, k);
      s.name = prefix + "outside seed " + std::to_string(s.seed) + suffix;
      s.start.kind = StartConfig::Kind::OutsideRooms;
      if (!rooms.empty()) s.motion.rooms.push_back(label(rooms[largest]));
      if (farthest < rooms.size()) s.motion.rooms.push_back(label(rooms[farthest]));
      if (s.motion.rooms.empty()) s.motion.kind = MotionConfig::Kind::Stand;
      out.push_back(std::move(s));
    }
    return;
  }
  for (std::size_t i = 0; i < rooms.size(); ++i) {
    std::size_t farthest = farthestFrom(rooms[i].centre);
    if (farthest == rooms.size()) farthest = i;
    for (int k = 0; k < o.seeds; ++k) {
      Scenario s = base(o, storey, storey_auto, k);
      s.name = prefix + label(rooms[i]) + " seed " + std::to_string(s.seed) + suffix;
      s.start.kind = StartConfig::Kind::RandomInRoom;
      s.start.room = label(rooms[i]);
      if (largest != i) s.motion.rooms.push_back(label(rooms[largest]));
      if (farthest != i && farthest != largest) s.motion.rooms.push_back(label(rooms[farthest]));
      if (s.motion.rooms.empty()) s.motion.kind = MotionConfig::Kind::RandomWalk, s.motion.walk_room = s.start.room;
      out.push_back(std::move(s));
    }
  }
}

}  // namespace

std::vector<Scenario> roomScenarios(const World& world, const RoomScenarioOptions& o) {
  if (o.starts != "rooms" && o.starts != "outside") throw std::invalid_argument("starts: expected 'rooms' or 'outside'");
  std::vector<Scenario> out;
  if (o.storey == "auto") {
    // Every storey that could hold the robot; names say which one the run starts on.
    for (const std::size_t s : pf::StoreyBank::candidateStoreys(world.building()))
      storeyScenarios(world, o, s, true, world.building().storeyLabel(s) + "/", out);
    return out;
  }
  storeyScenarios(world, o, world.storeyIndex(o.storey), false, "", out);
  return out;
}

Scenario multiStoreyTour(Scenario s) {
  if (s.motion.kind != MotionConfig::Kind::Tour) s.motion.rooms.clear(), s.motion.storeys.clear();
  s.motion.kind = MotionConfig::Kind::Tour;
  s.motion.all_storeys = true;
  s.motion.skip_unreachable_rooms = true;
  s.motion.explore_after_tour = true;
  return s;
}

Scenario stayInRoom(Scenario s) {
  s.motion.rooms.clear();
  if (s.start.kind == StartConfig::Kind::OutsideRooms) {
    s.motion.kind = MotionConfig::Kind::Stand;  // no room to walk in
    return s;
  }
  s.motion.kind = MotionConfig::Kind::RandomWalk;
  s.motion.walk_room = s.start.room;
  return s;
}

}  // namespace bimloc::sim
