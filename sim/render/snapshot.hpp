// Top-view snapshots of the particle filter over the plan (the paper's particle-filter figure:
// initialization, clustering, convergence) and of the S-Graph that tracks after it, rendered
// off-screen with OSMesa: no display needed.
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <cstdint>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace bimloc::sim {

struct SnapshotParticle {
  double x = 0, y = 0, yaw = 0, weight = 0;
};

// The S-Graph the tracker built (the paper's figure of its layers, seen from above): the
// robot-tracking layer (keyframes), the metric-semantic layer (walls, plan and new) and the
// topological layer (rooms linked to their walls). Plain data in the map frame, so the render
// library knows nothing of the tracker.
struct SnapshotGraph {
  std::vector<Eigen::Vector3d> keyframes;  // x, y, yaw, oldest first: drawn as a path
  struct Segment {
    Eigen::Vector2d start = Eigen::Vector2d::Zero(), end = Eigen::Vector2d::Zero();
    double thickness_m = 0;  // 0: a line of fixed pixel width
  };
  std::vector<Segment> matched_walls;  // plan walls observed, at their estimated place (axis)
  std::vector<Segment> new_planes;     // planes not in the plan: their seen extent
  struct Room {
    Eigen::Vector2d centre = Eigen::Vector2d::Zero();  // the estimated room node
    std::vector<Eigen::Vector2d> wall_points;          // where its edges meet its walls
  };
  std::vector<Room> rooms;
  bool empty() const { return keyframes.empty() && matched_walls.empty() && new_planes.empty() && rooms.empty(); }
};

struct SnapshotScene {
  const bim::Storey* storey = nullptr;      // walls and rooms; the view fits them (or, without
                                            // a storey, the particles and poses)
  std::vector<SnapshotParticle> particles;  // coloured by weight (viridis, min..max of these)
  std::optional<Eigen::Vector3d> truth;     // x, y, yaw: the true pose (green arrow)
  std::optional<Eigen::Vector3d> estimate;  // x, y, yaw: the estimate (red arrow)
  std::string title;                        // e.g. "R101, seed 3: converged"
  double time_s = 0;                        // shown as "t = 12.3 s"
  std::string phase;                        // "initialization" | "clustering" | "convergence"
  std::vector<std::pair<std::string, std::string>> legend_extra;  // "key: value" lines
  std::optional<SnapshotGraph> graph;  // once the S-Graph tracks: drawn over the plan, in the legend
};

struct SnapshotOptions {
  int width_px = 1200;
  int height_px = 900;
  double margin_m = 1.0;  // around the storey's rooms and walls
};

// RGB, rows top first, 3 bytes a pixel.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;
};

// Renders the top view and writes it as a PNG atomically (temporary name, then rename).
// Throws std::runtime_error naming the path on failure; no file is left behind then.
void renderSnapshot(const SnapshotScene& scene, const std::string& png_path, const SnapshotOptions& options = {});

// The same image, in memory. Thread-safe (calls are serialised). Throws std::invalid_argument
// for a size out of range, std::runtime_error when OSMesa fails.
Image renderSnapshotImage(const SnapshotScene& scene, const SnapshotOptions& options = {});

// Where the world point (x, y) lands in that image: continuous (column, row) pixel
// coordinates, row 0 at the top; the pixel that contains it is (floor(col), floor(row)).
Eigen::Vector2d worldToPixel(const SnapshotScene& scene, const SnapshotOptions& options, double x, double y);

}  // namespace bimloc::sim
