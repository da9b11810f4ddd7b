// The body motion of a trot on top of the planar path: Spot's body bobs once per step, rocks
// sideways once per stride (a stride is two steps: left pair, right pair) and pitches a little
// at the step frequency. All of it fades with the walking activity, so a standing body is still.
#pragma once

#include "sim/base/motion_config.hpp"

#include <bimloc/bim/building.hpp>

namespace bimloc::sim {

struct GaitOffsets {
  double dz_m = 0.0, roll_rad = 0.0, pitch_rad = 0.0;
};

// How much the legs are stepping, 0 (standing) .. 1 (walking or turning briskly): the larger of
// speed and turn rate, each relative to a brisk-but-slow reference, so the gait fades in and
// out continuously with the velocity ramps.
double gaitActivity(double speed_mps, double turn_rate_rps, double max_speed_mps, double max_turn_rate_rps);

// `phase_rad` shifts the gait cycle (drawn from the seed: a run does not start on a step).
GaitOffsets gaitOffsets(const GaitConfig& gait, double t_s, double activity, double phase_rad);

// The base's horizontal speed on a flight (issue 31): the trot slows to one tread per stride
// (each leg pair steps up one riser per stride, at the gait's step frequency), so a 0.28 m
// going at 2 steps/s gives 0.28 m/s, a third of the 0.8 m/s on the flat. A model: no published
// figure of Spot's or ANYmal's stair speed was found. A ramp (no risers): half the speed limit.
// Never above the speed limit.
double stairSpeed_mps(const bim::StairFlight& flight, const MotionConfig& motion);

}  // namespace bimloc::sim
