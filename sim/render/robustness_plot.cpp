#include "sim/render/robustness_plot.hpp"

#include "sim/render/draw.hpp"
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

using render::Colour;
using render::hex;

const Colour kInk = hex(0x222222), kFrame = hex(0x555555), kGrid = hex(0xd4d4d4);

struct Panel {
  double x0, y0, x1, y1, lo, hi;
  std::size_t levels;
  double x(std::size_t level) const {
    return levels < 2 ? 0.5 * (x0 + x1) : x0 + (x1 - x0) * (0.05 + 0.9 * double(level) / double(levels - 1));
  }
  double y(double v) const { return y1 - (y1 - y0) * (std::clamp(v, lo, hi) - lo) / (hi - lo); }
};

void panel(const Panel& p, const std::string& name, const std::vector<double>& ticks, int s, double pad) {
  for (const double t : ticks) {
    render::segment({p.x0, p.y(t)}, {p.x1, p.y(t)}, 0.8 * s, kGrid);
    const std::string label = render::tickLabel(t, ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0);
    render::drawText(p.x0 - pad - render::textWidth(label, s), p.y(t) - 3.5 * s, label, s, kInk);
  }
  render::strokeRect({p.x0 - 1, p.y0 - 1, p.x1 + 1, p.y1 + 1}, std::max(1, s / 2 + 1), kFrame);
  render::drawText(p.x0, p.y0 - pad - render::kLineHeight * s, name, s, kInk);
}

void line(const Panel& p, const std::vector<double>& values, const Colour& colour, double width) {
  bool have = false;
  Eigen::Vector2d prev;
  for (std::size_t i = 0; i < values.size(); ++i) {
    if (!std::isfinite(values[i])) {
      have = false;
      continue;
    }
    const Eigen::Vector2d at(p.x(i), p.y(values[i]));
    if (have) render::segment(prev, at, width, colour);
    render::fillDisc(at, 0.5 * width + 3.0, colour);
    prev = at, have = true;
  }
}

}  // namespace

std::uint32_t robustnessColour(std::size_t index) {
  static const std::uint32_t palette[] = {0x0072b2, 0xd55e00, 0x009e73, 0xcc79a7, 0xe69f00, 0x56b4e9, 0x000000};
  return palette[index % (sizeof palette / sizeof palette[0])];
}

Image renderRobustnessPlotImage(const RobustnessPlotData& d) {
  if (d.width_px < 300 || d.height_px < 200 || d.width_px > 8000 || d.height_px > 8000)
    throw std::invalid_argument("robustness plot: size out of range (300..8000 x 200..8000 px)");
  const int s = std::max(1, d.height_px / 400);
  const double pad = 6.0 * s, line_h = render::kLineHeight * s;
  double ate_max = 0.1;
  for (const auto& series : d.series)
    for (const double a : series.ate_m)
      if (std::isfinite(a)) ate_max = std::max(ate_max, a);
  const std::vector<double> ate_ticks = render::niceTicks(0.0, ate_max * 1.1, 5);
  const double ate_hi = std::max(ate_max * 1.1, ate_ticks.empty() ? 0.1 : ate_ticks.back());
  const double left = 8.0 * pad + render::textWidth("0.00", s), right = d.width_px - 2.0 * pad;
  const double top = 4.0 * pad + 2.0 * line_h + line_h * 2.0;  // title, legend, panel name
  const double bottom = d.height_px - 3.0 * pad - 2.0 * line_h;  // level labels, axis name
  const double gap = 2.5 * line_h, h = 0.5 * (bottom - top - gap);
  const Panel rate{left, top, right, top + h, 0.0, 1.0, d.levels.size()};
  const Panel ate{left, top + h + gap, right, bottom, 0.0, ate_hi, d.levels.size()};
  return render::renderOffscreen(d.width_px, d.height_px, [&] {
    panel(rate, "localization rate", render::niceTicks(0.0, 1.0, 5), s, pad);
    panel(ate, "median ATE [m]", ate_ticks, s, pad);
    const double width = std::max(2.0, 1.4 * s);
    // Methods often agree (the same rate): each later line thinner, so a line under another
    // still shows at its edges.
    const std::size_t n = d.series.size();
    for (std::size_t m = 0; m < n; ++m) {
      const double w = width * (1.0 + 1.5 * double(n - 1 - m));
      line(rate, d.series[m].rate, hex(robustnessColour(m)), w);
      line(ate, d.series[m].ate_m, hex(robustnessColour(m)), w);
    }
    for (std::size_t i = 0; i < d.levels.size(); ++i) {
      const double w = render::textWidth(d.levels[i], s);
      const double x = std::clamp(ate.x(i) - 0.5 * w, 0.0, d.width_px - pad - w);  // the end labels stay whole
      render::drawText(x, bottom + pad, d.levels[i], s, kInk);
    }
    const std::string axis = "site (deviation level: walls' max. offset)";
    render::drawText(0.5 * (left + right - render::textWidth(axis, s)), d.height_px - pad - line_h, axis, s, kInk);
    render::drawText(left, pad, render::fitText(d.title, s + 1, right - left), s + 1, kInk);
    double x = left;
    const double y = 2.0 * pad + render::kLineHeight * (s + 1);
    for (std::size_t m = 0; m < d.series.size(); ++m) {
      render::segment({x, y + 0.4 * line_h}, {x + 1.8 * line_h, y + 0.4 * line_h}, width, hex(robustnessColour(m)));
      x += 2.3 * line_h;
      render::drawText(x, y, d.series[m].method, s, kInk);
      x += render::textWidth(d.series[m].method, s) + 2.0 * line_h;
    }
  });
}

void renderRobustnessPlot(const RobustnessPlotData& data, const std::string& png_path) {
  std::string png;
  try {
    png = render::encodePng(renderRobustnessPlotImage(data));
  } catch (const std::exception& e) {
    throw std::runtime_error(png_path + ": " + e.what());
  }
  writeFileAtomically(png_path, png);
}

}  // namespace bimloc::sim
