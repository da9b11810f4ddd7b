// A barometer's altitude (issue 31, `--altitude`): the base's true height in the plan's frame,
// plus the sensor's noise, an offset left by its calibration at the start, and the drift of
// the weather's pressure over the run. Its draws come from their own stream of the seed.
#pragma once

#include <cstdint>
#include <random>

namespace bimloc::sim {

struct BarometerConfig {
  bool enabled = false;  // `--altitude`: the localizer is given the altitude
  // Bosch BMP390 datasheet (BST-BMP390-DS002-07, rev. 1.7, 2021): relative accuracy +-3 Pa,
  // which it equates to +-0.25 m (about 12 Pa per metre near sea level). Read as a 2-sigma
  // bound: 0.125 m per reading, and 0.125 m for the offset of the altitude zeroed on the
  // plan's floor at the start (the same relative accuracy, once).
  double noise_sigma_m = 0.125;
  double offset_sigma_m = 0.125;
  // The weather moves the pressure under a still sensor: a barometric tendency of about
  // 0.5 hPa in 3 hours (an order of magnitude of the 3-hourly tendencies weather stations
  // report, not a measured figure) at about 8.3 m per hPa is 0.5 * 8.3 / 10800 s = 0.38 mm/s:
  // a rate drawn once per run with this sigma, 0.12 m over a 5-minute tour.
  double drift_sigma_mps = 3.8e-4;
};

class Barometer {
 public:
  Barometer(const BarometerConfig& config, std::uint64_t seed);
  // The altitude read at t for the true altitude (map z of the base).
  double read(double t_s, double true_altitude_m);
  // What the reading's sigma is said to be (noise and offset; the drift is not known to it).
  double sigma_m() const;

 private:
  BarometerConfig config_;
  std::mt19937_64 rng_;
  double offset_m_ = 0.0, drift_mps_ = 0.0;
};

}  // namespace bimloc::sim
