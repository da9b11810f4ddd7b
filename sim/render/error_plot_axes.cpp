#include "sim/render/error_plot_axes.hpp"

#include "sim/render/error_plot_ticks.hpp"
#include "sim/render/font.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace bimloc::sim::render {

int plotTextScale(int width_px, int height_px) {
  constexpr int kMinSidePx = 160, kMaxSidePx = 16384;  // room for the labels; a sane canvas
  for (const int side : {width_px, height_px})
    if (side < kMinSidePx || side > kMaxSidePx)
      throw std::invalid_argument("plot size " + std::to_string(width_px) + "x" + std::to_string(height_px) +
                                  " px: each side must be in [" + std::to_string(kMinSidePx) + ", " +
                                  std::to_string(kMaxSidePx) + "]");
  return std::max(1, static_cast<int>(std::lround(std::min(width_px, height_px) / 450.0)));
}

void panelGrid(const ErrorPlotPanel& p, const std::vector<double>& time_ticks, double s) {
  for (const double d : decades(p.value_min, p.value_max)) {
    for (int m = 2; m <= 9 && d * m < p.value_max * 0.999; ++m) {
      const double y = p.toPixel(p.time_min, d * m).y();
      segment({p.x0, y}, {p.x1, y}, 0.6 * s, plotMinorGrid());
    }
    const double y = p.toPixel(p.time_min, d).y();
    segment({p.x0, y}, {p.x1, y}, 0.8 * s, plotGrid());
  }
  for (const double t : time_ticks) {
    const double x = p.toPixel(t, 1).x();
    segment({x, p.y0}, {x, p.y1}, 0.8 * s, plotGrid());
  }
}

void panelAxes(const ErrorPlotPanel& p, const AxisStyle& l, const std::string& name, const Colour& colour, bool time_labels) {
  const int s = l.text_scale;
  const double tick = l.pad, edge = std::max(1, s / 2 + 1), tick_w = std::max(2.0, 1.5 * s);
  strokeRect({p.x0 - edge, p.y0 - edge, p.x1 + edge, p.y1 + edge}, edge, plotFrame());
  for (const double d : decades(p.value_min, p.value_max)) {
    const double y = p.toPixel(p.time_min, d).y();
    segment({p.x0 - edge - tick, y}, {p.x0 - edge, y}, tick_w, plotFrame());
    const std::string label = decadeLabel(d);
    drawText(p.x0 - edge - tick - l.pad / 2 - textWidth(label, s), y - 3.5 * s, label, s, plotInk());
  }
  const double step = l.time_ticks.size() > 1 ? l.time_ticks[1] - l.time_ticks[0] : 1.0;
  for (const double t : l.time_ticks) {
    const double x = p.toPixel(t, 1).x();
    segment({x, p.y1 + edge}, {x, p.y1 + edge + tick}, tick_w, plotFrame());
    if (!time_labels) continue;
    const std::string label = tickLabel(t, step);
    drawText(x - 0.5 * textWidth(label, s), p.y1 + edge + tick + l.pad / 2, label, s, plotInk());
  }
  drawText(p.x0, p.y0 - edge - l.pad / 2 - kLineHeight * s, name, s, colour);
}

void panelCurve(const ErrorPlotPanel& p, const std::vector<std::pair<double, double>>& samples, const Colour& colour,
                double width) {
  ShapeBatch batch;
  Eigen::Vector2d prev;
  bool have_prev = false;
  for (const auto& [t, value] : samples) {
    const Eigen::Vector2d at = p.toPixel(t, value);
    if (!at.allFinite()) {
      have_prev = false;
      continue;
    }
    if (have_prev) batch.segment(prev, at, width, colour);
    batch.disc(at, 0.5 * width, colour, 8);  // round joins at the steps
    prev = at;
    have_prev = true;
  }
  batch.draw();
}

double plotKey(const std::vector<KeyItem>& items, double x0, double x1, double y, int s, bool draw) {
  const double line = kLineHeight * s;
  double x = x0, top = y;
  for (const auto& item : items) {
    const double width = 2.3 * line + textWidth(item.label, s);
    if (x > x0 && x + width > x1) x = x0, y += line + 0.5 * line;  // a new row
    if (draw) {
      item.symbol(Rect{x, y - 0.5 * s, x + 1.8 * line, y + line - 1.5 * s});
      drawText(x + 2.3 * line, y, item.label, s, plotInk());
    }
    x += width + 2 * line;
  }
  return y + line - top;
}

}  // namespace bimloc::sim::render
