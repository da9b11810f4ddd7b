#include "sim/render/trajectory_plot.hpp"

#include "sim/render/draw.hpp"
#include "sim/render/error_plot.hpp"
#include "sim/render/error_plot_ticks.hpp"
#include "sim/render/font.hpp"
#include "sim/render/gl_context.hpp"
#include "sim/render/legend.hpp"
#include "sim/render/png_write.hpp"
#include "sim/common/atomic_file.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace bimloc::sim {

namespace {

using render::hex;

// The plan box of both paths, grown to the panel's aspect so that a metre is as long in x as
// in y, and a 5% margin around.
struct View {
  double x0, y0, x1, y1;        // panel, pixels
  Eigen::Vector2d min, max;     // world box shown
  double px_per_m = 1;
  Eigen::Vector2d toPixel(const Eigen::Vector2d& p) const {
    return {x0 + (p.x() - min.x()) * px_per_m, y1 - (p.y() - min.y()) * px_per_m};
  }
};

View fit(const TrajectoryPlotData& data, double x0, double y0, double x1, double y1) {
  View v{x0, y0, x1, y1, Eigen::Vector2d::Zero(), Eigen::Vector2d::Ones(), 1};
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(INFINITY), hi = Eigen::Vector2d::Constant(-INFINITY);
  for (const auto* path : {&data.truth, &data.estimate})
    for (const auto& p : *path)
      if (p.allFinite()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  if (!(hi.x() >= lo.x())) lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Ones();
  const Eigen::Vector2d centre = 0.5 * (lo + hi);
  Eigen::Vector2d half = (0.5 * (hi - lo)).cwiseMax(0.5) * 1.05;  // at least a metre across
  const double w = x1 - x0, h = y1 - y0;
  if (half.x() / w > half.y() / h) half.y() = half.x() * h / w; else half.x() = half.y() * w / h;
  v.min = centre - half, v.max = centre + half;
  v.px_per_m = w / (2 * half.x());
  return v;
}

void path(const View& v, const std::vector<Eigen::Vector2d>& points, const render::Colour& colour, double width) {
  render::Points pixels;
  for (const auto& p : points) pixels.push_back(v.toPixel(p));
  if (pixels.size() >= 2) render::strokePolyline(pixels, width, colour, false);
  if (!pixels.empty()) render::fillDisc(pixels.front(), 2.5 * width, colour);  // the start
}

}  // namespace

Image renderTrajectoryViewImage(const TrajectoryPlotData& data, int width, int height) {
  if (width < 160 || height < 160 || width > 16384 || height > 16384)
    throw std::invalid_argument("trajectory plot size " + std::to_string(width) + "x" + std::to_string(height) +
                                " px: each side must be in [160, 16384]");
  const int s = std::max(1, static_cast<int>(std::lround(std::min(width, height) / 450.0)));
  const double pad = 6.0 * s, line = render::kLineHeight * s;
  const auto ink = hex(0x222222), grid = hex(0xdcdcdc), frame = hex(0x555555);
  return render::renderOffscreen(width, height, [&] {
    const double header = render::kLineHeight * (s + 1) + line + 3 * pad;
    const double left = render::textWidth("-0000.0", s) + 3 * pad, bottom = 2 * line + 3 * pad;
    const View v = fit(data, left, header, width - 3 * pad, height - bottom);
    const auto tx = render::niceTicks(v.min.x(), v.max.x(), 9), ty = render::niceTicks(v.min.y(), v.max.y(), 9);
    const double step_x = tx.size() > 1 ? tx[1] - tx[0] : 1, step_y = ty.size() > 1 ? ty[1] - ty[0] : 1;
    for (const double x : tx) {
      const double px = v.toPixel({x, 0}).x();
      render::segment({px, v.y0}, {px, v.y1}, 0.8 * s, grid);
      const std::string label = render::tickLabel(x, step_x);
      render::drawText(px - 0.5 * render::textWidth(label, s), v.y1 + pad, label, s, ink);
    }
    for (const double y : ty) {
      const double py = v.toPixel({0, y}).y();
      render::segment({v.x0, py}, {v.x1, py}, 0.8 * s, grid);
      const std::string label = render::tickLabel(y, step_y);
      render::drawText(v.x0 - pad - render::textWidth(label, s), py - 3.5 * s, label, s, ink);
    }
    const double w = std::max(2.0, 1.4 * s);
    path(v, data.truth, hex(kTrajectoryTruthRgb), 2.5 * w);
    path(v, data.estimate, hex(kTrajectoryEstimateRgb), w);
    render::strokeRect({v.x0, v.y0, v.x1, v.y1}, std::max(1, s / 2 + 1), frame);
    const std::string axis = "x [m] (y [m] up), start: dot";
    render::drawText(0.5 * (v.x0 + v.x1 - render::textWidth(axis, s)), height - pad - line, axis, s, ink);
    render::drawText(v.x0, pad, render::fitText(data.title, s + 1, v.x1 - v.x0), s + 1, ink);
    const double y = 2 * pad + render::kLineHeight * (s + 1);
    render::segment({v.x0, y + 0.4 * line}, {v.x0 + 2 * line, y + 0.4 * line}, 2.5 * w, hex(kTrajectoryTruthRgb));
    render::drawText(v.x0 + 2.5 * line, y, "truth", s, ink);
    const double x = v.x0 + 2.5 * line + render::textWidth("truth", s) + 2 * line;
    render::segment({x, y + 0.4 * line}, {x + 2 * line, y + 0.4 * line}, w, hex(kTrajectoryEstimateRgb));
    render::drawText(x + 2.5 * line, y, "estimate", s, ink);
  });
}

void renderTrajectoryPlot(const TrajectoryPlotData& data, const std::string& png_path, const TrajectoryPlotOptions& options) {
  std::string png;
  try {
    const Image top = renderTrajectoryViewImage(data, options.width_px, options.top_view_height_px);
    ErrorPlotData errors;
    errors.title = "error over time (associated poses)";
    errors.position_label = "APE translation [m]";
    errors.yaw_label = "APE rotation [deg]";
    errors.show_states = false;
    for (std::size_t i = 0; i < data.time_s.size(); ++i)
      errors.samples.push_back({data.time_s[i], data.ape_m[i], data.ape_rotation_deg[i], ErrorPlotState::Tracking});
    const Image bottom = renderErrorPlotImage(errors, {options.width_px, options.error_height_px});
    Image both = top;  // the same width: one under the other
    both.height += bottom.height;
    both.rgb.insert(both.rgb.end(), bottom.rgb.begin(), bottom.rgb.end());
    png = render::encodePng(both);
  } catch (const std::exception& e) {
    throw std::runtime_error(png_path + ": " + e.what());
  }
  writeFileAtomically(png_path, png);
}

}  // namespace bimloc::sim
