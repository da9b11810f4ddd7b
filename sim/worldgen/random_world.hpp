// Random floors for sweeps of the localizer: realistic, and hard in the ways real plans are.
// Drawn from a seed (same seed and options, same WorldSpec, same IFC bytes), in one of five
// styles, with architects' dimensions (exterior walls 0.30-0.45 m, partitions 0.10-0.20 m,
// load-bearing corridor walls 0.20-0.25 m, doors 0.85-1.00 m and 1.2-1.8 m double doors, rooms
// 2.5-8 m, corridors 1.5-2.5 m, storeys 2.8-3.5 m, coordinates on 5 mm):
//  - office: rows of identical offices on a corridor (straight, L or T), meeting rooms, WCs,
//    shafts and stores without doors, fire doors in long corridors, sometimes an open-plan hall;
//  - residential: identical apartments (every other one mirrored) on a corridor; a house below
//    nine rooms;
//  - school: classrooms along a corridor, single- or double-loaded, often an assembly hall;
//  - hall: a large hall with free-standing walls and small rooms opening into it;
//  - apartment_block: a stair core (lobby, stairwell) with two flats mirrored about it
//    (random_apartment_block.cpp).
// Office and apartment_block floors stack into buildings of up to five storeys, the same floor
// on each, joined by a half-turn stair in the stair core (random_storeys.hpp).
// Often (about half the floors) the floor is drawn symmetric - rows turned by 180 degrees or
// mirrored, mirrored wings - and then changed in one small place: a door moved or missing, a
// wall between two rooms moved, a short free-standing wall. That is the case where a particle
// filter converges in the twin room. Every room with a door can be reached from every other
// through doors; rooms without one are named so ("Shaft", "... (no door)").
#pragma once

#include "sim/worldgen/world_spec.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::worldgen {

enum class RandomStyle { Office, Residential, School, Hall, ApartmentBlock };

struct RandomWorldOptions {
  RandomStyle style = RandomStyle::Office;
  int rooms = 0;  // about this many rooms (within 10 % from 20 up); 0: the style's usual size, from the seed
                  // (apartment_block: ignored, a block has 12-14 rooms a floor)
  int storeys = 1;  // 1..kMaxRandomStoreys; more than one for office and apartment_block only
};

constexpr int kMaxRandomStoreys = 5;

// What the generator put in a world, beyond its spec.
struct RandomWorldInfo {
  std::vector<std::string> features;  // "row of 6 identical Office", "near-symmetric (mirror x): R012 door moved 450 mm", ...
  bool near_symmetric = false;        // drawn symmetric, then changed in one place
  int closed_rooms = 0;               // rooms without a door
  int free_walls = 0;                 // free-standing walls (in no room's boundary)
  int attempts = 1;                   // draws until one fitted together
  // The symmetry (spec_symmetry.hpp) under which the fewest walls and doorways have no twin.
  std::string closest_symmetry;
  int symmetry_mismatches = 0;
  std::string stair_room;  // the ground floor's stairwell, when the building has stairs
};

// "office", "residential", "school", "hall", "apartment_block".
const std::vector<std::string>& randomStyleNames();
// The styles `worldgen --random-count` cycles through: the first four (a fixed set, so that
// generated benchmark sets keep their floors).
constexpr int kCycledRandomStyles = 4;
// Whether a style stacks into several storeys.
bool randomStyleStacks(RandomStyle style);
// Throws std::invalid_argument listing the names for an unknown one.
RandomStyle randomStyle(const std::string& name);
std::string randomStyleName(RandomStyle style);

// The world "random_<style>_<seed>" ("..._<N>storeys" for N > 1). Checked with checkWorldSpec
// and for reachability through doors; a world that fails is a generator bug: std::logic_error
// naming seed and style. Options out of range (storeys): std::invalid_argument.
WorldSpec randomWorld(std::uint64_t seed, const RandomWorldOptions& options = {}, RandomWorldInfo* info = nullptr);

}  // namespace bimloc::worldgen
