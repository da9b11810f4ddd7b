// `bimloc eval --plot`: both trajectories seen from above (equal aspect, metres), and under
// them the error over time (the error plot's panels: translation and rotation APE). Drawn with
// the snapshots' OSMesa canvas, font and the error plot; no second plotting stack.
#pragma once

#include "sim/render/snapshot.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim {

struct TrajectoryPlotData {
  std::string title;
  std::vector<Eigen::Vector2d> truth, estimate;  // map x, y [m], the associated (aligned) poses
  std::vector<double> time_s;                    // per pose, from the first
  std::vector<double> ape_m, ape_rotation_deg;   // per pose
};

struct TrajectoryPlotOptions {
  int width_px = 1200;
  int top_view_height_px = 900;
  int error_height_px = 700;
};

// The truth wide and light under the estimate, so that both show where they coincide.
constexpr std::uint32_t kTrajectoryTruthRgb = 0xa3a3a3;
constexpr std::uint32_t kTrajectoryEstimateRgb = 0x2166ac;

// The top view alone; throws std::invalid_argument for a size out of range.
Image renderTrajectoryViewImage(const TrajectoryPlotData& data, int width_px, int height_px);

// Top view above the error plot, one PNG, written atomically; throws std::runtime_error
// naming the path on failure.
void renderTrajectoryPlot(const TrajectoryPlotData& data, const std::string& png_path, const TrajectoryPlotOptions& options = {});

}  // namespace bimloc::sim
