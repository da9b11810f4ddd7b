// The search over every start pose of the storey: a lattice of start poses (grid_m, grid_deg),
// each standing for its cell, and a branch-and-bound over it whose bound never underestimates
// (pathBound over a node's cells), or, for the tests, every lattice pose in turn.
#pragma once

#include "sim/oracle/deviation.hpp"
#include "sim/oracle/path_score.hpp"

#include <Eigen/Core>
#include <cstdint>
#include <vector>

namespace bimloc::sim::oracle {

// Start poses: positions on a grid over the field's extent, headings every step_rad.
struct Lattice {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  int nx = 0, ny = 0, nt = 0;
  double step_m = 0.1, step_rad = 0;
  std::vector<std::uint8_t> free;  // [j * nx + i]: the body fits there (clearance from every wall)
  std::vector<int> free_sum;       // summed-area table of `free`, (nx + 1) x (ny + 1)
  double free_area_m2 = 0;

  Lattice(const DistanceField& field, const OracleConfig& config);
  Eigen::Vector3d pose(int i, int j, int t) const { return {origin.x() + i * step_m, origin.y() + j * step_m, t * step_rad}; }
  int freeIn(int i0, int j0, int ni, int nj) const;  // free positions in the block
};

// The true start and its place: the starts within radius_m and angle_rad of it.
struct TruthZone {
  Eigen::Vector3d start = Eigen::Vector3d::Zero();
  double radius_m = 0.5, angle_rad = 10.0 * M_PI / 180.0;
};

enum class Region {
  Rivals,  // free lattice poses outside the truth's place
  Truth,   // lattice poses inside it (free or not: the robot stood there)
};

struct SearchAnswer {
  float best = -std::numeric_limits<float>::infinity();  // the best cell value found (see searchPlaces)
  Eigen::Vector3d pose = Eigen::Vector3d::Zero();
  bool reached = false;  // some cell's value is >= the bar
  std::size_t nodes = 0, cells = 0;
};

struct SearchContext {
  const DistanceField& field;
  const PointModel& model;
  const PathCloud& path;
  const Lattice& lattice;
  TruthZone zone;
  // When set, a pose's value is its robust one (robustScore: one wall's points dropped), and the
  // bounds are robustBound's; else pathScore and pathBound.
  const Discount* discount = nullptr;
};

// A start's value (pathScore, or robustScore with a discount) and its bound over a box.
float valueAt(const SearchContext& c, double x, double y, double yaw, float stop_below = -std::numeric_limits<float>::infinity());
float boundOver(const SearchContext& c, const Eigen::Vector3d& centre, const Eigen::Vector3d& half,
                float stop_below = -std::numeric_limits<float>::infinity());

// A cell's value: the best start a local search (pattern search from the lattice pose, steps
// halved down to 1/32 of the cell) finds within the cell. Stops once it reaches `stop_at`.
float cellValue(const SearchContext& c, int i, int j, int t, Eigen::Vector3d* best_pose,
                float stop_at = std::numeric_limits<float>::infinity());

// Branch-and-bound over the region's lattice poses. Cells whose bound is below `bar` are not
// looked at. With stop_at_bar, it stops at the first cell whose value reaches the bar
// (`reached`); without, it returns the best cell value when that is >= bar.
SearchAnswer searchPlaces(const SearchContext& c, Region region, float bar, bool stop_at_bar);

// The same answer as searchPlaces(c, region, -inf, false), by evaluating every cell.
SearchAnswer searchEveryPlace(const SearchContext& c, Region region);

}  // namespace bimloc::sim::oracle
