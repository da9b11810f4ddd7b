#include "sim/render/layers.hpp"

#include "sim/render/legend.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim::render {

namespace {

bool finite(const Eigen::Vector2d& p) { return p.allFinite(); }

// A segment's band: its thickness on the plan, but never thinner than `min_px`, so a matched
// partition or a new plane stays visible in a large building.
void band(const SnapshotGraph::Segment& s, const Layout& layout, double min_px, const Colour& colour) {
  if (!finite(s.start) || !finite(s.end)) return;
  const double width = std::max(min_px, s.thickness_m * layout.px_per_m);
  const Eigen::Vector2d a = layout.toPixel(s.start), b = layout.toPixel(s.end);
  segment(a, b, width, colour);
  // Square caps: the band covers the wall's ends as the plan's footprint does.
  const Eigen::Vector2d d = b - a;
  if (d.norm() > 1e-9) {
    const Eigen::Vector2d u = d.normalized() * (0.5 * width);
    segment(a - u, a, width, colour);
    segment(b, b + u, width, colour);
  }
}

// The legend's symbols, centred at the left of the text line.
void pathSymbol(const Eigen::Vector2d& c, double w, int s) {
  segment(c - Eigen::Vector2d(0.5 * w, 0), c + Eigen::Vector2d(0.5 * w, 0), 1.6 * s, keyframeColour());
  for (const double f : {-0.5, 0.0, 0.5}) fillDisc(c + Eigen::Vector2d(f * w, 0), 2.4 * s, keyframeColour());
}

void roomSymbol(const Eigen::Vector2d& c, double w, int s) {
  segment(c, c + Eigen::Vector2d(0.5 * w, 0), 1.0 * s, roomNodeColour());
  fillDisc(c, 4.2 * s, hex(0xffffff));
  fillDisc(c, 3.4 * s, roomNodeColour());
  fillDisc(c, 1.8 * s, hex(0xffffff));
}

}  // namespace

void drawGraphStructure(const SnapshotGraph& graph, const Layout& layout) {
  const int s = layout.text_scale;
  for (const auto& wall : graph.matched_walls) band(wall, layout, 2.0 * s, matchedWallColour());
  for (const auto& plane : graph.new_planes) band(plane, layout, 3.0 * s, newPlaneColour());
  // The topological layer: each room node joined to the walls that constrain it.
  const Colour edge = roomNodeColour();
  for (const auto& room : graph.rooms) {
    if (!finite(room.centre)) continue;
    for (const auto& p : room.wall_points)
      if (finite(p)) segment(layout.toPixel(room.centre), layout.toPixel(p), 1.2 * s, edge);
  }
  for (const auto& room : graph.rooms) {
    if (!finite(room.centre)) continue;
    for (const auto& p : room.wall_points)
      if (finite(p)) fillDisc(layout.toPixel(p), 2.2 * s, edge);
    // A ring: the room's name, drawn next, stays legible inside it.
    fillDisc(layout.toPixel(room.centre), 7.0 * s, hex(0xffffff));
    fillDisc(layout.toPixel(room.centre), 6.0 * s, roomNodeColour());
    fillDisc(layout.toPixel(room.centre), 3.5 * s, hex(0xffffff));
  }
}

void drawKeyframePath(const SnapshotGraph& graph, const Layout& layout) {
  const int s = layout.text_scale;
  Points path;
  for (const auto& k : graph.keyframes)
    if (k.allFinite()) path.push_back(layout.toPixel(k.x(), k.y()));
  // One batch: a ten-minute tour has hundreds of keyframes.
  ShapeBatch batch;
  for (std::size_t i = 0; i + 1 < path.size(); ++i) batch.segment(path[i], path[i + 1], 1.6 * s, keyframeColour());
  for (const auto& p : path) {
    batch.disc(p, 3.2 * s, hex(0xffffff), 16);
    batch.disc(p, 2.4 * s, keyframeColour(), 16);
  }
  batch.draw();
}

void graphLegendSection(Cursor& at, const SnapshotGraph& graph) {
  at.heading("S-Graph");
  const double symbol_w = 22.0 * at.s;
  // `label`, or `short_label` in a narrow column (below the plan, beside four others).
  const auto item = [&](const std::string& label, const std::string& short_label, std::size_t count, auto symbol) {
    symbol(Eigen::Vector2d(at.x + 0.4 * symbol_w, at.y + 0.4 * at.line()), 0.7 * symbol_w, at.s);
    const std::string n = " " + std::to_string(count);
    // Room for three digits whatever the count: the same words in every picture of a run.
    const bool fits = symbol_w + textWidth(label + " 999", at.s) <= at.width;
    at.text((fits ? label : short_label) + n, legendInk(), symbol_w);
    at.y += 0.3 * at.line();
  };
  const auto bar = [](const Colour& colour) {
    return [colour](const Eigen::Vector2d& c, double w, int s) {
      segment(c - Eigen::Vector2d(0.5 * w, 0), c + Eigen::Vector2d(0.5 * w, 0), 3.0 * s, colour);
    };
  };
  item("keyframes", "keyframes", graph.keyframes.size(), pathSymbol);
  item("plan walls", "matched", graph.matched_walls.size(), bar(matchedWallColour()));
  item("new planes", "new planes", graph.new_planes.size(), bar(newPlaneColour()));
  item("rooms", "rooms", graph.rooms.size(), roomSymbol);
}

}  // namespace bimloc::sim::render
