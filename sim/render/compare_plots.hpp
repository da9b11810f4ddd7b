// The figures of a comparison of localization methods (bimloc compare): a bar chart of the
// convergence times per start room and method (the paper's convergence-time table, drawn),
// and the position error over time, one curve per method. Plain data in, so the render
// library knows nothing of methods or runs; drawn with the error plot's canvas and font.
#pragma once

#include "sim/render/snapshot.hpp"

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

// The colour of series k (0xRRGGBB): ColorBrewer's Dark2, readable side by side; it repeats
// after eight.
std::uint32_t seriesRgb(std::size_t series);
constexpr std::uint32_t kBarFlagRgb = 0xd7191c;  // the mark of a flagged bar (a false convergence)

struct BarChartData {
  std::string title, value_label;  // value_label: the value axis, e.g. "convergence time [s]"
  std::vector<std::string> series;  // one colour and legend entry each
  struct Bar {
    std::size_t series = 0;
    std::optional<double> value;  // none: no value (N.L.), drawn pale to the top with a cross
    bool flagged = false;         // marked with a '!' above it and a frame in kBarFlagRgb
  };
  struct Group {
    std::string label;  // under the group
    std::vector<Bar> bars;
  };
  std::vector<Group> groups;
  double value_max = 1;  // the top of the axis (values above are drawn to it)
  std::string missing_label = "N.L.";  // what a bar without value means, in the legend
  std::string flag_label = "false convergence";
};

struct CurvesData {
  std::string title, value_label;  // value_label: the log-scale axis, e.g. "position error [m]"
  struct Curve {
    std::string name;
    std::vector<std::pair<double, double>> samples;  // (time [s], value), by time; NaN breaks the curve
  };
  std::vector<Curve> curves;  // curve k in seriesRgb(k)
};

struct PlotSize {
  int width_px = 1200;
  int height_px = 700;
};

// Throw std::invalid_argument for a size out of range (each side in [160, 16384]).
Image renderBarChartImage(const BarChartData& data, const PlotSize& size = {});
Image renderCurvesImage(const CurvesData& data, const PlotSize& size = {});

// Where the bar chart puts its plot area, and how a value maps to a row: for the tests.
struct BarChartFrame {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;  // the plot area, pixels, y down
  double value_max = 1;
  double rowOf(double value) const;  // continuous row of a value (0 at y1, value_max at y0)
  // Column span [left, right) of bar `bar` of group `group` (bars of a group side by side).
  std::pair<double, double> barSpan(const BarChartData& data, std::size_t group, std::size_t bar) const;
};
BarChartFrame barChartFrame(const BarChartData& data, const PlotSize& size = {});

}  // namespace bimloc::sim
