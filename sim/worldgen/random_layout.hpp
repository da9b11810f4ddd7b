// Building blocks of the random worlds (random_world.hpp): a seeded random source that does
// not depend on the standard library's distributions, frames that place a local layout in the
// plan (turned, mirrored), and wings: a corridor with a row of rooms on either side, drawn as
// PlanGrid lines and cells. Integer millimetres throughout.
#pragma once

#include "sim/worldgen/plan_grid.hpp"

#include <cstdint>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace bimloc::worldgen::layout {

// The building's outline starts this far from the plan's axes. IFC++ fails to cut a door
// opening out of a wall along y when the opening straddles x = 0 (for some thicknesses: 0.10,
// 0.15, 0.24, 0.36-0.40 m; the reader then warns "faces approximated"), and an entrance in a
// west wall whose outer face is at x = 0 does.
constexpr Mm kSiteMargin = 1000;

// std::mt19937_64's sequence is fixed by the standard; everything else is integer arithmetic
// here, so a seed gives the same world everywhere.
class Random {
 public:
  explicit Random(std::uint64_t seed);
  std::uint64_t next() { return engine_(); }
  Mm between(Mm lo, Mm hi) {  // uniform in [lo, hi] (the modulo's bias is below 1e-15)
    if (hi < lo) throw std::logic_error("random layout: empty range [" + std::to_string(lo) + ", " + std::to_string(hi) + "]");
    return lo + static_cast<Mm>(next() % static_cast<std::uint64_t>(hi - lo + 1));
  }
  Mm steps(Mm lo, Mm hi, Mm step) { return lo + step * between(0, (hi - lo) / step); }  // lo + k·step <= hi
  bool percent(int p) { return between(0, 99) < p; }
  template <typename T>
  const T& pick(const std::vector<T>& options) { return options[static_cast<std::size_t>(between(0, static_cast<Mm>(options.size()) - 1))]; }

 private:
  std::mt19937_64 engine_;
};

// Local (a, b) -> plan (x, y) = origin + M (a, b), M a signed permutation: turns by multiples
// of 90 degrees and mirror images.
struct Frame {
  int m00 = 1, m01 = 0, m10 = 0, m11 = 1;
  Mm ox = 0, oy = 0;

  static Frame swapped() { return {0, 1, 1, 0, 0, 0}; }  // a along y, b along x
  Frame then(const Frame& inner) const;                  // this ∘ inner
  bool aAlongX() const { return m00 != 0; }
  Mm x(Mm a, Mm b) const { return ox + m00 * a + m01 * b; }
  Mm y(Mm a, Mm b) const { return oy + m10 * a + m11 * b; }
  void lineA(PlanGrid& g, Mm a, Mm thickness) const;  // the line a = const
  void lineB(PlanGrid& g, Mm b, Mm thickness) const;
  void paint(PlanGrid& g, Mm a0, Mm b0, Mm a1, Mm b1, int label) const;
  int doorOnA(PlanGrid& g, Mm a_line, Mm b_centre, Mm width, Mm height) const;  // in the line a = a_line
  int doorOnB(PlanGrid& g, Mm b_line, Mm a_centre, Mm width, Mm height) const;
  void freeWallAlongA(PlanGrid& g, Mm b, Mm a0, Mm a1, Mm thickness) const;
  void freeWallAlongB(PlanGrid& g, Mm a, Mm b0, Mm b1, Mm thickness) const;
};

// An apartment: two bands across its depth. Near the corridor: bath, hall (the entrance) and an
// optional kitchen; at the facade: bedroom(s) and the living room, which the hall opens into.
struct Apartment {
  Mm near_depth = 0, partition = 100;  // near band depth; interior partitions
  Mm bath = 0, hall = 0;               // widths; the kitchen takes the rest of the near band (0: none)
  Mm bed = 0, bed2 = 0;                // bedroom widths at the facade (bed2 = 0: one bedroom)
  Mm entrance_at = 0;                  // entrance door centre, from the hall's start face
  Mm bed_door_at = 0;                  // bedroom door centre, from the band wall's face
  Mm door_width = 900;
};

// One slot of a row, along the corridor.
struct Item {
  enum class Kind { Room, Passage, Apartment } kind = Kind::Room;
  Mm width = 0;    // clear, along the row
  Mm divider = 0;  // thickness of the wall after it (unused after the last item)
  std::string use;
  bool door = true;
  bool door_from_end = false;  // door centre measured from the item's end face, not its start
  Mm door_at = 0;              // that distance
  Mm door_width = 900;
  Mm free_wall = 0;  // length of a free-standing wall in the middle of the room (0: none)
  Apartment apartment;
  bool mirrored = false;  // Kind::Apartment: drawn mirrored along the row
  std::string note;       // what perturb() changed here
  int label = -1;         // set when drawn (Kind::Apartment: its hall)
};

struct Row {
  Mm depth = 0;  // clear, across; 0: no row on this side
  std::vector<Item> items;
  Mm length() const;  // clear, from the first start face to the last end face
};

// A corridor along local a with rows of rooms on both sides (local b: "south" row at low b).
// Lines: start and end walls at a_start / a_end (axes), the south outer wall at b_south.
// With corridor == 0 there is one row (south) between the outer lines.
struct Wing {
  Frame frame;
  Mm a_start = 0, t_start = 0, a_end = 0, t_end = 0;
  Mm b_south = 0, t_south = 0, t_north = 0;  // outer lines' thickness
  Mm corridor = 0, corridor_wall = 0;
  Row south, north;
  int corridor_label = -1;
  // Set by drawWing: the axes of the corridor walls (= outer lines where a row is missing).
  Mm b_corridor_south = 0, b_corridor_north = 0, b_north = 0;
  Mm faceStart() const { return a_start + t_start / 2; }
  Mm faceEnd() const { return a_end - t_end / 2; }
  Mm width() const;  // from b_south to b_north (axes)
};

struct Floor {
  Floor(Random& random, Mm exterior_mm) : rng(random), grid(exterior_mm), exterior(exterior_mm) {}
  Random& rng;
  PlanGrid grid;
  Mm exterior;
  Mm door_height = 2100;
  Mm storey_height = 3000;  // floor to floor: what a stair core drawn on the floor must climb
  int stair_room = -1;      // the label of the stairwell, when the style draws one
  std::vector<std::string> features;
  bool near_symmetric = false;  // drawn symmetric, then changed in one place (perturb)
  int room(const std::string& use);  // R001, R002, ...
  static std::string roomName(int label);
};

// Draws the wing's lines, cells and doors; rooms get names in row order.
void drawWing(Floor& floor, Wing& wing);

// Items filling `length` exactly: `module` repeated, the remainder as one or two rooms from
// `specials` (widths 2.5-8 m), placed at the start, the end or amid the modules.
std::vector<Item> fillRow(Random& rng, Mm length, const Item& module, const std::vector<Item>& specials);
// The row read backwards (a 180-degree turn of it), and a palindrome: `half`, `centre` if its
// width is not 0, and `half` mirrored.
std::vector<Item> reversedItems(const std::vector<Item>& items);
std::vector<Item> palindrome(const std::vector<Item>& half, const Item& centre);
// Sum of widths and dividers in between.
Mm itemsLength(const std::vector<Item>& items);

// One small difference in a symmetric layout: a door moved or missing, two rooms resized, or
// a short free-standing wall. Returns what it did ("" when nothing applied).
std::string perturb(Random& rng, std::vector<Row*> rows);

}  // namespace bimloc::worldgen::layout
