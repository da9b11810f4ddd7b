// The error of a run over time, as a PNG: position error above, yaw error below, against the
// time of the run, the localizer's state shaded behind (searching, tracking, lost) and the
// convergence time as a vertical line. Drawn with the snapshots' OSMesa canvas and font.
#pragma once

#include "sim/render/snapshot.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace bimloc::sim {

enum class ErrorPlotState { Searching, Tracking, Lost };

struct ErrorPlotSample {
  double time_s = 0, position_m = 0, yaw_deg = 0;
  ErrorPlotState state = ErrorPlotState::Searching;  // from this sample to the next
};

struct ErrorPlotData {
  std::string title;
  std::vector<ErrorPlotSample> samples;  // by time
  std::optional<double> convergence_time_s;
  // When the base stepped onto another storey (issue 31): a dashed vertical line each, keyed.
  std::vector<double> storey_change_times_s;
  // The panels' names (", log scale" is added), and whether the states are shaded and keyed
  // (a run's plot) or not (`bimloc eval`: an estimate's error, no localizer state).
  std::string position_label = "position error [m]", yaw_label = "yaw error [deg]";
  bool show_states = true;
};

struct ErrorPlotOptions {
  int width_px = 1200;
  int height_px = 800;
};

// The colours, 0xRRGGBB: for a reader of the picture's legend, and for the tests.
constexpr std::uint32_t kErrorPlotPositionRgb = 0x2166ac;
constexpr std::uint32_t kErrorPlotYawRgb = 0xc2410c;
constexpr std::uint32_t kErrorPlotConvergenceRgb = 0x1b1b1b;
constexpr std::uint32_t kErrorPlotStoreyChangeRgb = 0x7b3294;
constexpr std::uint32_t kErrorPlotSearchingRgb = 0xfbefd0;
constexpr std::uint32_t kErrorPlotTrackingRgb = 0xe2f1de;
constexpr std::uint32_t kErrorPlotLostRgb = 0xf9d6d6;

// One panel: its box in pixels (y down) and its axes. Errors span decades (metres while the
// filter searches, centimetres while the graph tracks), so the value axis is logarithmic,
// whole decades from `value_min` to `value_max`; a value below value_min sits on the bottom edge.
struct ErrorPlotPanel {
  double x0 = 0, y0 = 0, x1 = 0, y1 = 0;
  double time_min = 0, time_max = 1;
  double value_min = 0.01, value_max = 1;
  // Continuous (column, row) of the point (t, value); the pixel holding it is their floor.
  Eigen::Vector2d toPixel(double time_s, double value) const;
};

struct ErrorPlotLayout {
  int width = 0, height = 0;
  int text_scale = 1;
  double pad = 6;
  ErrorPlotPanel position, yaw;  // position above, yaw below, the same time axis
  std::vector<double> time_ticks;
};

// Throws std::invalid_argument for a size out of range.
ErrorPlotLayout errorPlotLayout(const ErrorPlotData& data, const ErrorPlotOptions& options = {});

Image renderErrorPlotImage(const ErrorPlotData& data, const ErrorPlotOptions& options = {});

// Written atomically (temporary name, then rename); throws std::runtime_error naming the path.
void renderErrorPlot(const ErrorPlotData& data, const std::string& png_path, const ErrorPlotOptions& options = {});

}  // namespace bimloc::sim
