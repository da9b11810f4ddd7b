#include "sim/runner/run_scenario.hpp"

namespace bimloc::sim {

LocalizerSettings localizerSettings(const Scenario& s) {
  LocalizerSettings out;
  out.filter.seed = s.seed * 0x9E3779B97F4A7C15ull + 11;
  out.planes.seed = s.seed;
  const auto& j = s.localizer;
  if (!j.is_object()) throw ScenarioError(s.file + ": localizer: expected a mapping");
  for (const auto& [key, value] : j.items()) {
    const auto number = [&](double lo, double hi) {
      if (!value.is_number()) throw ScenarioError(s.file + ": localizer." + key + ": expected a number");
      const double v = value.get<double>();
      if (!(v >= lo && v <= hi))
        throw ScenarioError(s.file + ": localizer." + key + ": " + std::to_string(v) + " is outside [" +
                            std::to_string(lo) + ", " + std::to_string(hi) + "]");
      return v;
    };
    if (key == "method") {
      const std::string m = value.is_string() ? value.get<std::string>() : "";
      if (m != "pf" && m != "pf-no-rooms")
        throw ScenarioError(s.file + ": localizer.method: expected 'pf' or 'pf-no-rooms'");
      out.filter.use_rooms = m == "pf";
    } else if (key == "particles") {
      out.filter.particles = static_cast<int>(number(10, 1e6));
    } else if (key == "sigma_d_m") {
      out.filter.sigma_d_m = number(1e-3, 10);
    } else if (key == "sigma_azimuth_deg") {
      out.filter.sigma_azimuth_deg = number(0.01, 90);
    } else if (key == "converged_updates") {
      out.filter.converged_updates = static_cast<int>(number(1, 1000));
    } else if (key == "voxel_size_m") {
      out.planes.voxel_size_m = number(0.01, 1);
    } else if (key == "prior_rooms") {
      // The start was in one of these rooms (what a user knows: "we start in flat B").
      const auto list = value.is_string() ? nlohmann::json::array({value}) : value;
      if (!list.is_array() || list.empty()) throw ScenarioError(s.file + ": localizer.prior_rooms: expected a room name or a list of them");
      for (const auto& r : list) {
        if (!r.is_string()) throw ScenarioError(s.file + ": localizer.prior_rooms: expected room names");
        out.filter.prior_rooms.push_back(r.get<std::string>());
      }
    } else if (key == "prior_pose") {
      // [x, y, yaw_deg] of the start in the map frame; prior_sigma_m and prior_sigma_yaw_deg widen it.
      if (!value.is_array() || value.size() != 3 || !value[0].is_number() || !value[1].is_number() || !value[2].is_number())
        throw ScenarioError(s.file + ": localizer.prior_pose: expected [x, y, yaw_deg]");
      out.filter.prior_pose = Eigen::Vector3d(value[0].get<double>(), value[1].get<double>(), value[2].get<double>() * M_PI / 180.0);
      if (!out.filter.prior_pose->allFinite()) throw ScenarioError(s.file + ": localizer.prior_pose: not finite");
    } else if (key == "storey") {
      // The localizer is not told the storey: it considers every storey with walls and rooms.
      if (!value.is_string() || value.get<std::string>() != "auto")
        throw ScenarioError(s.file + ": localizer.storey: only 'auto' (the storey found from the scans); the storey "
                                     "itself is the scenario's `storey:`");
      out.storey_auto = true;
    } else if (key == "prior_sigma_m") {
      out.filter.prior_sigma_m = number(1e-3, 1e4);
    } else if (key == "prior_sigma_yaw_deg") {
      out.filter.prior_sigma_yaw_deg = number(0.01, 180);
    } else {
      throw ScenarioError(s.file + ": localizer: unknown key '" + key +
                          "' (keys: method, particles, sigma_d_m, sigma_azimuth_deg, converged_updates, voxel_size_m, "
                          "prior_rooms, prior_pose, prior_sigma_m, prior_sigma_yaw_deg, storey)");
    }
  }
  return out;
}

}  // namespace bimloc::sim
