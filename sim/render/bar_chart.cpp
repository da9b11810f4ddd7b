// The bar chart of a comparison: groups (start rooms) side by side, in each a bar per run and
// series (method), on a linear value axis from zero; a run without value (not localized) is
// a pale bar to the top of the axis with a cross on it, a flagged one (false convergence) is
// framed in red under a '!'.
#include "sim/render/compare_plots.hpp"

#include "sim/render/error_plot_axes.hpp"
#include "sim/render/error_plot_ticks.hpp"
#include "sim/render/font.hpp"
#include "sim/render/gl_context.hpp"
#include "sim/render/legend.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace bimloc::sim {

namespace {

double axisMax(const BarChartData& data) {
  return std::isfinite(data.value_max) && data.value_max > 0 ? data.value_max : 1.0;
}

std::vector<render::KeyItem> keyItems(const BarChartData& data, int s) {
  std::vector<render::KeyItem> items;
  for (std::size_t k = 0; k < data.series.size(); ++k)
    items.push_back({data.series[k], [k](const render::Rect& r) { render::fillRect(r, render::hex(seriesRgb(k))); }});
  items.push_back({data.missing_label, [s](const render::Rect& r) {
                     render::fillRect(r, render::hex(0x888888, 0.25f));
                     render::segment({r.x0, r.y0}, {r.x1, r.y1}, s, render::hex(0x555555));
                     render::segment({r.x0, r.y1}, {r.x1, r.y0}, s, render::hex(0x555555));
                   }});
  items.push_back({"! " + data.flag_label, [s](const render::Rect& r) {
                     render::fillRect(r, render::hex(0x888888));
                     render::strokeRect(r, s, render::hex(kBarFlagRgb));
                   }});
  return items;
}

std::string valueLabel(double value) {
  char text[32];
  std::snprintf(text, sizeof text, "%.1f", value);
  return text;
}

std::vector<double> valueTicks(double top) { return render::niceTicks(0, top, 8); }

}  // namespace

std::uint32_t seriesRgb(std::size_t series) {
  // ColorBrewer Dark2 (Brewer, colorbrewer2.org): qualitative, eight colours.
  static constexpr std::uint32_t kDark2[] = {0x1b9e77, 0xd95f02, 0x7570b3, 0xe7298a, 0x66a61e, 0xe6ab02, 0xa6761d, 0x666666};
  return kDark2[series % 8];
}

double BarChartFrame::rowOf(double value) const {
  return y1 - std::clamp(value, 0.0, value_max) / value_max * (y1 - y0);
}

std::pair<double, double> BarChartFrame::barSpan(const BarChartData& data, std::size_t group, std::size_t bar) const {
  const double group_w = (x1 - x0) / static_cast<double>(std::max<std::size_t>(1, data.groups.size()));
  const std::size_t bars = std::max<std::size_t>(1, data.groups.at(group).bars.size());
  const double bar_w = 0.8 * group_w / static_cast<double>(bars);  // a tenth of the group's width either side
  const double left = x0 + group_w * static_cast<double>(group) + 0.1 * group_w + bar_w * static_cast<double>(bar);
  const double gap = std::min(0.15 * bar_w, 3.0);
  return {left + gap, left + bar_w - gap};
}

BarChartFrame barChartFrame(const BarChartData& data, const PlotSize& size) {
  const int s = render::plotTextScale(size.width_px, size.height_px);
  const double pad = 6.0 * s, line = render::kLineHeight * s;
  BarChartFrame f;
  f.value_max = axisMax(data);
  int label_w = 0;
  const auto ticks = valueTicks(f.value_max);
  const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
  for (const double v : ticks) label_w = std::max(label_w, render::textWidth(render::tickLabel(v, step), s));
  f.x0 = label_w + 3 * pad;
  f.x1 = std::max(f.x0 + 8, size.width_px - 3 * pad);
  const double key_top = 2 * pad + render::kLineHeight * (s + 1);
  const double key_h = render::plotKey(keyItems(data, s), f.x0, f.x1, key_top, s, false);
  f.y0 = key_top + key_h + 2 * pad + line + pad;  // the key, then the axis name above the plot
  f.y1 = std::max(f.y0 + 8, size.height_px - (line + 3 * pad));  // the group labels below
  return f;
}

