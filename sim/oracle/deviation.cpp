#include "sim/oracle/deviation.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim::oracle {
namespace {

// The values below are summed in double and the bound raised by this much: a float sum of ~10^4
// terms of up to 8.4 nats may round by a few hundredths, a double one by ~10^-7, so the bound,
// rounded to float to the nearest as the value is, stays at or above it (docs/oracle.md).
constexpr double kRoundingSlack = 1e-3;

// The greatest per-group sum, or 0 (no wall dropped): the one deviation most favourable to the rival.
double bestDrop(const Discount& d) {
  double most = 0;
  for (const double v : d.scratch) most = std::max(most, v);
  return most;
}

}  // namespace

WallLabels::WallLabels(const DistanceField& field, const std::vector<int>& wall_of) : field_(&field), wall_of_(wall_of) {
  for (const int w : wall_of_) walls_ = std::max(walls_, w + 1);
}

Discount discountOf(const WallLabels& labels, const DistanceField& field, const PointModel& model, const PathCloud& path,
                    const Eigen::Vector3d& truth_pose) {
  Discount d;
  const auto c = static_cast<float>(std::cos(truth_pose.z())), s = static_cast<float>(std::sin(truth_pose.z()));
  const auto tx = static_cast<float>(truth_pose.x()), ty = static_cast<float>(truth_pose.y());
  std::vector<std::int32_t> renumber(static_cast<std::size_t>(labels.walls()), -1);
  d.group.resize(path.size()), d.truth.resize(path.size());
  for (std::size_t i = 0; i < path.size(); ++i) {
    // The same placement and score as pathScore's.
    const float px = c * path.x[i] - s * path.y[i] + tx, py = s * path.x[i] + c * path.y[i] + ty;
    d.truth[i] = model.score(field.at(px, py));
    const int wall = labels.at(px, py);
    if (wall < 0) {
      d.group[i] = -1;
      continue;
    }
    auto& g = renumber[static_cast<std::size_t>(wall)];
    if (g < 0) g = d.groups++;
    d.group[i] = g;
  }
  d.scratch.assign(static_cast<std::size_t>(d.groups), 0.0);
  return d;
}

// Both below: for each wall w the term T_w = sum of the rival's (or its bound's) values over the
// points off w + the truth's over the points on w, returned as max(T_none, max_w T_w) =
// sum + max(0, max_w sum over w's points of (truth - rival)). Every point adds a value <= 0 to
// every T_w, so each only falls as points are added: once sum + the greatest group sum seen so
// far (>= the greatest now) is below stop_below, the final value is too.

float robustScore(const DistanceField& field, const PointModel& model, const PathCloud& path, const Discount& d, double x, double y,
                  double yaw, float stop_below) {
  const auto c = static_cast<float>(std::cos(yaw)), s = static_cast<float>(std::sin(yaw));
  const auto tx = static_cast<float>(x), ty = static_cast<float>(y);
  std::fill(d.scratch.begin(), d.scratch.end(), 0.0);
  double sum = 0, seen = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const float v = model.score(field.at(c * path.x[i] - s * path.y[i] + tx, s * path.x[i] + c * path.y[i] + ty));
    sum += v;
    if (d.group[i] >= 0) seen = std::max(seen, d.scratch[static_cast<std::size_t>(d.group[i])] += d.truth[i] - static_cast<double>(v));
    if (sum + seen < stop_below) return static_cast<float>(sum + seen);
  }
  return static_cast<float>(sum + bestDrop(d));
}

float robustBound(const DistanceField& field, const PointModel& model, const PathCloud& path, const Discount& d, double cx, double cy,
                  double yaw, double half_x, double half_y, double half_yaw, float stop_below) {
  // The box and the per-point bound are pathBound's (path_score.cpp), point for point.
  const auto c = static_cast<float>(std::cos(yaw)), s = static_cast<float>(std::sin(yaw));
  const auto tx = static_cast<float>(cx), ty = static_cast<float>(cy);
  const float chord = chordPerMetre(half_yaw);
  const auto hx = static_cast<float>(half_x), hy = static_cast<float>(half_y);
  std::fill(d.scratch.begin(), d.scratch.end(), 0.0);
  double sum = kRoundingSlack, seen = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const float px = c * path.x[i] - s * path.y[i] + tx, py = s * path.x[i] + c * path.y[i] + ty;
    const float bound = pointBound(field, model, px, py, hx, hy, pointTurn(chord, path.r[i]));
    sum += bound;
    // truth - bound <= truth - value: a group's sum here bounds its sum in robustScore from below,
    // but T_w = sum - (group's sum of bounds) + (group's sum of truths) >= the value's T_w, term by term.
    if (d.group[i] >= 0)
      seen = std::max(seen, d.scratch[static_cast<std::size_t>(d.group[i])] += d.truth[i] - static_cast<double>(bound));
    if (sum + seen < stop_below) return static_cast<float>(sum + seen);
  }
  return static_cast<float>(sum + bestDrop(d));
}

}  // namespace bimloc::sim::oracle
