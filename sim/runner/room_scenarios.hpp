// The paper's experiment on any plan, with no YAML to write: one scenario per room of a
// storey, starting at a random pose in that room and walking out of it through the building.
#pragma once

#include "sim/scenario/scenario.hpp"
#include "sim/world/world.hpp"

#include <string>
#include <vector>

namespace bimloc::sim {

struct RoomScenarioOptions {
  std::string plan;
  std::string storey = "0";
  int seeds = 1;
  std::string method = "pf";  // pf | pf-no-rooms
  double duration_s = 40.0;
  std::uint64_t first_seed = 1;
};

// Scenarios for every room of the storey (random start in the room, a tour to the largest
// room and on to another one). Rooms are named by their Name, or GlobalId where Names repeat.
std::vector<Scenario> roomScenarios(const World& world, const RoomScenarioOptions& options);

// The same scenario with a random walk in its start room instead of the tour: for plans whose
// doors are closed in the mesh, where no path leads out of the room.
Scenario stayInRoom(Scenario scenario);

}  // namespace bimloc::sim
