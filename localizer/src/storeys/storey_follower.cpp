#include <bimloc/storeys/storey_follower.hpp>

#include <algorithm>
#include <cmath>
#include <limits>

namespace bimloc::storeys {
namespace {

// The flight of the same stair that goes on from a half landing at `z`: the one whose bottom
// (going up) or top (going down) stands there, nearest to `at`.
int nextFlight(const bim::Building& building, int flight, bool up) {
  const bim::StairFlight& from = building.stairs.at(static_cast<std::size_t>(flight));
  const Eigen::Vector3d& at = up ? from.top : from.bottom;
  constexpr double kSameLandingZ = 0.2;  // a landing's flights meet at its z
  int best = -1;
  double best_d = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < building.stairs.size(); ++i) {
    if (static_cast<int>(i) == flight || building.stairs[i].stair_id != from.stair_id) continue;
    const Eigen::Vector3d& end = up ? building.stairs[i].bottom : building.stairs[i].top;
    if (std::abs(end.z() - at.z()) > kSameLandingZ) continue;
    const double d = (end - at).head<2>().norm();
    if (d < best_d) best_d = d, best = static_cast<int>(i);
  }
  return best;
}

}  // namespace

std::optional<std::size_t> storeyAtHeight(const bim::Building& building, const std::vector<std::size_t>& candidates,
                                          double base_z_m, double base_height_m, double tolerance_m) {
  std::optional<std::size_t> best;
  double best_d = tolerance_m;
  for (const std::size_t s : candidates) {
    const double d = std::abs(base_z_m - (building.storeys.at(s).elevation_m + base_height_m));
    if (d <= best_d) best_d = d, best = s;
  }
  return best;
}

double altitudeSigma(const AltitudeReading& altitude, const StoreyFollowConfig& config) {
  const double drift = config.altitude_drift_sigma_mps * std::max(0.0, altitude.since_reference_s);
  return std::hypot(altitude.sigma_m, drift);
}

double altitudeLogLikelihood(const bim::Building& building, std::size_t storey, const AltitudeReading& altitude,
                             double base_height_m, const StoreyFollowConfig& config) {
  const double off = std::abs(altitude.altitude_m - (building.storeys.at(storey).elevation_m + base_height_m));
  const double beyond = std::max(0.0, off - config.floor_finish_m);
  const double sigma = altitudeSigma(altitude, config);
  if (!(sigma > 0)) return beyond > 0 ? -std::numeric_limits<double>::infinity() : 0.0;
  return -0.5 * (beyond / sigma) * (beyond / sigma);
}

std::vector<std::size_t> storeysAtAltitude(const bim::Building& building, const std::vector<std::size_t>& candidates,
                                           const AltitudeReading& altitude, double base_height_m, const StoreyFollowConfig& config) {
  const double reach = config.altitude_sigmas * altitudeSigma(altitude, config) + config.floor_finish_m;
  std::vector<std::size_t> kept;
  for (const std::size_t s : candidates)
    if (std::abs(altitude.altitude_m - (building.storeys.at(s).elevation_m + base_height_m)) <= reach) kept.push_back(s);
  return kept;
}

int flightAt(const bim::Building& building, const Eigen::Vector3d& base_map, double base_height_m, double margin_m) {
  const double foot_z = base_map.z() - base_height_m;
  for (std::size_t i = 0; i < building.stairs.size(); ++i) {
    const bim::StairFlight& f = building.stairs[i];
    const double run = f.run_m();
    if (!(run > 1e-6)) continue;
    const Eigen::Vector2d dir = (f.top - f.bottom).head<2>() / run;
    const Eigen::Vector2d v = base_map.head<2>() - f.bottom.head<2>();
    const double along = v.dot(dir), across = std::abs(dir.x() * v.y() - dir.y() * v.x());
    if (along < -margin_m || along > run + margin_m || across > 0.5 * f.width_m + margin_m) continue;
    // At the flight's height there (not under it: the space below a flight is the lower floor's).
    constexpr double kOnStepsM = 0.5;  // a few risers: the odometry's height drift over a flight, and the nosing line
    const double surface_z = f.bottom.z() + std::clamp(along / run, 0.0, 1.0) * f.rise_m();
    if (std::abs(foot_z - surface_z) > std::max(kOnStepsM, margin_m)) continue;
    return static_cast<int>(i);
  }
  return -1;
}

