#include "sim/render/error_plot_ticks.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>

namespace bimloc::sim::render {

std::vector<double> niceTicks(double lo, double hi, int max_count) {
  std::vector<double> ticks;
  if (!(hi > lo) || max_count < 1 || !std::isfinite(lo) || !std::isfinite(hi)) return ticks;
  const double raw = (hi - lo) / max_count;
  const double magnitude = std::pow(10.0, std::floor(std::log10(raw)));
  double step = 10 * magnitude;
  for (const double m : {1.0, 2.0, 5.0})
    if (m * magnitude >= raw) {
      step = m * magnitude;
      break;
    }
  // Integer multiples, not repeated additions: the labels stay exact.
  for (long k = static_cast<long>(std::ceil(lo / step - 1e-9)); k * step <= hi + 1e-9 * step; ++k)
    ticks.push_back(k * step);
  return ticks;
}

std::vector<double> decades(double lo, double hi) {
  std::vector<double> out;
  const int a = static_cast<int>(std::lround(std::log10(lo))), b = static_cast<int>(std::lround(std::log10(hi)));
  for (int k = a; k <= b; ++k) out.push_back(std::pow(10.0, k));
  return out;
}

std::string decadeLabel(double decade) {
  const int k = static_cast<int>(std::lround(std::log10(decade)));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", std::max(0, -k), decade);
  return buf;
}

std::string tickLabel(double value, double step) {
  const int digits = std::clamp(static_cast<int>(std::ceil(-std::log10(step) - 1e-9)), 0, 6);
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*f", digits, std::abs(value) < 0.5 * step * 1e-6 ? 0.0 : value);
  return buf;
}

void logDecadeRange(const std::vector<double>& values, double floor, double cap, double& lo, double& hi) {
  double smallest = std::numeric_limits<double>::infinity(), largest = 0;
  for (const double v : values)
    if (std::isfinite(v) && v > 0) smallest = std::min(smallest, v), largest = std::max(largest, v);
  if (!(largest > 0)) {  // nothing to show: a default decade pair
    lo = 10 * floor;
    hi = 1000 * floor;
    return;
  }
  lo = std::pow(10.0, std::floor(std::log10(std::max(smallest, floor)) + 1e-9));
  hi = std::pow(10.0, std::ceil(std::log10(std::min(std::max(largest, lo), cap)) - 1e-9));
  if (hi <= lo * 1.5) hi = lo * 10;
}

}  // namespace bimloc::sim::render
