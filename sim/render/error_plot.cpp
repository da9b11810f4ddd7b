// Drawing the error plot: shading, grid, the convergence line, the error curve, then axes,
// labels and the header's legend on top.
#include "sim/render/error_plot.hpp"

#include "sim/render/draw.hpp"
#include "sim/render/error_plot_axes.hpp"
#include "sim/render/error_plot_ticks.hpp"
#include "sim/render/font.hpp"
#include "sim/render/gl_context.hpp"
#include "sim/render/legend.hpp"
#include "sim/render/png_write.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace bimloc::sim {

namespace {

using render::Colour;
using render::hex;

const Colour kInk = render::plotInk(), kGrid = render::plotGrid();

Colour stateColour(ErrorPlotState s) {
  return hex(s == ErrorPlotState::Searching ? kErrorPlotSearchingRgb
             : s == ErrorPlotState::Lost    ? kErrorPlotLostRgb
                                            : kErrorPlotTrackingRgb);
}

std::string format(const char* fmt, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, value);
  return buf;
}

// Each sample's state holds from its time to the next sample's (the last: to the axis end).
void shadeStates(const ErrorPlotData& data, const ErrorPlotPanel& p) {
  for (std::size_t i = 0; i < data.samples.size(); ++i) {
    const double t0 = data.samples[i].time_s;
    const double t1 = i + 1 < data.samples.size() ? data.samples[i + 1].time_s : p.time_max;
    if (!std::isfinite(t0) || !std::isfinite(t1) || t1 <= t0) continue;
    const double a = std::max(p.x0, p.toPixel(t0, 1).x()), b = std::min(p.x1, p.toPixel(t1, 1).x());
    if (b > a) render::fillRect({a, p.y0, b, p.y1}, stateColour(data.samples[i].state));
  }
}

// The curve of the position or yaw error.
void curve(const ErrorPlotData& data, const ErrorPlotPanel& p, bool yaw, const Colour& colour, double width) {
  std::vector<std::pair<double, double>> samples;
  for (const auto& e : data.samples) samples.emplace_back(e.time_s, yaw ? e.yaw_deg : e.position_m);
  render::panelCurve(p, samples, colour, width);
}

void convergenceLine(const ErrorPlotData& data, const ErrorPlotPanel& p, double s) {
  if (!data.convergence_time_s || !std::isfinite(*data.convergence_time_s)) return;
  const double x = p.toPixel(*data.convergence_time_s, 1).x();
  if (x < p.x0 || x > p.x1) return;
  render::segment({x, p.y0}, {x, p.y1}, 1.5 * s, hex(kErrorPlotConvergenceRgb));
}

// A dashed vertical line at each change of storey.
void storeyChangeLines(const ErrorPlotData& data, const ErrorPlotPanel& p, double s) {
  for (const double t : data.storey_change_times_s) {
    if (!std::isfinite(t)) continue;
    const double x = p.toPixel(t, 1).x();
    if (x < p.x0 || x > p.x1) continue;
    const double dash = 6 * s;
    for (double y = p.y0; y < p.y1; y += 2 * dash)
      render::segment({x, y}, {x, std::min(p.y1, y + dash)}, 1.5 * s, hex(kErrorPlotStoreyChangeRgb));
  }
}

// The title, and under it what the vertical line and the shading mean (a row of their own: a
// long scenario name would run into them).
void header(const ErrorPlotData& data, const ErrorPlotLayout& l) {
  const int s = l.text_scale, big = s + 1;
  render::drawText(l.position.x0, l.pad, render::fitText(data.title, big, l.position.x1 - l.position.x0), big, kInk);
  if (!data.show_states) return;
  const double y = l.pad * 2 + render::kLineHeight * big;
  std::vector<render::KeyItem> items;
  const std::string converged =
      data.convergence_time_s ? "converged at " + format("%.1f s", *data.convergence_time_s) : "not converged";
  items.push_back({converged, [&](const render::Rect& r) {
                     if (data.convergence_time_s)
                       render::segment({0.5 * (r.x0 + r.x1), r.y0}, {0.5 * (r.x0 + r.x1), r.y1}, 1.5 * s,
                                       hex(kErrorPlotConvergenceRgb));
                   }});
  const auto swatch = [](ErrorPlotState state) {
    return [state](const render::Rect& r) {
      render::fillRect(r, stateColour(state));
      render::strokeRect(r, 1, kGrid);
    };
  };
  if (!data.storey_change_times_s.empty())
    items.push_back({"storey change", [&](const render::Rect& r) {
                       const double x = 0.5 * (r.x0 + r.x1), mid = 0.5 * (r.y0 + r.y1);
                       render::segment({x, r.y0}, {x, mid - 1}, 1.5 * s, hex(kErrorPlotStoreyChangeRgb));
                       render::segment({x, mid + 2}, {x, r.y1}, 1.5 * s, hex(kErrorPlotStoreyChangeRgb));
                     }});
  items.push_back({"searching", swatch(ErrorPlotState::Searching)});
  items.push_back({"tracking", swatch(ErrorPlotState::Tracking)});
  items.push_back({"lost", swatch(ErrorPlotState::Lost)});
  // One row: the layout leaves room for one, and a plot is wide enough for these four.
  render::plotKey(items, l.position.x0, 1e9, y, s, true);
}

}  // namespace

Image renderErrorPlotImage(const ErrorPlotData& data, const ErrorPlotOptions& options) {
  const ErrorPlotLayout l = errorPlotLayout(data, options);
  const double s = l.text_scale;
  return render::renderOffscreen(l.width, l.height, [&] {
    for (const ErrorPlotPanel* p : {&l.position, &l.yaw}) {
      if (data.show_states) shadeStates(data, *p);
      render::panelGrid(*p, l.time_ticks, s);
      convergenceLine(data, *p, s);
      storeyChangeLines(data, *p, s);
    }
    // At least two pixels: the pixel under a point of the curve is wholly its colour.
    const double width = std::max(2.0, 1.4 * s);
    curve(data, l.position, false, hex(kErrorPlotPositionRgb), width);
    curve(data, l.yaw, true, hex(kErrorPlotYawRgb), width);
    // A curve's end may poke over its panel's edge: the margins are painted after it.
    render::fillRect({0, 0, static_cast<double>(l.width), l.position.y0 - 1}, hex(0xffffff));
    render::fillRect({0, l.position.y1 + 1, static_cast<double>(l.width), l.yaw.y0 - 1}, hex(0xffffff));
    render::fillRect({0, l.yaw.y1 + 1, static_cast<double>(l.width), static_cast<double>(l.height)}, hex(0xffffff));
    const render::AxisStyle style{l.text_scale, l.pad, l.time_ticks};
    render::panelAxes(l.position, style, data.position_label + ", log scale", hex(kErrorPlotPositionRgb), false);
    render::panelAxes(l.yaw, style, data.yaw_label + ", log scale", hex(kErrorPlotYawRgb), true);
    const std::string time = "time [s]";
    render::drawText(0.5 * (l.yaw.x0 + l.yaw.x1 - render::textWidth(time, l.text_scale)),
                     l.height - l.pad - render::kLineHeight * s, time, l.text_scale, kInk);
    header(data, l);
  });
}

void renderErrorPlot(const ErrorPlotData& data, const std::string& png_path, const ErrorPlotOptions& options) {
  render::writePng(png_path, [&] { return renderErrorPlotImage(data, options); });
}

}  // namespace bimloc::sim
