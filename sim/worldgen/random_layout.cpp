// Frames, wings and apartments drawn on a PlanGrid (random_layout.hpp).
#include "sim/worldgen/random_layout.hpp"

#include <algorithm>
#include <cstdio>
#include <stdexcept>

namespace bimloc::worldgen::layout {

Random::Random(std::uint64_t seed) {
  // SplitMix64's finaliser, so that neighbouring seeds start far apart.
  std::uint64_t z = seed + 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  engine_.seed(z ^ (z >> 31));
}

Frame Frame::then(const Frame& in) const {
  return {m00 * in.m00 + m01 * in.m10, m00 * in.m01 + m01 * in.m11,
          m10 * in.m00 + m11 * in.m10, m10 * in.m01 + m11 * in.m11,
          ox + m00 * in.ox + m01 * in.oy, oy + m10 * in.ox + m11 * in.oy};
}

void Frame::lineA(PlanGrid& g, Mm a, Mm t) const {
  if (aAlongX()) g.lineX(x(a, 0), t);
  else g.lineY(y(a, 0), t);
}

void Frame::lineB(PlanGrid& g, Mm b, Mm t) const {
  if (aAlongX()) g.lineY(y(0, b), t);
  else g.lineX(x(0, b), t);
}

void Frame::paint(PlanGrid& g, Mm a0, Mm b0, Mm a1, Mm b1, int label) const {
  const Mm xa = x(a0, b0), xb = x(a1, b1), ya = y(a0, b0), yb = y(a1, b1);
  g.paint(std::min(xa, xb), std::min(ya, yb), std::max(xa, xb), std::max(ya, yb), label);
}

int Frame::doorOnA(PlanGrid& g, Mm a_line, Mm b_centre, Mm width, Mm height) const {
  const Mm gx = x(a_line, b_centre), gy = y(a_line, b_centre);
  return aAlongX() ? g.door(false, gx, gy, width, height) : g.door(true, gy, gx, width, height);
}

int Frame::doorOnB(PlanGrid& g, Mm b_line, Mm a_centre, Mm width, Mm height) const {
  const Mm gx = x(a_centre, b_line), gy = y(a_centre, b_line);
  return aAlongX() ? g.door(true, gy, gx, width, height) : g.door(false, gx, gy, width, height);
}

void Frame::freeWallAlongA(PlanGrid& g, Mm b, Mm a0, Mm a1, Mm t) const {
  if (aAlongX()) g.freeWall(true, y(a0, b), x(a0, b), x(a1, b), t);
  else g.freeWall(false, x(a0, b), y(a0, b), y(a1, b), t);
}

void Frame::freeWallAlongB(PlanGrid& g, Mm a, Mm b0, Mm b1, Mm t) const {
  if (aAlongX()) g.freeWall(false, x(a, b0), y(a, b0), y(a, b1), t);
  else g.freeWall(true, y(a, b0), x(a, b0), x(a, b1), t);
}

Mm itemsLength(const std::vector<Item>& items) {
  Mm length = 0;
  for (std::size_t k = 0; k < items.size(); ++k) length += items[k].width + (k + 1 < items.size() ? items[k].divider : 0);
  return length;
}

Mm Row::length() const { return itemsLength(items); }

Mm Wing::width() const { return b_north - b_south; }

std::string Floor::roomName(int label) {
  char name[16];
  std::snprintf(name, sizeof name, "R%03d", label + 1);
  return name;
}

int Floor::room(const std::string& use) { return grid.addRoom(roomName(grid.roomCount()), use); }

namespace {

// Where a row lies across the wing: its band between two line axes, the corridor-side line
// (doors), and the corridor-side face, from which apartments measure their depth.
struct Band {
  Mm b_lo, b_hi, b_door, b_face;
  int towards_outer;  // +1: depth grows with b
};

// An apartment in the slot [a_lo, a_hi] (axes) of a row, its faces `start`..`end`.
void drawApartment(Floor& f, const Frame& F, Item& item, const Band& band, Mm a_lo, Mm a_hi, Mm start, Mm end) {
  const Apartment& ap = item.apartment;
  const Mm W = item.width, t = ap.partition;
  const auto A = [&](Mm p) { return item.mirrored ? end - p : start + p; };
  const auto B = [&](Mm q) { return band.b_face + band.towards_outer * q; };
  const Mm side0 = item.mirrored ? a_hi : a_lo, side1 = item.mirrored ? a_lo : a_hi;
  const Mm b_corr = band.b_door, b_outer = band.towards_outer > 0 ? band.b_hi : band.b_lo;
  const Mm b_near = B(ap.near_depth + t / 2);
  F.lineB(f.grid, b_near, t);
  const Mm hall_from = ap.bath + t;
  const bool kitchen = hall_from + ap.hall < W;
  std::vector<Mm> near_axes = {side0, A(ap.bath + t / 2)}, far_axes = {side0, A(ap.bed + t / 2)};
  if (kitchen) near_axes.push_back(A(hall_from + ap.hall + t / 2));
  if (ap.bed2 > 0) far_axes.push_back(A(W - ap.bed2 - t / 2));
  near_axes.push_back(side1), far_axes.push_back(side1);
  for (std::size_t k = 1; k + 1 < near_axes.size(); ++k) F.lineA(f.grid, near_axes[k], t);
  for (std::size_t k = 1; k + 1 < far_axes.size(); ++k) F.lineA(f.grid, far_axes[k], t);
  const auto paint = [&](Mm a0, Mm a1, Mm b0, Mm b1, const char* use) {
    const int label = f.room(use);
    F.paint(f.grid, std::min(a0, a1), std::min(b0, b1), std::max(a0, a1), std::max(b0, b1), label);
    return label;
  };
  paint(near_axes[0], near_axes[1], b_corr, b_near, "Bathroom");
  const int hall = paint(near_axes[1], near_axes[2], b_corr, b_near, "Hall");
  if (kitchen) paint(near_axes[2], near_axes[3], b_corr, b_near, "Kitchen");
  paint(far_axes[0], far_axes[1], b_near, b_outer, "Bedroom");
  paint(far_axes[1], far_axes[2], b_near, b_outer, "Living room");
  if (ap.bed2 > 0) paint(far_axes[2], far_axes[3], b_near, b_outer, "Bedroom");
  item.label = hall;

  const Mm h = f.door_height, mid_near = B(ap.near_depth / 2 / 5 * 5);
  F.doorOnB(f.grid, b_corr, A(hall_from + ap.entrance_at), ap.door_width, h);      // corridor - hall
  F.doorOnA(f.grid, near_axes[1], mid_near, 850, h);                               // hall - bath
  if (kitchen) F.doorOnA(f.grid, near_axes[2], mid_near, 850, h);                  // hall - kitchen
  const Mm living_from = ap.bed + t, living_to = ap.bed2 > 0 ? W - ap.bed2 - t : W;
  const Mm lo = std::max(hall_from, living_from), hi = std::min(hall_from + ap.hall, living_to);
  F.doorOnB(f.grid, b_near, A((lo + hi) / 2 / 5 * 5), ap.door_width, h);          // hall - living
  const Mm q_bed = ap.near_depth + t + ap.bed_door_at;
  F.doorOnA(f.grid, far_axes[1], B(q_bed), ap.door_width, h);                      // living - bedroom
  if (ap.bed2 > 0) F.doorOnA(f.grid, far_axes[2], B(q_bed), ap.door_width, h);     // living - bedroom 2
}

void drawRow(Floor& f, Wing& w, Row& row, const Band& band) {
  const Frame& F = w.frame;
  Mm cursor = w.faceStart(), prev_axis = w.a_start;
  for (std::size_t k = 0; k < row.items.size(); ++k) {
    Item& item = row.items[k];
    const bool last = k + 1 == row.items.size();
    const Mm start = cursor, end = cursor + item.width;
    const Mm end_axis = last ? w.a_end : end + item.divider / 2;
    if (!last) F.lineA(f.grid, end_axis, item.divider);
    if (last && end != w.faceEnd()) {
      throw std::logic_error("random layout: a row ends at " + std::to_string(end) + " mm, its wing at " +
                             std::to_string(w.faceEnd()) + " mm");
    }
    if (item.kind == Item::Kind::Passage) {
      F.paint(f.grid, prev_axis, band.b_lo, end_axis, band.b_hi, w.corridor_label);
    } else if (item.kind == Item::Kind::Apartment) {
      drawApartment(f, F, item, band, prev_axis, end_axis, start, end);
    } else {
      item.label = f.room(item.use);
      F.paint(f.grid, prev_axis, band.b_lo, end_axis, band.b_hi, item.label);
      if (item.door) {
        F.doorOnB(f.grid, band.b_door, item.door_from_end ? end - item.door_at : start + item.door_at, item.door_width,
                  f.door_height);
      }
      if (item.free_wall > 0) {  // across the middle of the room, parallel to the corridor
        const Mm face_lo = band.towards_outer > 0 ? band.b_face : band.b_face - row.depth;
        const Mm b_mid = (face_lo + row.depth / 2) / 5 * 5, a_mid = (start + end) / 2 / 5 * 5;
        F.freeWallAlongA(f.grid, b_mid, a_mid - item.free_wall / 2, a_mid + item.free_wall / 2, 120);
      }
    }
    prev_axis = end_axis;
    cursor = end + item.divider;
  }
}

}  // namespace

void drawWing(Floor& f, Wing& w) {
  const Frame& F = w.frame;
  F.lineA(f.grid, w.a_start, w.t_start);
  F.lineA(f.grid, w.a_end, w.t_end);
  F.lineB(f.grid, w.b_south, w.t_south);
  const bool south = w.south.depth > 0, north = w.corridor > 0 && w.north.depth > 0;
  Mm b = w.b_south + w.t_south / 2;  // face cursor across the wing
  if (south) b += w.south.depth + (w.corridor > 0 ? w.corridor_wall : w.t_north) / 2;
  w.b_corridor_south = south ? b : w.b_south;
  if (w.corridor > 0) {
    if (south) F.lineB(f.grid, b, w.corridor_wall);
    b += (south ? w.corridor_wall / 2 : 0) + w.corridor + (north ? w.corridor_wall : w.t_north) / 2;
    w.b_corridor_north = b;
    if (north) {
      F.lineB(f.grid, b, w.corridor_wall);
      b += w.corridor_wall / 2 + w.north.depth + w.t_north / 2;
    }
  } else {
    w.b_corridor_north = b;  // one row, doors in the outer line
  }
  w.b_north = b;
  F.lineB(f.grid, w.b_north, w.t_north);
  if (w.corridor > 0) F.paint(f.grid, w.a_start, w.b_corridor_south, w.a_end, w.b_corridor_north, w.corridor_label);
  if (south) {
    const Mm door_line = w.corridor > 0 ? w.b_corridor_south : w.b_north;
    const Mm face = door_line - (w.corridor > 0 ? w.corridor_wall : w.t_north) / 2;
    drawRow(f, w, w.south, {w.b_south, door_line, door_line, face, -1});
  }
  if (north) {
    drawRow(f, w, w.north, {w.b_corridor_north, w.b_north, w.b_corridor_north, w.b_corridor_north + w.corridor_wall / 2, 1});
  }
}

}  // namespace bimloc::worldgen::layout