Image renderBarChartImage(const BarChartData& data, const PlotSize& size) {
  const BarChartFrame f = barChartFrame(data, size);
  const int s = render::plotTextScale(size.width_px, size.height_px);
  const double pad = 6.0 * s, line = render::kLineHeight * s;
  return render::renderOffscreen(size.width_px, size.height_px, [&] {
    const auto ticks = valueTicks(f.value_max);
    const double step = ticks.size() > 1 ? ticks[1] - ticks[0] : 1.0;
    for (const double v : ticks) {
      const double y = f.rowOf(v);
      render::segment({f.x0, y}, {f.x1, y}, 0.8 * s, render::plotGrid());
      const std::string label = render::tickLabel(v, step);
      render::drawText(f.x0 - pad - 0.5 * pad - render::textWidth(label, s), y - 3.5 * s, label, s, render::plotInk());
      render::segment({f.x0 - pad, y}, {f.x0, y}, std::max(2.0, 1.5 * s), render::plotFrame());
    }
    const double group_w = (f.x1 - f.x0) / static_cast<double>(std::max<std::size_t>(1, data.groups.size()));
    for (std::size_t g = 0; g < data.groups.size(); ++g) {
      const double gx = f.x0 + group_w * static_cast<double>(g);
      if (g > 0) render::segment({gx, f.y0}, {gx, f.y1}, 0.8 * s, render::plotMinorGrid());
      const std::string label = render::fitText(data.groups[g].label, s, group_w - pad);
      render::drawText(gx + 0.5 * (group_w - render::textWidth(label, s)), f.y1 + 2 * pad, label, s, render::plotInk());
      for (std::size_t b = 0; b < data.groups[g].bars.size(); ++b) {
        const BarChartData::Bar& bar = data.groups[g].bars[b];
        const auto [left, right] = f.barSpan(data, g, b);
        const render::Colour colour = render::hex(seriesRgb(bar.series));
        double top = f.y0;
        if (bar.value && std::isfinite(*bar.value)) {
          top = f.rowOf(*bar.value);
          render::fillRect({left, top, right, f.y1}, colour);
        } else {  // not localized: pale to the top, crossed at the top
          const render::Colour pale = render::hex(seriesRgb(bar.series), 0.25f);
          render::fillRect({left, f.y0, right, f.y1}, pale);
          const double c = std::min(right - left, 8.0 * s), mid = 0.5 * (left + right), y = f.y0 + s;
          const double width = std::max(1.0, std::min(0.15 * c, 1.5 * s));
          render::segment({mid - 0.5 * c, y}, {mid + 0.5 * c, y + c}, width, colour);
          render::segment({mid - 0.5 * c, y + c}, {mid + 0.5 * c, y}, width, colour);
          if (render::textWidth("N.L.", s) <= right - left)
            render::drawText(mid - 0.5 * render::textWidth("N.L.", s), y + c + pad, "N.L.", s, render::plotInk());
        }
        if (bar.flagged) render::strokeRect({left, top, right, f.y1}, std::max(1, s), render::hex(kBarFlagRgb));
        // Above the bar: its value where it fits (the table's number), and the flag's '!'.
        std::string text = bar.value && std::isfinite(*bar.value) ? valueLabel(*bar.value) : std::string();
        if (render::textWidth(text + "!", s) > right - left + 4) text.clear();  // over its neighbours: none
        if (bar.flagged) text += "!";
        if (!text.empty())
          render::drawText(0.5 * (left + right) - 0.5 * render::textWidth(text, s), std::max(f.y0 + s, top - 9.0 * s), text,
                           s, bar.flagged ? render::hex(kBarFlagRgb) : render::plotInk());
      }
    }
    const double edge = std::max(1, s / 2 + 1);
    render::strokeRect({f.x0 - edge, f.y0 - edge, f.x1 + edge, f.y1 + edge}, edge, render::plotFrame());
    render::drawText(f.x0, f.y0 - edge - pad / 2 - line, data.value_label, s, render::plotInk());
    render::drawText(f.x0, pad, render::fitText(data.title, s + 1, f.x1 - f.x0), s + 1, render::plotInk());
    render::plotKey(keyItems(data, s), f.x0, f.x1, 2 * pad + render::kLineHeight * (s + 1), s, true);
  });
}

}  // namespace bimloc::sim
