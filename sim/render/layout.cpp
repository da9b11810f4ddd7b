#include "sim/render/layout.hpp"

#include "sim/render/font.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace bimloc::sim::render {

namespace {

constexpr int kMinSidePx = 64;
constexpr int kMaxSidePx = 16384;  // OSMesa's largest viewport
constexpr int kPanelChars = 21;    // legend panel width (beside the plan), in characters
constexpr double kPanelLines = 7.5;  // legend panel height (below the plan), in text lines

struct Box {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector2d hi = -lo;
  void add(double x, double y) {
    if (!std::isfinite(x) || !std::isfinite(y)) return;
    lo = lo.cwiseMin(Eigen::Vector2d(x, y));
    hi = hi.cwiseMax(Eigen::Vector2d(x, y));
  }
  bool empty() const { return !(lo.x() <= hi.x()); }
};

// The storey's rooms and walls; without them (no storey, or a mesh-only world) whatever the
// scene shows (particles, poses, keyframes), so a snapshot of the filter alone still frames
// its particles.
Box contentBox(const SnapshotScene& scene) {
  Box box;
  if (scene.storey) {
    for (const auto& room : scene.storey->rooms)
      for (const auto& p : room.footprint) box.add(p.x(), p.y());
    for (const auto& wall : scene.storey->walls)
      for (const auto& face : wall.faces) {
        box.add(face.start.x(), face.start.y());
        box.add(face.end.x(), face.end.y());
      }
  }
  if (box.empty()) {
    for (const auto& p : scene.particles) box.add(p.x, p.y);
    if (scene.truth) box.add(scene.truth->x(), scene.truth->y());
    if (scene.estimate) box.add(scene.estimate->x(), scene.estimate->y());
    if (scene.graph)
      for (const auto& k : scene.graph->keyframes) box.add(k.x(), k.y());
  }
  if (box.empty()) box.add(0, 0);
  return box;
}

}  // namespace

Layout computeLayout(const SnapshotScene& scene, const SnapshotOptions& options) {
  for (const int side : {options.width_px, options.height_px})
    if (side < kMinSidePx || side > kMaxSidePx)
      throw std::invalid_argument("snapshot size " + std::to_string(options.width_px) + "x" +
                                  std::to_string(options.height_px) + " px: each side must be in [" +
                                  std::to_string(kMinSidePx) + ", " + std::to_string(kMaxSidePx) + "]");
  if (!std::isfinite(options.margin_m) || options.margin_m < 0)
    throw std::invalid_argument("snapshot margin must be finite and >= 0, got " + std::to_string(options.margin_m));

  Layout l;
  l.width = options.width_px;
  l.height = options.height_px;
  // Text grows with the image so a large figure stays legible when scaled down on a page.
  l.text_scale = std::max(1, static_cast<int>(std::lround(std::min(l.width, l.height) / 450.0)));
  l.pad = 6 * l.text_scale;
  const double w = l.width, h = l.height;
  const double header_h = kLineHeight * (l.text_scale + 1) + 2 * l.pad;
  l.header = {0, 0, w, header_h};

  const Box box = contentBox(scene);
  l.world_min = box.lo - Eigen::Vector2d::Constant(options.margin_m);
  l.world_max = box.hi + Eigen::Vector2d::Constant(options.margin_m);
  // A single point with no margin would give an empty box: keep at least a metre.
  const Eigen::Vector2d size = (l.world_max - l.world_min).cwiseMax(1.0);
  const Eigen::Vector2d centre = 0.5 * (l.world_min + l.world_max);
  l.world_min = centre - 0.5 * size;
  l.world_max = centre + 0.5 * size;
  const auto fit = [&](const Rect& plan) { return std::min(plan.width() / size.x(), plan.height() / size.y()); };

  const double panel_w = std::min(0.35 * w, static_cast<double>(kPanelChars * kAdvance * l.text_scale + 3 * l.pad));
  const Rect plan_beside{0, header_h, w - panel_w, h};
  const double panel_h = std::min(0.4 * h, (kPanelLines * kLineHeight + 2.0) * l.text_scale + 4 * l.pad);
  const Rect plan_above{0, header_h, w, h - panel_h};
  // Beside unless below is clearly better (a wide plan in a tall image).
  l.legend_below = fit(plan_above) > 1.1 * fit(plan_beside);
  l.plan = l.legend_below ? plan_above : plan_beside;
  l.panel = l.legend_below ? Rect{0, h - panel_h, w, h} : Rect{w - panel_w, header_h, w, h};
  l.px_per_m = fit(l.plan);
  l.origin = {l.plan.x0 + 0.5 * (l.plan.width() - size.x() * l.px_per_m),
              l.plan.y0 + 0.5 * (l.plan.height() - size.y() * l.px_per_m)};
  if (l.legend_below) {  // the legend right under the plan, the two centred together
    const double slack = 0.5 * (l.plan.height() - size.y() * l.px_per_m);
    l.plan.y1 -= slack;
    l.panel.y0 -= slack;
    l.panel.y1 -= slack;
  }
  return l;
}

}  // namespace bimloc::sim::render
