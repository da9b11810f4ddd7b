#include "sim/lidar/vlp16_turns.hpp"

#include <cmath>

namespace bimloc::sim {

std::vector<std::vector<Vlp16Point>> splitVlp16Turns(const std::vector<Vlp16Point>& points, double cut_deg) {
  std::vector<std::vector<Vlp16Point>> turns;
  double previous = 0.0;
  for (const Vlp16Point& p : points) {
    const double relative = std::fmod(std::fmod(p.azimuth_deg - cut_deg, 360.0) + 360.0, 360.0);
    // A fall of more than half a turn is a wrap; a small one is the jitter of interpolation
    // or dual-return pairs.
    if (turns.empty() || relative < previous - 180.0) turns.emplace_back();
    turns.back().push_back(p);
    previous = relative;
  }
  return turns;
}

}  // namespace bimloc::sim
