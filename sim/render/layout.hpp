// Where things go in a snapshot: a header strip (title, phase, time) on top, a legend panel
// on the right or along the bottom (whichever leaves the plan larger), and the plan fitted
// into the rest with equal aspect.
#pragma once

#include "sim/render/snapshot.hpp"

#include <Eigen/Core>

namespace bimloc::sim::render {

struct Rect {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // pixels, y down
  double width() const { return x1 - x0; }
  double height() const { return y1 - y0; }
};

struct Layout {
  int width = 0, height = 0;
  int text_scale = 1;  // font pixels per glyph pixel for ordinary text
  int pad = 6;         // spacing unit, pixels
  Rect header, plan, panel;
  bool legend_below = false;  // panel along the bottom, sections side by side
  Eigen::Vector2d world_min = Eigen::Vector2d::Zero();  // the fitted box, margin included
  Eigen::Vector2d world_max = Eigen::Vector2d::Ones();
  double px_per_m = 1.0;
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();  // pixel of (world_min.x, world_max.y)

  Eigen::Vector2d toPixel(double x, double y) const {
    return {origin.x() + (x - world_min.x()) * px_per_m, origin.y() + (world_max.y() - y) * px_per_m};
  }
  Eigen::Vector2d toPixel(const Eigen::Vector2d& p) const { return toPixel(p.x(), p.y()); }
};

// Throws std::invalid_argument for a size or margin out of range.
Layout computeLayout(const SnapshotScene& scene, const SnapshotOptions& options);

}  // namespace bimloc::sim::render
