// The layers of a snapshot, painted back to front: plan, the S-Graph's walls and rooms, room
// names, particles, its keyframe path, poses, header, legend.
#pragma once

#include "sim/render/draw.hpp"
#include "sim/render/layout.hpp"
#include "sim/render/snapshot.hpp"

#include <cstddef>

namespace bimloc::sim::render {

// The colours shared by the map and its legend.
inline Colour truthColour() { return hex(0x1a9641); }
inline Colour estimateColour() { return hex(0xd7191c); }
inline Colour wallColour() { return hex(0x2b2b2b); }
// The S-Graph's layers: none of them a colour of the particles' viridis ramp at its ends.
inline Colour keyframeColour() { return hex(0x2166ac); }
inline Colour matchedWallColour() { return hex(0xc51b7d); }
inline Colour newPlaneColour() { return hex(0xf28e2b); }
inline Colour roomNodeColour() { return hex(0x6a3d9a); }

// Weights are coloured relative to the snapshot's own lightest and heaviest particle: the
// filter's weights are unnormalised likelihoods whose absolute scale means nothing.
struct WeightRange {
  double lo = 0, hi = 0;
  std::size_t count = 0;  // particles with a finite weight
  double normalise(double w) const { return hi > lo ? (w - lo) / (hi - lo) : 1.0; }
};
WeightRange weightRange(const std::vector<SnapshotParticle>& particles);

void drawPlan(const bim::Storey& storey, const Layout& layout);  // floors and walls
// The rooms' names, after the graph's room nodes (drawn as rings, so a name stays legible).
void drawRoomLabels(const bim::Storey& storey, const Layout& layout);
void drawParticles(const std::vector<SnapshotParticle>& particles, const WeightRange& range, const Layout& layout);
// A pose marker: a dot at the position and an arrow along the heading (`dir`, pixels).
void drawPoseMarker(const Eigen::Vector2d& pixel, const Eigen::Vector2d& dir, const Colour& colour, int scale);
// Walls, new planes and rooms go under the particles; the keyframe path over them (the
// converged cloud sits on the robot, where the path ends).
void drawGraphStructure(const SnapshotGraph& graph, const Layout& layout);
void drawKeyframePath(const SnapshotGraph& graph, const Layout& layout);
void drawPoses(const SnapshotScene& scene, const Layout& layout);
void drawHeader(const SnapshotScene& scene, const Layout& layout);
struct Cursor;
void graphLegendSection(Cursor& at, const SnapshotGraph& graph);
void drawLegend(const SnapshotScene& scene, const WeightRange& range, const Layout& layout);

}  // namespace bimloc::sim::render
