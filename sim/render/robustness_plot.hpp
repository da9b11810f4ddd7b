// The robustness figure of `bimloc sweep --sites ... --methods ...`: the localization rate
// (above) and the median ATE (below) of each method against the site's deviation level, one
// line per method over the presets in the order given (exact, as_built, construction, heavy).
// Drawn with the error plot's canvas, font and ticks: no second plotting stack.
#pragma once

#include "sim/render/snapshot.hpp"

#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim {

struct RobustnessSeries {
  std::string method;
  std::vector<double> rate;   // per level, 0..1 (NaN: no run)
  std::vector<double> ate_m;  // per level, median ATE (NaN: no converged run)
};

struct RobustnessPlotData {
  std::string title;
  std::vector<std::string> levels;  // x axis labels, e.g. "construction (10 cm)"
  std::vector<RobustnessSeries> series;
  int width_px = 1200, height_px = 800;
};

// A method's line colour (a colour-blind-safe palette, by the method's index).
std::uint32_t robustnessColour(std::size_t index);

Image renderRobustnessPlotImage(const RobustnessPlotData& data);
// Written atomically; throws std::runtime_error naming the path.
void renderRobustnessPlot(const RobustnessPlotData& data, const std::string& png_path);

}  // namespace bimloc::sim
