// Where the error plot's panels go and how they map time and error to pixels.
#include "sim/render/error_plot.hpp"

#include "sim/render/error_plot_ticks.hpp"
#include "sim/render/font.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace bimloc::sim {

namespace {

constexpr int kMinSidePx = 160;  // room for two panels and their labels
constexpr int kMaxSidePx = 16384;

}  // namespace

Eigen::Vector2d ErrorPlotPanel::toPixel(double time_s, double value) const {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  if (!std::isfinite(time_s) || std::isnan(value)) return {nan, nan};
  const double v = std::clamp(value, value_min, value_max);
  const double fx = (time_s - time_min) / (time_max - time_min);
  const double fy = std::log10(v / value_min) / std::log10(value_max / value_min);
  return {x0 + fx * (x1 - x0), y1 - fy * (y1 - y0)};
}

ErrorPlotLayout errorPlotLayout(const ErrorPlotData& data, const ErrorPlotOptions& options) {
  for (const int side : {options.width_px, options.height_px})
    if (side < kMinSidePx || side > kMaxSidePx)
      throw std::invalid_argument("error plot size " + std::to_string(options.width_px) + "x" +
                                  std::to_string(options.height_px) + " px: each side must be in [" +
                                  std::to_string(kMinSidePx) + ", " + std::to_string(kMaxSidePx) + "]");
  ErrorPlotLayout l;
  l.width = options.width_px;
  l.height = options.height_px;
  l.text_scale = std::max(1, static_cast<int>(std::lround(std::min(l.width, l.height) / 450.0)));
  const int s = l.text_scale;
  l.pad = 6.0 * s;
  const double line = render::kLineHeight * s;

  double t_min = 0, t_max = 0;
  std::vector<double> position, yaw;
  for (const auto& e : data.samples) {
    if (std::isfinite(e.time_s)) t_min = std::min(t_min, e.time_s), t_max = std::max(t_max, e.time_s);
    position.push_back(e.position_m);
    yaw.push_back(e.yaw_deg);
  }
  if (t_max <= t_min) t_max = t_min + 1;
  l.time_ticks = render::niceTicks(t_min, t_max, 9);

  ErrorPlotPanel p;
  p.time_min = t_min;
  p.time_max = t_max;
  l.position = l.yaw = p;
  render::logDecadeRange(position, 1e-3, 1e3, l.position.value_min, l.position.value_max);
  render::logDecadeRange(yaw, 1e-2, 1e3, l.yaw.value_min, l.yaw.value_max);

  // Left: the widest decade label and its tick; top: the header; above each panel its name;
  // below the lower one the time labels and the axis name.
  int label_w = 0;
  for (const ErrorPlotPanel* panel : {&l.position, &l.yaw})
    for (const double v : render::decades(panel->value_min, panel->value_max))
      label_w = std::max(label_w, render::textWidth(render::decadeLabel(v), s));
  const double left = label_w + 3 * l.pad, right = l.width - 3 * l.pad;
  const double header = render::kLineHeight * (s + 1) + line + 3 * l.pad;  // title, then the key to the shading
  const double name = line + l.pad;  // a panel's name above it
  const double bottom = 2 * line + 3 * l.pad;
  const double panel_h = std::max(8.0, (l.height - header - 2 * name - 2 * l.pad - bottom) / 2);
  l.position.x0 = l.yaw.x0 = left;
  l.position.x1 = l.yaw.x1 = std::max(left + 8, right);
  l.position.y0 = header + name;
  l.position.y1 = l.position.y0 + panel_h;
  l.yaw.y0 = l.position.y1 + 2 * l.pad + name;
  l.yaw.y1 = l.yaw.y0 + panel_h;
  return l;
}

}  // namespace bimloc::sim
