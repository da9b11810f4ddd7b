#include "sim/render/layers.hpp"

#include "sim/render/colormap.hpp"
#include "sim/render/font.hpp"
#include "sim/render/legend.hpp"

#include <GL/gl.h>

#include <cmath>
#include <cstdio>

namespace bimloc::sim::render {

namespace {

const Colour kInk = legendInk();
const Colour kMuted = legendMuted();
const Colour kRule = hex(0xcfcfcf);

std::string format(const char* fmt, double value) {
  char buf[64];
  std::snprintf(buf, sizeof buf, fmt, value);
  return buf;
}

// The largest round length that fits in max_px at this zoom.
double scaleBarMetres(double max_px, double px_per_m) {
  double best = 0.1;
  for (const double m : {0.1, 0.2, 0.5, 1.0, 2.0, 5.0, 10.0, 20.0, 50.0, 100.0, 200.0, 500.0})
    if (m * px_per_m <= max_px) best = m;
  return best;
}

void weightSection(Cursor& at, const WeightRange& range) {
  at.heading(textWidth("Particle weight", at.s) <= at.width ? "Particle weight" : "Weight");
  const double bar_h = 1.4 * at.line();
  const int steps = 96;
  for (int i = 0; i < steps; ++i)
    fillRect({at.x + at.width * i / steps, at.y, at.x + at.width * (i + 1) / steps + 0.5, at.y + bar_h},
             fromBytes(viridis((i + 0.5) / steps)));
  strokeRect({at.x, at.y, at.x + at.width, at.y + bar_h}, std::max(1, at.s / 2), hex(0x555555));
  at.y += bar_h + at.s * 3;
  if (range.count == 0) {
    at.text("no particles");
    return;
  }
  const std::string lo = format("%.3g", range.lo), hi = format("%.3g", range.hi);
  if (range.hi > range.lo) {
    drawText(at.x, at.y, lo, at.s, kMuted);
    drawText(at.x + at.width - textWidth(hi, at.s), at.y, hi, at.s, kMuted);
    at.y += at.line();
  } else {
    at.text("all equal: " + hi);  // all in the colour bar's top colour
  }
  at.text(std::to_string(range.count) + (range.count == 1 ? " particle" : " particles"));
}

void poseSection(Cursor& at, const SnapshotScene& scene) {
  at.heading("Pose");
  const double symbol_w = 26.0 * at.s;
  const auto item = [&](const Colour& colour, const std::string& label) {
    drawPoseMarker({at.x + 5.0 * at.s, at.y + 0.4 * at.line()}, {1, 0}, colour, at.s);
    at.text(label, kInk, symbol_w);
    at.y += 0.3 * at.line();
  };
  item(truthColour(), "truth");
  item(estimateColour(), "estimate");
  if (scene.truth && scene.estimate && scene.truth->allFinite() && scene.estimate->allFinite()) {
    const double dist = (scene.truth->head<2>() - scene.estimate->head<2>()).norm();
    const double dyaw = std::remainder(scene.estimate->z() - scene.truth->z(), 2 * M_PI);
    at.text("error " + format("%.2f m", dist));
    at.text("      " + format("%.1f", std::abs(dyaw) * 180 / M_PI) + "\u00B0");
  }
}

void scaleSection(Cursor& at, const Layout& layout) {
  at.heading("Scale");
  const double axes = 9.0 * at.line() / 4;  // room for the x/y axes on the right
  const double metres = scaleBarMetres(at.width - axes - 4 * at.s, layout.px_per_m);
  const double len = metres * layout.px_per_m, h = 0.5 * at.line(), edge = std::max(1.0, 0.5 * at.s);
  const double y = at.y + h;
  // A filled half and an open half: the cartographer's scale bar, readable at a glance.
  fillRect({at.x, y - 0.3 * h, at.x + len / 2, y + 0.3 * h}, kInk);
  strokeRect({at.x + len / 2, y - 0.3 * h, at.x + len, y + 0.3 * h}, edge, kInk);
  const std::string label = metres >= 1 ? format("%.0f m", metres) : format("%.1f m", metres);
  drawText(at.x, y + 0.6 * h, label, at.s, kMuted);
  // World axes: x to the right, y up (the plan's frame).
  const Eigen::Vector2d o(at.x + at.width - 0.7 * axes, y + 0.9 * h);
  const double arm = 0.45 * axes;
  drawArrow(o, {1, 0}, arm, 1.2 * at.s, kInk, kInk, 0);
  drawArrow(o, {0, -1}, arm, 1.2 * at.s, kInk, kInk, 0);
  drawText(o.x() + arm + at.s * 2, o.y() - 0.45 * at.line(), "x", at.s, kMuted);
  drawText(o.x() - 0.5 * textWidth("y", at.s), o.y() - arm - at.line(), "y", at.s, kMuted);
  at.y += 2.2 * at.line();
}

}  // namespace

std::string fitText(const std::string& text, int scale, double max_px) {
  if (textWidth(text, scale) <= max_px) return text;
  const std::size_t keep = static_cast<std::size_t>(std::max(0.0, max_px / (kAdvance * scale) - 3));
  // Cut after `keep` code points: UTF-8 continuation bytes (10xxxxxx) do not start one.
  std::size_t end = 0, count = 0;
  while (end < text.size()) {
    if ((static_cast<unsigned char>(text[end]) & 0xC0) != 0x80 && count++ == keep) break;
    ++end;
  }
  return text.substr(0, end) + "...";
}

void Cursor::heading(const std::string& text) {
  drawText(x, y, fitText(text, s, width), s, legendInk());
  drawText(x + 1, y, fitText(text, s, width), s, legendInk());  // a pixel to the right: bold
  y += line() + 2 * s;
}

void Cursor::text(const std::string& text, const Colour& colour, double indent) {
  drawText(x + indent, y, fitText(text, s, width - indent), s, colour);
  y += line();
}

void drawHeader(const SnapshotScene& scene, const Layout& layout) {
  const Rect& r = layout.header;
  fillRect(r, hex(0xffffff));
  fillRect({r.x0, r.y1 - std::max(1, layout.text_scale / 2), r.x1, r.y1}, kRule);
  const int s = layout.text_scale, big = s + 1;
  const double baseline_y = r.y0 + layout.pad + 0.5 * s;
  // Right: the phase as a badge, then the time.
  const std::string time = "t = " + format("%.1f s", scene.time_s);
  double right = r.x1 - 2 * layout.pad - textWidth(time, big);
  drawText(right, baseline_y, time, big, kInk);
  if (!scene.phase.empty()) {
    const double w = textWidth(scene.phase, s) + 2 * layout.pad;
    const Rect badge{right - 2 * layout.pad - w, baseline_y - s, right - 2 * layout.pad,
                     baseline_y - s + kLineHeight * s + 2.5 * s};
    fillRect(badge, hex(0x3b4a5a));
    drawText(badge.x0 + layout.pad, badge.y0 + 2 * s, scene.phase, s, hex(0xffffff));
    right = badge.x0;
  }
  const double title_w = right - 4 * layout.pad;
  drawText(2 * layout.pad, baseline_y, fitText(scene.title, big, title_w), big, kInk);
}

void extraSection(Cursor& at, const SnapshotScene& scene, double bottom) {
  for (const auto& [key, value] : scene.legend_extra) {
    if (at.y + 2 * at.line() > bottom) break;  // out of room: the panel is not a log
    const std::string k = key.empty() ? "" : key + ": ";
    double indent = k.empty() ? 0 : textWidth(k, at.s) + at.s;  // the space after the colon
    if (!k.empty()) drawText(at.x, at.y, fitText(k, at.s, at.width), at.s, kMuted);
    if (indent + textWidth(value, at.s) > at.width) {  // a long value goes on its own line
      at.y += at.line();
      indent = 2 * kAdvance * at.s;
    }
    at.text(value, kInk, indent);
  }
}

void drawLegend(const SnapshotScene& scene, const WeightRange& range, const Layout& layout) {
  fillRect(layout.panel, hex(0xffffff));
  const int s = layout.text_scale, pad = layout.pad;
  const Rect& p = layout.panel;
  Rect area = layout.legend_below ? Rect{p.x0 + 2 * pad, p.y0 + pad, p.x1 - 2 * pad, p.y1 - pad}
                                  : Rect{p.x0 + pad, p.y0 + 2 * pad, p.x1 - 2 * pad, p.y1 - 2 * pad};
  // Below the plan: columns (weight | pose | scale | graph | extras, those that do not fit as
  // their own column under the scale) of at most a panel's width each; beside it: one column.
  // The box is flush with the plan when its columns fit there, else as wide as the panel.
  const auto width_of = [&](const Rect& a, int n) {
    return std::min((a.width() - 4 * pad - (n - 1) * 3 * pad) / n, 19.0 * kAdvance * s);
  };
  const auto fits = [&](const Rect& a, int n) { return width_of(a, n) >= 15.0 * kAdvance * s; };
  const int optional_sections = (scene.graph ? 1 : 0) + (scene.legend_extra.empty() ? 0 : 1);
  int own_columns = 0;  // optional sections with a column of their own
  if (layout.legend_below) {
    Rect flush = area;
    flush.x0 = layout.origin.x();
    flush.x1 = layout.toPixel(layout.world_max).x();
    const bool can_flush = flush.width() >= 0.6 * area.width();
    for (int k = optional_sections; k >= 0; --k) {
      if (can_flush && (k == 0 || fits(flush, 3 + k))) area = flush;
      if (k == 0 || fits(area, 3 + k)) {
        own_columns = k;
        break;
      }
    }
  }
  const int columns = layout.legend_below ? 3 + own_columns : 1;
  const double column_w = width_of(area, columns);
  const auto column = [&](int i) {
    return Cursor{area.x0 + 2 * pad + i * (column_w + 3 * pad), area.y0 + 2 * pad, column_w, s};
  };
  // The box fits its contents, which are only measured by laying them out: record them in a
  // display list, draw the box, then play the list on top.
  const GLuint list = glGenLists(1);
  glNewList(list, GL_COMPILE);
  Cursor at = column(0);
  double bottom = at.y;
  int next_column = 1;
  const auto next = [&](bool own) {  // the next section: in a new column or under the last
    bottom = std::max(bottom, at.y);
    if (own) at = column(next_column++); else at.gap();
  };
  weightSection(at, range);
  next(layout.legend_below);
  poseSection(at, scene);
  next(layout.legend_below);
  scaleSection(at, layout);
  int optional_left = own_columns;
  if (scene.graph) {
    next(optional_left-- > 0);
    graphLegendSection(at, *scene.graph);
  }
  if (!scene.legend_extra.empty()) {
    next(optional_left-- > 0);
    extraSection(at, scene, area.y1 - pad);
  }
  bottom = std::max(bottom, at.y);
  glEndList();
  const double right =
      layout.legend_below ? area.x0 + 4 * pad + columns * column_w + (columns - 1) * 3 * pad : area.x1;
  const Rect box{area.x0, area.y0, std::min(area.x1, right), std::min(area.y1, bottom + pad)};
  fillRect(box, hex(0xf7f7f7));
  strokeRect(box, std::max(1, s / 2), kRule);
  glCallList(list);
  glDeleteLists(list, 1);
}

}  // namespace bimloc::sim::render
