// The frame, grid, ticks and labels of a plot panel with a time axis and a logarithmic value
// axis: the error plot's look, shared by the plots that put several runs or methods side by
// side (bimloc compare).
#pragma once

#include "sim/render/draw.hpp"
#include "sim/render/error_plot.hpp"

#include <functional>
#include <string>
#include <utility>
#include <vector>

namespace bimloc::sim::render {

inline Colour plotInk() { return hex(0x222222); }
inline Colour plotFrame() { return hex(0x555555); }
inline Colour plotGrid() { return hex(0xc4c4c4); }
inline Colour plotMinorGrid() { return hex(0xe4e4e4); }

// The text scale of a plot of that size (one font pixel per glyph pixel up to about 675 px on
// the shorter side); throws std::invalid_argument unless each side is in [160, 16384].
int plotTextScale(int width_px, int height_px);

struct AxisStyle {
  int text_scale = 1;
  double pad = 6;  // spacing unit, pixels
  std::vector<double> time_ticks;
};

// Grid lines at the decades (and their multiples, lighter) and at the time ticks.
void panelGrid(const ErrorPlotPanel& p, const std::vector<double>& time_ticks, double scale);

// The frame, the decade labels on the left, the time ticks below (labelled when
// `time_labels`), and the panel's name above it in `colour` (the legend of its curve).
void panelAxes(const ErrorPlotPanel& p, const AxisStyle& style, const std::string& name, const Colour& colour,
               bool time_labels);

// A curve of (time, value) points on the panel, round-joined, broken where a value is not
// finite (no estimate to compare).
void panelCurve(const ErrorPlotPanel& p, const std::vector<std::pair<double, double>>& samples, const Colour& colour,
                double width);

// The key of a plot: items (a symbol drawn in its box, then its label) from left to right
// starting at (x0, y), onto a new row where one would pass x1. Returns the height of the
// rows; draws only when `draw` (the layout measures first).
struct KeyItem {
  std::string label;
  std::function<void(const Rect&)> symbol;
};
double plotKey(const std::vector<KeyItem>& items, double x0, double x1, double y, int scale, bool draw);

}  // namespace bimloc::sim::render