FlightEnd flightEnd(const bim::Building& building, int flight, bool top) {
  FlightEnd end;
  // A stair of n flights has n-1 landings: follow them (bounded, against a cycle in bad data).
  for (std::size_t hop = 0; hop <= building.stairs.size() && flight >= 0; ++hop) {
    const bim::StairFlight& f = building.stairs.at(static_cast<std::size_t>(flight));
    const Eigen::Vector2d up = (f.top - f.bottom).head<2>();
    end.at = top ? f.top : f.bottom;
    end.heading_rad = top ? std::atan2(up.y(), up.x()) : std::atan2(-up.y(), -up.x());
    end.storey = top ? f.top_storey : f.bottom_storey;
    if (end.storey >= 0) break;
    flight = nextFlight(building, flight, top);
  }
  return end;
}

StoreyFollower::StoreyFollower(const bim::Building& building, const StoreyFollowConfig& config) : building_(building), config_(config) {
  // The storeys a robot can be tracked on: those with walls (and rooms, as the filter's).
  for (std::size_t s = 0; s < building.storeys.size(); ++s)
    if (!building.storeys[s].walls.empty() && !building.storeys[s].rooms.empty()) all_.push_back(s);
}

void StoreyFollower::noteHeight(double stamp_s, double z) {
  if (!std::isfinite(stamp_s) || !std::isfinite(z)) return;
  heights_.emplace_back(stamp_s, z);
  while (heights_.size() > 2 && heights_.front().first < stamp_s - config_.settled_window_s) heights_.pop_front();
}

bool StoreyFollower::settled() const {
  if (heights_.size() < 2 || heights_.back().first - heights_.front().first < 0.8 * config_.settled_window_s) return false;
  double lo = heights_.front().second, hi = lo;
  for (const auto& [t, z] : heights_) lo = std::min(lo, z), hi = std::max(hi, z);
  return hi - lo < config_.settled_rise_m;
}

std::optional<StoreyArrival> StoreyFollower::step(double stamp_s, std::size_t storey, const Eigen::Vector3d& base_map,
                                                  double base_height_m, const std::optional<AltitudeReading>& altitude) {
  noteHeight(stamp_s, base_map.z());
  if (!config_.follow || !base_map.allFinite()) return std::nullopt;
  const int on = flightAt(building_, base_map, base_height_m, config_.flight_margin_m);
  std::optional<std::size_t> at = storeyAtHeight(building_, all_, base_map.z(), base_height_m, config_.floor_tolerance_m);
  // Storeys at (nearly) the same height as the tracked one (a plan's duplicate levels, split
  // levels): it stays on the tracked one. A change of storey is a climb of more than the tolerance.
  const double off_tracked = std::abs(base_map.z() - base_height_m - building_.storeys.at(storey).elevation_m);
  if (at && *at != storey &&
      (off_tracked <= config_.floor_tolerance_m ||
       std::abs(building_.storeys[*at].elevation_m - building_.storeys[storey].elevation_m) <= config_.floor_tolerance_m))
    at = storey;
  climbing_ = on >= 0 || !(at && *at == storey);
  if (!climbing_) climbing_since_.reset();
  else if (!climbing_since_) climbing_since_ = stamp_s;
  if (climbing_ && stamp_s - *climbing_since_ > config_.max_climb_s) climbing_ = false;
  if (on >= 0) {
    last_flight_ = on, last_on_flight_ = base_map;
    return std::nullopt;
  }
  if (!at || *at == storey || !settled()) return std::nullopt;
  if (altitude && storeysAtAltitude(building_, {*at}, *altitude, base_height_m, config_).empty()) return std::nullopt;
  StoreyArrival arrival;
  arrival.from = storey, arrival.to = *at;
  if (last_flight_ >= 0) {
    // It left the flight by the end nearer to where it was last seen on it.
    const bim::StairFlight& f = building_.stairs[static_cast<std::size_t>(last_flight_)];
    const bool top = (last_on_flight_ - f.top).head<2>().norm() < (last_on_flight_ - f.bottom).head<2>().norm();
    const FlightEnd end = flightEnd(building_, last_flight_, top);
    if (end.storey == static_cast<int>(*at)) arrival.flight = last_flight_, arrival.landing = end;
  }
  last_flight_ = -1;
  return arrival;
}

}  // namespace bimloc::storeys
