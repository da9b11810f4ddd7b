// The paper's experiment on any plan, with no YAML to write: one scenario per room of a
// storey, starting at a random pose in that room and walking out of it through the building;
// or starts outside every room (halls without a space, doorways, just outside the building).
#pragma once

#include "sim/scenario/scenario.hpp"
#include "sim/world/world.hpp"

#include <string>
#include <vector>

namespace bimloc::sim {

struct RoomScenarioOptions {
  std::string plan;
  // A storey name or index; "auto": every storey with walls and rooms, each run on its true
  // storey in the simulator, the localizer not told which (localizer.storey: auto).
  std::string storey = "0";
  // "rooms": a random start in each room, `seeds` each; "outside": `seeds` random starts in
  // no room per storey (start.outside_rooms).
  std::string starts = "rooms";
  int seeds = 1;
  std::string method = "sgraph";  // sgraph | pf | pf-no-rooms
  double duration_s = 40.0;
  std::uint64_t first_seed = 1;
};

// The scenarios (rooms named by their Name, or GlobalId where Names repeat): the start, then
// a tour to the largest room of the storey and on to another one. Throws
// std::invalid_argument for an unknown storey, or `starts`.
std::vector<Scenario> roomScenarios(const World& world, const RoomScenarioOptions& options);

// The same scenario with a random walk in its start room instead of the tour: for plans whose
// doors are closed in the mesh, where no path leads out of the room. A start in no room
// stands instead.
Scenario stayInRoom(Scenario scenario);

// `--multi-storey` (issue 31): the scenario's motion becomes a tour that, after its own rooms
// (a tour's; none for another motion), visits every storey the stairs reach from the start,
// an equal share of the duration on each (MotionConfig::all_storeys).
Scenario multiStoreyTour(Scenario scenario);

}  // namespace bimloc::sim
