#include "sim/base/gait.hpp"

#include <algorithm>
#include <cmath>

namespace bimloc::sim {
namespace {

// Full gait from 0.2 m/s or 20 deg/s on (or the limits, if lower): Spot steps at its full
// rhythm as soon as it moves at all; only the start and stop ramps are partial.
constexpr double kBriskSpeed_mps = 0.2;
constexpr double kBriskTurn_rps = 20.0 * M_PI / 180.0;

}  // namespace

double gaitActivity(double speed_mps, double turn_rate_rps, double max_speed_mps, double max_turn_rate_rps) {
  const double v_ref = std::min(kBriskSpeed_mps, max_speed_mps);
  const double w_ref = std::min(kBriskTurn_rps, max_turn_rate_rps);
  return std::min(1.0, std::max(std::abs(speed_mps) / v_ref, std::abs(turn_rate_rps) / w_ref));
}

GaitOffsets gaitOffsets(const GaitConfig& gait, double t_s, double activity, double phase_rad) {
  GaitOffsets g;
  if (activity <= 0.0) return g;
  const double step = 2.0 * M_PI * gait.step_frequency_hz * t_s + phase_rad;
  const double deg = M_PI / 180.0;
  g.dz_m = activity * gait.bob_amplitude_m * std::sin(step);
  g.roll_rad = activity * gait.roll_amplitude_deg * deg * std::sin(0.5 * step);
  g.pitch_rad = activity * gait.pitch_amplitude_deg * deg * std::cos(step);
  return g;
}

double stairSpeed_mps(const bim::StairFlight& flight, const MotionConfig& motion) {
  constexpr double kRampFraction = 0.5;
  constexpr double kStepsPerStride = 2.0;  // a trot: left pair, right pair
  if (flight.risers <= 0 || !(flight.going_m > 0.0)) return kRampFraction * motion.max_speed_mps;
  return std::min(motion.max_speed_mps, flight.going_m * motion.gait.step_frequency_hz / kStepsPerStride);
}

}  // namespace bimloc::sim
