#include "sim/render/layers.hpp"

#include "sim/render/colormap.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace bimloc::sim::render {

namespace {

bool finite(const SnapshotParticle& p) {
  return std::isfinite(p.x) && std::isfinite(p.y) && std::isfinite(p.yaw) && std::isfinite(p.weight);
}

// World yaw (counter-clockwise from x) as a pixel direction: the image's y axis points down.
Eigen::Vector2d pixelDirection(double yaw) { return {std::cos(yaw), -std::sin(yaw)}; }

}  // namespace

WeightRange weightRange(const std::vector<SnapshotParticle>& particles) {
  WeightRange range;
  for (const auto& p : particles) {
    if (!finite(p)) continue;
    range.lo = range.count ? std::min(range.lo, p.weight) : p.weight;
    range.hi = range.count ? std::max(range.hi, p.weight) : p.weight;
    ++range.count;
  }
  return range;
}

void drawParticles(const std::vector<SnapshotParticle>& particles, const WeightRange& range, const Layout& layout) {
  // Heaviest last, so the particles that matter are on top of the cloud.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < particles.size(); ++i)
    if (finite(particles[i])) order.push_back(i);
  std::stable_sort(order.begin(), order.end(),
                   [&](std::size_t a, std::size_t b) { return particles[a].weight < particles[b].weight; });
  // About 12 cm across on the plan, but never a speck nor a blot whatever the zoom.
  const double r = std::clamp(0.06 * layout.px_per_m, 1.6, 2.2 * layout.text_scale);
  const double edge = std::max(0.6, 0.25 * r);
  const Colour outline = hex(0x1e1e1e, 0.6f);
  // Enough segments for a round dot at the supersampled size, no more: there may be many.
  const int segments = std::clamp(static_cast<int>(4 * r), 8, 24);
  ShapeBatch batch;
  for (const std::size_t i : order) {
    const SnapshotParticle& p = particles[i];
    const Colour fill = fromBytes(viridis(range.normalise(p.weight)));
    const Eigen::Vector2d c = layout.toPixel(p.x, p.y);
    const Eigen::Vector2d tip = c + pixelDirection(p.yaw) * (3.2 * r);
    batch.segment(c, tip, 0.9 * r + 2 * edge, outline);
    batch.segment(c, tip, 0.9 * r, fill);
    batch.disc(c, r + edge, outline, segments);
    batch.disc(c, r, fill, segments);
  }
  batch.draw();
}

void drawPoseMarker(const Eigen::Vector2d& pixel, const Eigen::Vector2d& dir, const Colour& colour, int scale) {
  const Colour white = hex(0xffffff);
  drawArrow(pixel, dir, 15.0 * scale, 2.6 * scale, colour, white, 1.0 * scale);
  fillDisc(pixel, 3.8 * scale, white);
  fillDisc(pixel, 2.8 * scale, colour);
}

void drawPoses(const SnapshotScene& scene, const Layout& layout) {
  // The estimate under the truth: when the filter has converged, the truth stays visible.
  if (scene.estimate && scene.estimate->allFinite())
    drawPoseMarker(layout.toPixel(scene.estimate->x(), scene.estimate->y()), pixelDirection(scene.estimate->z()),
                   estimateColour(), layout.text_scale);
  if (scene.truth && scene.truth->allFinite())
    drawPoseMarker(layout.toPixel(scene.truth->x(), scene.truth->y()), pixelDirection(scene.truth->z()),
                   truthColour(), layout.text_scale);
}

}  // namespace bimloc::sim::render
