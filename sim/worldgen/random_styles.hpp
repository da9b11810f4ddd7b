// The random worlds' styles (random_world.hpp) and the composite floor they share: one wing
// along x (A), optionally wings along y (B) whose corridors meet A's in an L, a T or a comb,
// optionally a large room at A's east end (an assembly hall, an open-plan office).
#pragma once

#include "sim/worldgen/random_layout.hpp"

#include <stdexcept>
#include <string>
#include <vector>

namespace bimloc::worldgen::layout {

// A room of a row: its use, the divider after it, and its door (door_at 0: fillRow centres it).
inline Item room(const char* use, Mm divider, bool door, Mm door_width) {
  Item item;
  item.use = use;
  item.divider = divider;
  item.door = door;
  item.door_width = door_width;
  return item;
}

// I: wing A alone; L: wing B at A's west end; T: `branches` wings B off A's north row (a comb
// from two on), never at its ends.
enum class Shape { I, L, T };
enum class Symmetry { None, Rot180, MirrorX, MirrorY };  // of the whole floor, before perturb()
const char* symmetryName(Symmetry s);

// How to fill a row: the repeated module (width, divider, door) and the rooms that take up the
// remainder.
struct RowRecipe {
  Mm depth = 0;  // 0: no row
  Item module;
  std::vector<Item> specials;
  bool alternate = false;  // every other module mirrored (apartments sharing a bathroom wall)
};

struct CompositePlan {
  Shape shape = Shape::I;
  Symmetry symmetry = Symmetry::None;
  Mm corridor = 2000, corridor_wall = 200;
  RowRecipe south, north;            // wing A
  int modules = 6;                   // per row of A (about)
  Mm corridor_b = 2000;              // wings B (L, T)
  RowRecipe west, east;              // a wing B's rows
  int modules_b = 4;
  int branches = 1;                  // T: how many wings B
  std::string corridor_use = "Corridor";
  int corridor_free_walls = 0;       // free-standing walls in A's corridor (a hall used as one)
  bool entrance_west = true, entrance_east = false, entrance_b = false;
  Mm fire_wall_every = 0;            // split A's corridor by doors in walls about this far apart (0: never)
  Mm end_hall = 0;                   // length of a large room beyond A's east end (0: none)
  std::string end_hall_use = "Hall";
  int end_hall_free_walls = 0;
};

// Draws the plan (perturbing it once when symmetric) and notes its features.
void drawComposite(Floor& floor, CompositePlan plan);

// Shape, branches and modules per row for about `rooms` rooms (modules, for apartments) of which
// `fixed_rooms` are not in rows: straight, L or T as drawn from the percentages, but no row
// longer than about 70 m - more wings instead.
void shareRooms(Random& rng, CompositePlan& plan, int rooms, int fixed_rooms, int percent_l, int percent_t);

// Up to `count` free-standing walls in the clear rectangle [a0, a1] x [b0, b1] of `frame`, each
// at least 0.9 m from the others and from the rectangle's sides, placed symmetrically when
// `symmetry` is not None (about the rectangle's centre). Returns how many.
int freeWalls(Floor& floor, const Frame& frame, Mm a0, Mm b0, Mm a1, Mm b1, int count, Symmetry symmetry);

// The styles: a floor of about `rooms` rooms.
void drawOffice(Floor& floor, int rooms);
void drawSchool(Floor& floor, int rooms);
void drawResidential(Floor& floor, int rooms);
void drawHall(Floor& floor, int rooms);
// A stair core (lobby and stairwell) with a flat on either side, mirror images of each other.
void drawApartmentBlock(Floor& floor, int rooms);

}  // namespace bimloc::worldgen::layout
