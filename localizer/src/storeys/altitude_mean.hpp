// The altitude the search weighs the storeys by: the mean of the recent readings, each less the
// odometry's height when it was read, plus the odometry's height now. A barometer's per-reading
// noise (0.1-0.3 m) averages out over the window, while the odometry carries the mean across a
// climb; what the readings share (the offset of their reference, the drift since) stays. The
// reading's sigma is kept as told: the mean's error is at most the reading's, and which part
// of it is noise the input does not say.
//
// Why not the latest reading: the search weighs the storeys at every update, and a decision is
// taken the first time the margin passes the bar. With a fresh noise draw each time, a reading
// half-way between two storeys would sooner or later be 2 sigma off towards one of them and
// decide it, right or wrong.
#pragma once

#include <bimloc/storeys/storey_follower.hpp>

#include <deque>
#include <optional>
#include <utility>

namespace bimloc::storeys {

class AltitudeMean {
 public:
  // Readings within this many seconds of the newest are averaged: 100 readings at 10 Hz (the
  // noise down tenfold), over which the barometer's drift (0.38 mm/s) and the odometry's height
  // drift (centimetres over a flight) move the mean by millimetres.
  static constexpr double kWindowS = 10.0;

  // A reading (counted once: a reading seen again at the same stamp is skipped) and the
  // odometry's height at that moment.
  void add(const AltitudeReading& reading, double odom_z) {
    if (!samples_.empty() && samples_.back().first == reading.stamp_s) return;
    samples_.emplace_back(reading.stamp_s, reading.altitude_m - odom_z);
    sum_ += samples_.back().second;
    while (!samples_.empty() && samples_.front().first < reading.stamp_s - kWindowS) {
      sum_ -= samples_.front().second;
      samples_.pop_front();
    }
    if (samples_.size() == 1) sum_ = samples_.front().second;  // no rounding carried over
    latest_ = reading;
  }
  // The latest reading with its altitude replaced by the mean, referred to odom_z; none before
  // the first reading.
  std::optional<AltitudeReading> at(double odom_z) const {
    if (!latest_ || samples_.empty()) return std::nullopt;
    AltitudeReading r = *latest_;
    r.altitude_m = odom_z + sum_ / static_cast<double>(samples_.size());
    return r;
  }

 private:
  std::deque<std::pair<double, double>> samples_;  // (stamp, altitude less the odometry's z)
  double sum_ = 0;
  std::optional<AltitudeReading> latest_;
};

}  // namespace bimloc::storeys
