// Which storey the robot is on, from its height (issue 31): the odometry's height change
// carried from the storey it was tracked on, an altimeter's reading (a barometer), and the
// plan's stairs (Building::stairs), which say where a flight arrives.
//
// Heights: a storey's floor is taken at its elevation; the base stands `base_height_m` above
// its floor (the odometry's z at the start: the odom frame starts on the start storey's floor,
// as the particle filter assumes). So the base's z in the map on storey s is
// elevation(s) + base_height_m, and an altitude reading (the base's height above the plan's
// z = 0) is compared with that.
#pragma once

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <cstddef>
#include <deque>
#include <optional>
#include <utility>
#include <vector>

namespace bimloc::storeys {

struct StoreyFollowConfig {
  bool follow = true;  // false: the localizer stays on the storey it converged on (as before issue 31)
  // Each storey's map also holds the walls filed under other storeys that stand in its wall band
  // (bim/standing_walls.hpp: split levels); false: the walls the file files under it, alone.
  bool standing_walls = true;
  // The base's z within this of a storey's floor + base height: it stands on that storey.
  // Storeys are 2.5-4 m apart; a flight's last steps (and odometry's height drift over a
  // flight, a few centimetres) are well inside it, the half-way landing (1.3-1.5 m) is not.
  double floor_tolerance_m = 0.6;
  // The height settled: it changed less than settled_rise_m over the last settled_window_s
  // (a robot on the stairs gains a riser every second or so).
  double settled_window_s = 1.0;
  double settled_rise_m = 0.08;
  // A flight's footprint (its run line, +- half its width) grown by this: the base on it is
  // on the stairs, not on a storey, whatever its height. Two tracking errors (a few cm): a base
  // whose estimate overshoots the flight (odometry slipping on it) is still climbing, which the
  // settled height catches. 0.3 m held the arrival 0.4-0.6 s longer (docs/results/2026-11-26-h31tours.md).
  double flight_margin_m = 0.1;
  // Off the tracked floor for longer than this is no climb (a flight takes 10-30 s) but the
  // odometry's height drifting (lidar odometry drifts in z on long runs): the localizer stops
  // treating the robot as climbing (its search runs again).
  double max_climb_s = 60.0;
  // An altitude rules a storey out when it is farther than altitude_sigmas * altitudeSigma() +
  // floor_finish_m from its floor + base height (storeysAtAltitude), and weighs the storeys
  // it does not rule out by its Gaussian log-likelihood (altitudeLogLikelihood).
  double altitude_sigmas = 3.0;
  // How far the floor the robot stands on may lie from its storey's elevation, a bound (not a
  // noise): the slab's own elevation tolerance, +-19 mm (ACI 117-10, "Specification for
  // Tolerances for Concrete Construction and Materials", the elevation of a slab's top surface
  // +-3/4 in), and the floor build-up a site may not have laid yet when the plan's elevation is
  // the finished floor's: a floating screed of at least 45 mm (DIN 18560-2:2022, the nominal
  // thickness of a cement screed on an insulating layer) over its impact-sound insulation and a
  // covering, about 0.1 m. 0.02 + 0.1 m.
  double floor_finish_m = 0.12;
  // The barometer's drift since its reference (the localizer's first reading): the weather
  // moves the pressure under a still sensor, a tendency of about 0.5 hPa in 3 hours at about
  // 8.3 m per hPa, 0.38 mm/s (the order of magnitude of the 3-hourly tendencies weather
  // stations report; the bench's model, sim/odometry/barometer.hpp). A rate of this sigma: its
  // effect grows with the time since the reference and adds to the reading's sigma.
  double altitude_drift_sigma_mps = 3.8e-4;
  // The arrival landing as a prior: when the tracker cannot confirm the new storey's walls,
  // the filter searches within this of the pose carried across the flight (1 sigma).
  double arrival_sigma_m = 1.0;
  double arrival_sigma_yaw_deg = 20.0;
};

struct AltitudeReading {
  double stamp_s = 0, altitude_m = 0, sigma_m = 0;
  double since_reference_s = 0;  // the time since the altitude's reference (for its drift)
};

// The altitude's sigma: the reading's own, and its drift since its reference
// (StoreyFollowConfig::altitude_drift_sigma_mps), independent, in quadrature.
double altitudeSigma(const AltitudeReading& altitude, const StoreyFollowConfig& config);

// The altitude's log-likelihood on storey s (an index into building.storeys): Gaussian in the
// distance from the storey's floor + base height beyond StoreyFollowConfig::floor_finish_m
// (0 within it), of sigma altitudeSigma(). Up to a constant, the same for every storey: a
// difference of two is the altitude's log-likelihood ratio between them.
double altitudeLogLikelihood(const bim::Building& building, std::size_t storey, const AltitudeReading& altitude,
                             double base_height_m, const StoreyFollowConfig& config);

// The storey (of `candidates`, indices into building.storeys) whose floor + base height is
// nearest base_z_m, if within tolerance_m.
std::optional<std::size_t> storeyAtHeight(const bim::Building& building, const std::vector<std::size_t>& candidates,
                                          double base_z_m, double base_height_m, double tolerance_m);

// The candidates an altitude does not rule out (StoreyFollowConfig::altitude_sigmas,
// floor_finish_m, altitudeSigma()), in their order.
std::vector<std::size_t> storeysAtAltitude(const bim::Building& building, const std::vector<std::size_t>& candidates,
                                           const AltitudeReading& altitude, double base_height_m, const StoreyFollowConfig& config);

// The flight (index into building.stairs) whose footprint, grown by margin_m, holds the base,
// its feet (its z less base_height_m) at the flight's height there, within 0.5 m (or margin_m);
// -1 when none. Under a flight is not on it.
int flightAt(const bim::Building& building, const Eigen::Vector3d& base_map, double base_height_m, double margin_m);

// Where a flight puts the robot when it leaves it: the storey of the end it left by (for a
// half landing, -1, the storey of the far end of the next flight of the same stair from there).
struct FlightEnd {
  int storey = -1;
  Eigen::Vector3d at = Eigen::Vector3d::Zero();  // the run line's end, at the floor's z
  double heading_rad = 0;                        // the run line's direction, walking off that end
};
FlightEnd flightEnd(const bim::Building& building, int flight, bool top);

// One decision per step: has the tracked robot arrived on another storey?
struct StoreyArrival {
  std::size_t from = 0, to = 0;
  int flight = -1;  // the flight it came by (index into building.stairs), -1 when the plan has none there
  std::optional<FlightEnd> landing;  // that flight's end
};

class StoreyFollower {
 public:
  StoreyFollower(const bim::Building& building, const StoreyFollowConfig& config);

