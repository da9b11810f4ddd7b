#include "sim/render/snapshot.hpp"

#include "sim/render/gl_context.hpp"
#include "sim/render/layers.hpp"
#include "sim/render/layout.hpp"
#include "sim/render/png_write.hpp"

#include <stdexcept>

namespace bimloc::sim {

Image renderSnapshotImage(const SnapshotScene& scene, const SnapshotOptions& options) {
  const render::Layout layout = render::computeLayout(scene, options);
  const render::WeightRange range = render::weightRange(scene.particles);
  return render::renderOffscreen(layout.width, layout.height, [&] {
    if (scene.storey) render::drawPlan(*scene.storey, layout);
    if (scene.graph) render::drawGraphStructure(*scene.graph, layout);
    if (scene.storey) render::drawRoomLabels(*scene.storey, layout);
    render::drawParticles(scene.particles, range, layout);
    if (scene.graph) render::drawKeyframePath(*scene.graph, layout);
    render::drawPoses(scene, layout);
    // Header and legend are opaque and come last: they cover whatever strays off the plan.
    render::drawHeader(scene, layout);
    render::drawLegend(scene, range, layout);
  });
}

void renderSnapshot(const SnapshotScene& scene, const std::string& png_path, const SnapshotOptions& options) {
  render::writePng(png_path, [&] { return renderSnapshotImage(scene, options); });
}

Eigen::Vector2d worldToPixel(const SnapshotScene& scene, const SnapshotOptions& options, double x, double y) {
  return render::computeLayout(scene, options).toPixel(x, y);
}

}  // namespace bimloc::sim
