// Drawing the error plot: shading, grid, the convergence line, the error curve, then axes,
// labels and the header's legend on top.
#include "sim/render/error_plot.hpp"

#include "sim/render/draw.hpp"
#include "sim/render/error_plot_ticks.hpp"
#include "sim/render/font.hpp"
#include "sim/render/gl_context.hpp"
#include "sim/render/legend.hpp"
#include "sim/render/png_write.hpp"
#include "sim/world/atomic_file.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace bimloc::sim {

namespace {

using render::Colour;
using render::hex;

const Colour kInk = hex(0x222222), kMuted = hex(0x6b6b6b), kFrame = hex(0x555555);
const Colour kGrid = hex(0xc4c4c4), kMinorGrid = hex(0xe4e4e4);

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

void grid(const ErrorPlotPanel& p, const std::vector<double>& time_ticks, double s) {
  for (const double d : render::decades(p.value_min, p.value_max)) {
    for (int m = 2; m <= 9 && d * m < p.value_max * 0.999; ++m) {
      const double y = p.toPixel(p.time_min, d * m).y();
      render::segment({p.x0, y}, {p.x1, y}, 0.6 * s, kMinorGrid);
    }
    const double y = p.toPixel(p.time_min, d).y();
    render::segment({p.x0, y}, {p.x1, y}, 0.8 * s, kGrid);
  }
  for (const double t : time_ticks) {
    const double x = p.toPixel(t, 1).x();
    render::segment({x, p.y0}, {x, p.y1}, 0.8 * s, kGrid);
  }
}

// The curve, broken where a value is not finite (no estimate to compare).
void curve(const ErrorPlotData& data, const ErrorPlotPanel& p, bool yaw, const Colour& colour, double width) {
  render::ShapeBatch batch;
  Eigen::Vector2d prev;
  bool have_prev = false;
  for (const auto& e : data.samples) {
    const Eigen::Vector2d at = p.toPixel(e.time_s, yaw ? e.yaw_deg : e.position_m);
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

void axes(const ErrorPlotPanel& p, const ErrorPlotLayout& l, const std::string& name, const Colour& colour,
          bool time_labels) {
  const int s = l.text_scale;
  const double tick = l.pad, edge = std::max(1, s / 2 + 1), tick_w = std::max(2.0, 1.5 * s);
  render::strokeRect({p.x0 - edge, p.y0 - edge, p.x1 + edge, p.y1 + edge}, edge, kFrame);
  for (const double d : render::decades(p.value_min, p.value_max)) {
    const double y = p.toPixel(p.time_min, d).y();
    render::segment({p.x0 - edge - tick, y}, {p.x0 - edge, y}, tick_w, kFrame);
    const std::string label = render::decadeLabel(d);
    render::drawText(p.x0 - edge - tick - l.pad / 2 - render::textWidth(label, s), y - 3.5 * s, label, s, kInk);
  }
  const double step = l.time_ticks.size() > 1 ? l.time_ticks[1] - l.time_ticks[0] : 1.0;
  for (const double t : l.time_ticks) {
    const double x = p.toPixel(t, 1).x();
    render::segment({x, p.y1 + edge}, {x, p.y1 + edge + tick}, tick_w, kFrame);
    if (!time_labels) continue;
    const std::string label = render::tickLabel(t, step);
    render::drawText(x - 0.5 * render::textWidth(label, s), p.y1 + edge + tick + l.pad / 2, label, s, kInk);
  }
  // The panel's name above it, in the curve's colour: the legend of the curve.
  render::drawText(p.x0, p.y0 - edge - l.pad / 2 - render::kLineHeight * s, name, s, colour);
}

void convergenceLine(const ErrorPlotData& data, const ErrorPlotPanel& p, double s) {
  if (!data.convergence_time_s || !std::isfinite(*data.convergence_time_s)) return;
  const double x = p.toPixel(*data.convergence_time_s, 1).x();
  if (x < p.x0 || x > p.x1) return;
  render::segment({x, p.y0}, {x, p.y1}, 1.5 * s, hex(kErrorPlotConvergenceRgb));
}

// The title, and under it what the vertical line and the shading mean (a row of their own: a
// long scenario name would run into them).
void header(const ErrorPlotData& data, const ErrorPlotLayout& l) {
  const int s = l.text_scale, big = s + 1;
  render::drawText(l.position.x0, l.pad, render::fitText(data.title, big, l.position.x1 - l.position.x0), big, kInk);
  if (!data.show_states) return;
  const double y = l.pad * 2 + render::kLineHeight * big, line = render::kLineHeight * s;
  double x = l.position.x0;
  const auto item = [&](const std::string& label, const auto& symbol) {
    symbol(render::Rect{x, y - 0.5 * s, x + 1.8 * line, y + line - 1.5 * s});
    x += 2.3 * line;
    render::drawText(x, y, label, s, kInk);
    x += render::textWidth(label, s) + 2 * line;
  };
  const std::string converged =
      data.convergence_time_s ? "converged at " + format("%.1f s", *data.convergence_time_s) : "not converged";
  item(converged, [&](const render::Rect& r) {
    if (data.convergence_time_s)
      render::segment({0.5 * (r.x0 + r.x1), r.y0}, {0.5 * (r.x0 + r.x1), r.y1}, 1.5 * s, hex(kErrorPlotConvergenceRgb));
  });
  const auto swatch = [](ErrorPlotState state) {
    return [state](const render::Rect& r) {
      render::fillRect(r, stateColour(state));
      render::strokeRect(r, 1, kGrid);
    };
  };
  item("searching", swatch(ErrorPlotState::Searching));
  item("tracking", swatch(ErrorPlotState::Tracking));
  item("lost", swatch(ErrorPlotState::Lost));
}

}  // namespace

Image renderErrorPlotImage(const ErrorPlotData& data, const ErrorPlotOptions& options) {
  const ErrorPlotLayout l = errorPlotLayout(data, options);
  const double s = l.text_scale;
  return render::renderOffscreen(l.width, l.height, [&] {
    for (const ErrorPlotPanel* p : {&l.position, &l.yaw}) {
      if (data.show_states) shadeStates(data, *p);
      grid(*p, l.time_ticks, s);
      convergenceLine(data, *p, s);
    }
    // At least two pixels: the pixel under a point of the curve is wholly its colour.
    const double width = std::max(2.0, 1.4 * s);
    curve(data, l.position, false, hex(kErrorPlotPositionRgb), width);
    curve(data, l.yaw, true, hex(kErrorPlotYawRgb), width);
    // A curve's end may poke over its panel's edge: the margins are painted after it.
    render::fillRect({0, 0, static_cast<double>(l.width), l.position.y0 - 1}, hex(0xffffff));
    render::fillRect({0, l.position.y1 + 1, static_cast<double>(l.width), l.yaw.y0 - 1}, hex(0xffffff));
    render::fillRect({0, l.yaw.y1 + 1, static_cast<double>(l.width), static_cast<double>(l.height)}, hex(0xffffff));
    axes(l.position, l, data.position_label + ", log scale", hex(kErrorPlotPositionRgb), false);
    axes(l.yaw, l, data.yaw_label + ", log scale", hex(kErrorPlotYawRgb), true);
    const std::string time = "time [s]";
    render::drawText(0.5 * (l.yaw.x0 + l.yaw.x1 - render::textWidth(time, l.text_scale)),
                     l.height - l.pad - render::kLineHeight * s, time, l.text_scale, kInk);
    header(data, l);
  });
}

void renderErrorPlot(const ErrorPlotData& data, const std::string& png_path, const ErrorPlotOptions& options) {
  std::string png;
  try {
    png = render::encodePng(renderErrorPlotImage(data, options));
  } catch (const std::exception& e) {
    throw std::runtime_error(png_path + ": " + e.what());
  }
  writeFileAtomically(png_path, png);  // names the path itself, and leaves no file on failure
}

}  // namespace bimloc::sim