  // The base's pose on storey `storey` (its z: the storey's elevation + the odometry's height
  // since it arrived there; see the header's comment), and the latest altitude if any. An
  // arrival when the base stands (height settled, on no flight) on another storey of the plan
  // and the altitude does not rule that storey out.
  std::optional<StoreyArrival> step(double stamp_s, std::size_t storey, const Eigen::Vector3d& base_map, double base_height_m,
                                    const std::optional<AltitudeReading>& altitude);
  // The base is not on the floor of the storey it was last placed on: on a flight, or between
  // floors (its height from the tracked storey's floor beyond the tolerance). Searching there
  // for the storey's walls would look for them at the wrong height.
  bool climbing() const { return climbing_; }
  int lastFlight() const { return last_flight_; }  // the flight the base was last on, -1 none yet

  // The base's height at a moment (step() notes it too); whether it settled
  // (StoreyFollowConfig::settled_*) over the heights noted.
  void noteHeight(double stamp_s, double z);
  bool settled() const;

 private:
  const bim::Building& building_;
  StoreyFollowConfig config_;
  std::vector<std::size_t> all_;
  std::deque<std::pair<double, double>> heights_;  // (stamp, base z) over the settling window
  bool climbing_ = false;
  std::optional<double> climbing_since_;
  int last_flight_ = -1;
  Eigen::Vector3d last_on_flight_ = Eigen::Vector3d::Zero();
};

}  // namespace bimloc::storeys
