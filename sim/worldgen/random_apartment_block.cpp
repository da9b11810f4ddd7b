// Apartment blocks (random_styles.hpp): a central stair core - a lobby entered from the street
// and a stairwell behind it - with a flat on either side, the two flats mirror images of each
// other about the core. Each flat: a hall across the whole flat, entered from the lobby; living
// room and kitchen on the south facade, bedroom(s) and bathroom on the north one, all opening
// into the hall. The stairwell is as deep as the half-turn stair of the storey height needs.
// About half the blocks are changed in one small place (a door moved, a partition moved in one
// flat); the others keep the flats exact twins, and the core's doors (the stairwell's in front
// of the flight going up, the street door beside it) are what tells the two halves apart.
#include "sim/worldgen/random_styles.hpp"
#include "sim/worldgen/stair_layout.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::worldgen::layout {
namespace {

constexpr Mm kBlockJamb = 200;  // from a door's edge to the room's corner, at least

// One flat, along a: from the core's face outwards. Door centres along a, from that face.
struct BlockFlat {
  Mm living = 0, kitchen = 0;         // south band
  Mm bed = 0, bath = 0, bed2 = 0;     // north band (bed2 = 0: one bedroom)
  Mm living_door = 0, kitchen_door = 0, bed_door = 0, bath_door = 0, bed2_door = 0;
  Mm width() const { return living + kitchen; }  // + one partition
};

struct BlockPlan {
  Mm t = 100, party = 200;                 // partitions, the core's walls
  Mm south = 0, hall = 0, north = 0;       // band depths (clear)
  Mm core = 0;                             // the core's clear width
  Mm flat_door = 900, room_door = 850, entrance_width = 1000, stair_door_width = 900;
  Mm stair_door_at = 0, entrance_at = 0;   // centres, from the core's west face
  BlockFlat west, east;
};

// A door centre in [lo, hi] (clear faces) with the jambs clear of the corners, on 5 mm.
Mm doorIn(Random& rng, Mm lo, Mm hi, Mm width) {
  const Mm first = lo + width / 2 + kBlockJamb, last = hi - width / 2 - kBlockJamb;
  if (last < first) throw LayoutConflict("apartment block: a door does not fit in " + std::to_string(hi - lo) + " mm");
  return rng.steps(first, last, 5);  // lo, hi and half a door width are all on 5 mm
}

bool fitsIn(Mm centre, Mm lo, Mm hi, Mm width) {
  return centre - width / 2 - kBlockJamb >= lo && centre + width / 2 + kBlockJamb <= hi;
}

BlockFlat drawFlat(Random& rng, const BlockPlan& p) {
  BlockFlat f;
  f.living = rng.steps(3600, 5000, 50);
  f.kitchen = rng.steps(2600, 3400, 50);
  f.bed = rng.steps(3000, 4000, 50);
  f.bath = rng.steps(2500, 2800, 50);
  f.bed2 = rng.percent(40) ? rng.steps(2800, 3400, 50) : 0;
  const Mm south = f.living + p.t + f.kitchen;
  const Mm north = f.bed + p.t + f.bath + (f.bed2 > 0 ? p.t + f.bed2 : 0);
  if (south < north) {  // the wider band sets the flat's width; living room and kitchen share the rest
    const Mm more = (north - south) / 2 / 50 * 50;
    f.living += more, f.kitchen += north - south - more;
  }
  if (north < south) f.bed += south - north;
  const Mm W = f.width() + p.t;
  f.living_door = doorIn(rng, 0, f.living, p.room_door);
  f.kitchen_door = doorIn(rng, f.living + p.t, W, p.room_door);
  f.bed_door = doorIn(rng, 0, f.bed, p.room_door);
  f.bath_door = doorIn(rng, f.bed + p.t, f.bed + p.t + f.bath, p.room_door);
  if (f.bed2 > 0) f.bed2_door = doorIn(rng, f.bed + 2 * p.t + f.bath, W, p.room_door);
  return f;
}

// One small change to one flat: a door moved, or the living room / kitchen partition moved.
std::string perturbFlat(Random& rng, const BlockPlan& p, BlockFlat& f) {
  const Mm W = f.width() + p.t;
  if (rng.percent(50)) {
    const Mm delta = rng.steps(300, 500, 50) * (rng.percent(50) ? 1 : -1);
    const Mm living = f.living + delta, kitchen = f.kitchen - delta;
    if (living >= 3000 && kitchen >= 2500 && fitsIn(f.living_door, 0, living, p.room_door) &&
        fitsIn(f.kitchen_door + delta, living + p.t, W, p.room_door)) {
      f.living = living, f.kitchen = kitchen, f.kitchen_door += delta;
      return "living room / kitchen wall moved " + std::to_string(std::abs(delta)) + " mm";
    }
  }
  struct Choice {
    Mm* door;
    Mm lo, hi;
    const char* what;
  };
  std::vector<Choice> doors = {{&f.living_door, 0, f.living, "living room"},
                               {&f.kitchen_door, f.living + p.t, W, "kitchen"},
                               {&f.bed_door, 0, f.bed, "bedroom"},
                               {&f.bath_door, f.bed + p.t, f.bed + p.t + f.bath, "bathroom"}};
  const std::size_t first = static_cast<std::size_t>(rng.between(0, static_cast<Mm>(doors.size()) - 1));
  const Mm delta = rng.steps(300, 600, 50);
  for (std::size_t k = 0; k < doors.size(); ++k) {
    const Choice& c = doors[(first + k) % doors.size()];
    for (Mm sign : {1, -1}) {
      if (!fitsIn(*c.door + sign * delta, c.lo, c.hi, p.room_door)) continue;
      *c.door += sign * delta;
      return std::string(c.what) + " door moved " + std::to_string(delta) + " mm";
    }
  }
  return "";
}

void drawBlock(Floor& fl, const BlockPlan& p) {
  PlanGrid& g = fl.grid;
  const Mm E = fl.exterior, h = fl.door_height, t = p.t;
  const Mm W = p.west.width() + t;
  const Mm xW = kSiteMargin + E / 2, xPW = xW + E / 2 + W + p.party / 2;
  const Mm core0 = xPW + p.party / 2, core1 = core0 + p.core;
  const Mm xPE = core1 + p.party / 2, xE = xPE + p.party / 2 + W + E / 2;
  const Mm yS = kSiteMargin + E / 2, y1 = yS + E / 2 + p.south + t / 2, y2 = y1 + t + p.hall;
  const Mm yN = y2 + t / 2 + p.north + E / 2;
  g.lineX(xW, E), g.lineX(xE, E), g.lineY(yS, E), g.lineY(yN, E);
  g.lineX(xPW, p.party), g.lineX(xPE, p.party), g.lineY(y1, t), g.lineY(y2, t);

  const int lobby = fl.room("Lobby");
  g.paint(xPW, yS, xPE, y2, lobby);
  fl.stair_room = fl.room("Stairwell");
  g.paint(xPW, y2, xPE, yN, fl.stair_room);
  g.door(true, y2, core0 + p.stair_door_at, p.stair_door_width, h);   // lobby - stairwell
  g.door(true, yS, core0 + p.entrance_at, p.entrance_width, h);       // street - lobby

  for (int side : {-1, 1}) {
    const BlockFlat& f = side < 0 ? p.west : p.east;
    const Mm face = side < 0 ? core0 - p.party : core1 + p.party, party_axis = side < 0 ? xPW : xPE;
    const Mm outer = side < 0 ? xW : xE;
    const auto X = [&](Mm a) { return face + side * a; };
    const Mm a_living = f.living + t / 2, a_bed = f.bed + t / 2, a_bath = f.bed + t + f.bath + t / 2;
    g.lineX(X(a_living), t), g.lineX(X(a_bed), t);
    if (f.bed2 > 0) g.lineX(X(a_bath), t);
    const auto paint = [&](Mm x0, Mm x1, Mm y0, Mm y1_, const char* use) {
      const int label = fl.room(use);
      g.paint(std::min(x0, x1), y0, std::max(x0, x1), y1_, label);
    };
    paint(party_axis, outer, y1, y2, "Hall");
    paint(party_axis, X(a_living), yS, y1, "Living room");
    paint(X(a_living), outer, yS, y1, "Kitchen");
    paint(party_axis, X(a_bed), y2, yN, "Bedroom");
    paint(X(a_bed), f.bed2 > 0 ? X(a_bath) : outer, y2, yN, "Bathroom");
    if (f.bed2 > 0) paint(X(a_bath), outer, y2, yN, "Bedroom");
    const Mm hall_mid = (y1 + t / 2 + p.hall / 2) / 5 * 5;
    g.door(false, party_axis, hall_mid, p.flat_door, h);  // lobby - hall
    g.door(true, y1, X(f.living_door), p.room_door, h);
    g.door(true, y1, X(f.kitchen_door), p.room_door, h);
    g.door(true, y2, X(f.bed_door), p.room_door, h);
    g.door(true, y2, X(f.bath_door), p.room_door, h);
    if (f.bed2 > 0) g.door(true, y2, X(f.bed2_door), p.room_door, h);
  }
}

}  // namespace

