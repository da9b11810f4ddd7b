#include "sim/oracle/path_score.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim::oracle {

PointModel::PointModel(const OracleConfig& c, double clamp_m) {
  const double hit_peak = c.z_hit / (std::sqrt(2.0 * M_PI) * c.sigma_m), clutter = (1.0 - c.z_hit) / c.max_range_m;
  const auto n = static_cast<std::size_t>(std::ceil(clamp_m / step_)) + 2;
  table_.resize(n);
  for (std::size_t k = 0; k < n; ++k) {
    const double d = static_cast<double>(k) * step_;
    table_[k] = static_cast<float>(std::log(hit_peak * std::exp(-0.5 * d * d / (c.sigma_m * c.sigma_m)) + clutter) -
                                   std::log(hit_peak + clutter));
  }
  // DistanceField::codeDistance's rule (code * clamp / 255), bounded as upperBound bounds, a
  // micrometre lower: the code's distance, rounded in float, may come out an ulp above the cell
  // value it stands for.
  for (int code = 0; code < 256; ++code)
    code_bounds_[static_cast<std::size_t>(code)] =
        upperBound(std::max(0.0f, static_cast<float>(code) * static_cast<float>(clamp_m) / 255.0f - 1e-6f));
}

float PointModel::upperBound(float d) const {
  const auto k = static_cast<std::size_t>(std::max(0.0f, d) / step_);  // rounded down: the table decreases
  return table_[std::min(k, table_.size() - 1)];
}

void PathCloud::add(float px, float py) {
  x.push_back(px), y.push_back(py), r.push_back(std::hypot(px, py));
}

void PathCloud::finish() {
  double sum = 0;
  for (float v : r) sum += static_cast<double>(v) * v;
  r_rms = r.empty() ? 0.0f : static_cast<float>(std::sqrt(sum / static_cast<double>(r.size())));
}

float pathScore(const DistanceField& field, const PointModel& model, const PathCloud& path, double x, double y, double yaw,
                float stop_below) {
  const auto c = static_cast<float>(std::cos(yaw)), s = static_cast<float>(std::sin(yaw));
  const auto tx = static_cast<float>(x), ty = static_cast<float>(y);
  float sum = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    sum += model.score(field.at(c * path.x[i] - s * path.y[i] + tx, s * path.x[i] + c * path.y[i] + ty));
    if (sum < stop_below) return sum;
  }
  return sum;
}

float pathBound(const DistanceField& field, const PointModel& model, const PathCloud& path, double cx, double cy, double yaw,
                double half_x, double half_y, double half_yaw, float stop_below) {
  const auto c = static_cast<float>(std::cos(yaw)), s = static_cast<float>(std::sin(yaw));
  const auto tx = static_cast<float>(cx), ty = static_cast<float>(cy);
  const float chord = chordPerMetre(half_yaw);
  const auto hx = static_cast<float>(half_x), hy = static_cast<float>(half_y);
  float sum = 0;
  for (std::size_t i = 0; i < path.size(); ++i) {
    const float px = c * path.x[i] - s * path.y[i] + tx, py = s * path.x[i] + c * path.y[i] + ty;
    sum += pointBound(field, model, px, py, hx, hy, pointTurn(chord, path.r[i]));
    if (sum < stop_below) return sum;
  }
  return sum;
}

}  // namespace bimloc::sim::oracle
