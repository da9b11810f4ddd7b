// How the storeys hang together through their stairs (issue 31): each flight whose bottom
// stands on a storey, followed over its half landings (flights whose end is on no storey) to
// the flight that reaches the next storey, is a link, walked up or down. The planner routes a
// tour from storey to storey over the fewest links.
#pragma once

#include <bimloc/bim/building.hpp>

#include <cstddef>
#include <optional>
#include <vector>

namespace bimloc::sim {

// One way from storey `from` to storey `to`: the flights in walking order.
struct StairLink {
  std::size_t from = 0, to = 0;
  bool up = true;
  std::vector<const bim::StairFlight*> flights;
  // Where the base steps onto flight i and off it, in walking order (bottom then top going up).
  const Eigen::Vector3d& entry(std::size_t i) const { return up ? flights[i]->bottom : flights[i]->top; }
  const Eigen::Vector3d& exit(std::size_t i) const { return up ? flights[i]->top : flights[i]->bottom; }
};

// Every link of the building, up and down (the building must outlive them). A chain of
// flights that reaches no storey, or comes back to the one it left, is no link.
std::vector<StairLink> stairLinks(const bim::Building& building);

// The links to walk from `from` to `to`, fewest first (empty when from == to); nullopt when
// the stairs do not connect them.
std::optional<std::vector<const StairLink*>> stairRoute(const std::vector<StairLink>& links, std::size_t from,
                                                        std::size_t to);

// The storeys reachable from `start` by stairs, `start` first, then by the number of links.
std::vector<std::size_t> reachableStoreys(const std::vector<StairLink>& links, std::size_t start);

}  // namespace bimloc::sim
