// A path's score against the plan: the sum over its points of the per-point log-likelihood of a
// robust mixture (a Gaussian hit on the nearest wall plus a uniform clutter floor), and an
// upper bound of that score over a box of start poses (for the branch-and-bound).
#pragma once

#include "sim/oracle/oracle_config.hpp"
#include "sim/oracle/wall_field.hpp"

#include <Eigen/Core>
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <vector>

namespace bimloc::sim::oracle {

// log p(d) - log p(0) for p(d) = z_hit N(d; 0, sigma) + (1 - z_hit) / max_range: 0 on a wall,
// decreasing, down to the clutter floor. Tabulated every millimetre up to the field's clamp.
class PointModel {
 public:
  PointModel(const OracleConfig& config, double clamp_m);
  float score(float d) const;       // linear between table entries
  float upperBound(float d) const;  // >= score(d') for every d' >= d
  // upperBound of a DistanceField code (a distance in units of clamp / 255): a table.
  float boundOfCode(std::uint8_t code) const { return code_bounds_[code]; }
  float floor() const { return table_.back(); }

 private:
  std::vector<float> table_;
  float step_ = 0.001f;
  std::array<float, 256> code_bounds_{};
};

// The points of a path in its start frame: each keyframe's points composed with the
// keyframe's odometry relative to the first one. A start pose P places them at P * q.
struct PathCloud {
  std::vector<float> x, y, r;  // r = |q|, what a turn of the start pose moves the point by per radian
  float r_rms = 0;
  std::size_t size() const { return x.size(); }
  void add(float px, float py);
  void finish();  // r_rms
};

// The score of the path started at (x, y, yaw); below `stop_below` it may stop early and
// return any value below it (each point only lowers the sum).
float pathScore(const DistanceField& field, const PointModel& model, const PathCloud& path, double x, double y, double yaw,
                float stop_below = -std::numeric_limits<float>::infinity());

// An upper bound of pathScore over every start in [cx +- half_x] x [cy +- half_y] x
// [yaw +- half_yaw]: each point's distance bounded below over the box its position sweeps.
// Stops early below `stop_below` as pathScore does.
float pathBound(const DistanceField& field, const PointModel& model, const PathCloud& path, double cx, double cy, double yaw,
                double half_x, double half_y, double half_yaw, float stop_below = -std::numeric_limits<float>::infinity());

// A turn by at most half_yaw about the start moves a point at distance r by at most the chord
// 2 r sin(half_yaw / 2), in each axis: the chord per metre of r, and a point's turn with float
// rounding's margin. pathBound and robustBound both place their boxes with these.
inline float chordPerMetre(double half_yaw) { return static_cast<float>(2.0 * std::sin(std::min(half_yaw, M_PI) / 2.0)); }
inline float pointTurn(float chord_per_m, float r) { return chord_per_m * r + 1e-4f; }

// The bound of one point of pathBound: at (px, py) for the box's centre, moved by at most
// hx + turn in x and hy + turn in y by any start in the box.
inline float pointBound(const DistanceField& field, const PointModel& model, float px, float py, float hx, float hy, float turn) {
  return model.boundOfCode(field.minCodeOver(px - hx - turn, py - hy - turn, px + hx + turn, py + hy + turn));
}

inline float PointModel::score(float d) const {
  const float f = std::max(0.0f, d) / step_;
  const auto k = static_cast<std::size_t>(f);
  if (k + 1 >= table_.size()) return table_.back();
  const float u = f - static_cast<float>(k);
  return (1 - u) * table_[k] + u * table_[k + 1];
}

}  // namespace bimloc::sim::oracle
