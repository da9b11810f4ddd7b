// The layers of a snapshot, painted back to front: plan, particles, poses, header, legend.
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

// Weights are coloured relative to the snapshot's own lightest and heaviest particle: the
// filter's weights are unnormalised likelihoods whose absolute scale means nothing.
struct WeightRange {
  double lo = 0, hi = 0;
  std::size_t count = 0;  // particles with a finite weight
  double normalise(double w) const { return hi > lo ? (w - lo) / (hi - lo) : 1.0; }
};
WeightRange weightRange(const std::vector<SnapshotParticle>& particles);

void drawPlan(const bim::Storey& storey, const Layout& layout);
void drawParticles(const std::vector<SnapshotParticle>& particles, const WeightRange& range, const Layout& layout);
// A pose marker: a dot at the position and an arrow along the heading (`dir`, pixels).
void drawPoseMarker(const Eigen::Vector2d& pixel, const Eigen::Vector2d& dir, const Colour& colour, int scale);
void drawPoses(const SnapshotScene& scene, const Layout& layout);
void drawHeader(const SnapshotScene& scene, const Layout& layout);
void drawLegend(const SnapshotScene& scene, const WeightRange& range, const Layout& layout);

}  // namespace bimloc::sim::render