void drawApartmentBlock(Floor& fl, int /*rooms*/) {
  Random& rng = fl.rng;
  BlockPlan p;
  p.t = rng.pick<Mm>({100, 120});
  p.party = rng.pick<Mm>({200, 220, 240, 250});
  p.south = rng.steps(4000, 5000, 50);
  p.hall = rng.steps(1400, 1800, 50);
  p.core = rng.steps(2800, 3200, 10);
  p.flat_door = rng.pick<Mm>({900, 1000});
  p.room_door = rng.pick<Mm>({850, 900});
  const StairDimensions stair;
  const double flight_m = std::min(stair.max_flight_width_m, (p.core / 1000.0 - stair.eye_m) / 2);
  const Mm well = static_cast<Mm>(std::ceil(stairwellDepth(fl.storey_height / 1000.0, flight_m, stair) * 1000 / 50)) * 50;
  p.north = well + rng.steps(0, 400, 50);
  p.west = drawFlat(rng, p);
  p.east = p.west;
  // The stairwell's door in front of the flight going up, or in the middle of the core.
  const Mm flight_mm = static_cast<Mm>(std::lround(flight_m * 1000));
  const bool up_west = rng.percent(50);
  const bool twins = rng.percent(50);
  std::string note;
  if (twins) {  // exact twin flats: the core's doors off its axis tell the halves apart
    p.stair_door_at = (up_west ? flight_mm / 2 : p.core - flight_mm / 2) / 5 * 5;
    const Mm off = p.core / 2 - p.entrance_width / 2 - kBlockJamb;
    p.entrance_at = (p.core / 2 + (up_west ? off : -off)) / 5 * 5;
  } else {  // symmetric core, one flat changed in one place
    p.stair_door_at = p.entrance_at = p.core / 2;
    const bool west = rng.percent(50);
    note = perturbFlat(rng, p, west ? p.west : p.east);
    if (note.empty()) throw LayoutConflict("apartment block: no small change fits");
    note = "near-symmetric (mirror x): " + std::string(west ? "west" : "east") + " flat's " + note;
    fl.near_symmetric = true;
  }
  drawBlock(fl, p);
  const int rooms_per_flat = 5 + (p.west.bed2 > 0 ? 1 : 0);
  fl.features.push_back("stair core with two mirrored flats of " + std::to_string(rooms_per_flat) + " rooms");
  fl.features.push_back(twins ? std::string("twin flats; stairwell and street doors off the core's axis")
                              : note);
}

}  // namespace bimloc::worldgen::layout
