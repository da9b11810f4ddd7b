// Starts outside every room: halls and corridors the plan has no IfcSpace for, doorways, and
// the ground just outside the building. The localizer spreads its particles over rooms, but
// rooms are a prior, not a measurement: it must localize from there too, and this is where
// the simulator puts the robot to find out.
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>

namespace bimloc::sim {

class World;

// How far outside the walls a start may be drawn: the lidar still sees the facade.
constexpr double kOutsideReach_m = 3.0;

// Where a spot in no room is: "doorway" (within a wall's thickness of a room), "no room"
// (inside the building's outline: a hall or corridor without a space), or "outside".
std::string outsideKind(const bim::Storey& storey, const Eigen::Vector2d& p);

// A random spot of the storey in no room where the body (radius, at body height) fits,
// within kOutsideReach_m of a wall, from which a path leads into the nearest room, drawn from
// `seed`, which also picks the kind of place tried first (seed % 3: 0 anywhere, mostly in front
// of the building; 1 just off a room's edge, i.e. doorways; 2 inside the building's outline);
// nullopt when none was found.
std::optional<Eigen::Vector2d> outsideRoomsSpot(const World& world, std::size_t storey, double radius_m, double body_height_m,
                                                std::uint64_t seed);

}  // namespace bimloc::sim
