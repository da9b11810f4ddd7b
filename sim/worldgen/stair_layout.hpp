// The stair core of the stacked random worlds: a half-turn stair (two straight flights and a
// half landing between them) fitted into a rectangular stairwell entered from one side, and the
// void it needs in the floor slab above. Dimensions as building codes ask for them: risers of
// at most 0.185 m, a going of 0.27 m (2 risers + 1 going about 0.63 m), flights up to 1.4 m wide,
// a half landing as deep as a flight is wide, a floor landing of at least 1.2 m before the
// first riser.
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <optional>
#include <string>
#include <vector>

namespace bimloc::worldgen {

// A stairwell's clear rectangle seen from its door: the points origin + inward·u + across·v,
// u in [0, depth_m] (u = 0: the side with the door), v in [0, width_m].
struct StairWell {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  Eigen::Vector2d inward = Eigen::Vector2d::UnitY();  // unit, axis-aligned; the flights run along it
  Eigen::Vector2d across = Eigen::Vector2d::UnitX();  // unit, axis-aligned
  double depth_m = 0.0, width_m = 0.0;
};

struct StairDimensions {
  double max_riser_m = 0.185;  // risers per flight: the fewest that keep each at most this high
  double going_m = 0.27;
  double max_flight_width_m = 1.4;
  double min_flight_width_m = 0.9;
  double eye_m = 0.10;           // least gap between the two flights
  double floor_landing_m = 1.2;  // least clear depth from the door's side to the first riser
  double landing_thickness_m = 0.2;
};

// Risers per flight of a half-turn stair climbing `storey_height_m`.
int risersPerFlight(double storey_height_m, const StairDimensions& d = {});

// The clear depth a well needs for that stair with flights `flight_width_m` wide.
double stairwellDepth(double storey_height_m, double flight_width_m, const StairDimensions& d = {});

struct FittedStair {
  StairSpec stair;
  std::vector<Eigen::Vector2d> void_outline;  // CCW: where the flights rise through the slab above
};

// The stair from the well's floor up `storey_height_m`, the first flight on the v = 0 side when
// `first_on_low_side`, the flights against the well's side walls. nullopt when the well is too
// narrow or too shallow.
std::optional<FittedStair> fitHalfTurnStair(const StairWell& well, double storey_height_m, bool first_on_low_side,
                                            const std::string& name, const StairDimensions& d = {});

}  // namespace bimloc::worldgen
