// Several curves over time on one logarithmic panel (the position error of each method):
// the error plot's axes and look, one colour per curve, named in the key above.
#include "sim/render/compare_plots.hpp"

#include "sim/render/error_plot_axes.hpp"
#include "sim/render/error_plot_ticks.hpp"
#include "sim/render/font.hpp"
#include "sim/render/gl_context.hpp"
#include "sim/render/legend.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim {

namespace {

std::vector<render::KeyItem> keyItems(const CurvesData& data, int s) {
  std::vector<render::KeyItem> items;
  for (std::size_t k = 0; k < data.curves.size(); ++k)
    items.push_back({data.curves[k].name, [k, s](const render::Rect& r) {
                       const double y = 0.5 * (r.y0 + r.y1);
                       render::segment({r.x0, y}, {r.x1, y}, std::max(2.0, 1.4 * s), render::hex(seriesRgb(k)));
                     }});
  return items;
}

}  // namespace

Image renderCurvesImage(const CurvesData& data, const PlotSize& size) {
  const int s = render::plotTextScale(size.width_px, size.height_px);
  const double pad = 6.0 * s, line = render::kLineHeight * s;
  ErrorPlotPanel p;
  double t_min = 0, t_max = 0;
  std::vector<double> values;
  for (const auto& c : data.curves)
    for (const auto& [t, v] : c.samples) {
      if (std::isfinite(t)) t_min = std::min(t_min, t), t_max = std::max(t_max, t);
      values.push_back(v);
    }
  if (t_max <= t_min) t_max = t_min + 1;
  p.time_min = t_min, p.time_max = t_max;
  render::logDecadeRange(values, 1e-3, 1e3, p.value_min, p.value_max);
  render::AxisStyle style{s, pad, render::niceTicks(t_min, t_max, 9)};

  int label_w = 0;
  for (const double v : render::decades(p.value_min, p.value_max))
    label_w = std::max(label_w, render::textWidth(render::decadeLabel(v), s));
  p.x0 = label_w + 3 * pad;
  p.x1 = std::max(p.x0 + 8, size.width_px - 3 * pad);
  const double key_top = 2 * pad + render::kLineHeight * (s + 1);
  const double key_h = render::plotKey(keyItems(data, s), p.x0, p.x1, key_top, s, false);
  p.y0 = key_top + key_h + 2 * pad + line + pad;  // the key, then the axis name
  p.y1 = std::max(p.y0 + 8, size.height_px - (2 * line + 3 * pad));  // time labels and name below

  return render::renderOffscreen(size.width_px, size.height_px, [&] {
    render::panelGrid(p, style.time_ticks, s);
    for (std::size_t k = 0; k < data.curves.size(); ++k)
      render::panelCurve(p, data.curves[k].samples, render::hex(seriesRgb(k)), std::max(2.0, 1.4 * s));
    // A curve's end may poke over the panel's edge: the margins are painted after it.
    const double w = size.width_px, h = size.height_px;
    render::fillRect({0, 0, w, p.y0 - 1}, render::hex(0xffffff));
    render::fillRect({0, p.y1 + 1, w, h}, render::hex(0xffffff));
    render::panelAxes(p, style, data.value_label + ", log scale", render::plotInk(), true);
    const std::string time = "time [s]";
    render::drawText(0.5 * (p.x0 + p.x1 - render::textWidth(time, s)), h - pad - line, time, s, render::plotInk());
    render::drawText(p.x0, pad, render::fitText(data.title, s + 1, p.x1 - p.x0), s + 1, render::plotInk());
    render::plotKey(keyItems(data, s), p.x0, p.x1, key_top, s, true);
  });
}

}  // namespace bimloc::sim
