// Checks an SGraphConfig before use: a value that cannot work (a zero sigma, a window of one
// keyframe) is replaced by the default, and the warning names it.
#include "config_check.hpp"

#include <cmath>
#include <utility>

namespace bimloc::sgraph {

const char* toString(TrackingState state) { return state == TrackingState::Tracking ? "tracking" : "lost"; }

namespace detail {

SGraphConfig checkedConfig(const SGraphConfig& config, std::vector<std::string>& warnings) {
  SGraphConfig c = config;
  const SGraphConfig defaults;
  const std::pair<const char*, double SGraphConfig::*> positive[] = {
      {"keyframe_spacing_m", &SGraphConfig::keyframe_spacing_m},
      {"keyframe_spacing_deg", &SGraphConfig::keyframe_spacing_deg},
      {"plane_sigma_azimuth_deg", &SGraphConfig::plane_sigma_azimuth_deg},
      {"plane_sigma_elevation_deg", &SGraphConfig::plane_sigma_elevation_deg},
      {"plane_sigma_d_m", &SGraphConfig::plane_sigma_d_m},
      {"association_sigma_azimuth_deg", &SGraphConfig::association_sigma_azimuth_deg},
      {"association_sigma_d_m", &SGraphConfig::association_sigma_d_m},
      {"association_gate_mahalanobis2", &SGraphConfig::association_gate_mahalanobis2},
      {"room_match_distance_m", &SGraphConfig::room_match_distance_m},
      {"merge_max_offset_m", &SGraphConfig::merge_max_offset_m},
      {"odometry_sigma_xy_floor_m", &SGraphConfig::odometry_sigma_xy_floor_m},
      {"odometry_sigma_yaw_floor_deg", &SGraphConfig::odometry_sigma_yaw_floor_deg},
      {"odometry_jump_m", &SGraphConfig::odometry_jump_m},
      {"odometry_jump_deg", &SGraphConfig::odometry_jump_deg},
      {"initial_sigma_xy_m", &SGraphConfig::initial_sigma_xy_m},
      {"initial_sigma_yaw_deg", &SGraphConfig::initial_sigma_yaw_deg},
      {"wall_prior_sigma_m", &SGraphConfig::wall_prior_sigma_m},
      {"wall_prior_sigma_deg", &SGraphConfig::wall_prior_sigma_deg},
      {"wall_thickness_sigma_m", &SGraphConfig::wall_thickness_sigma_m},
      {"room_prior_sigma_m", &SGraphConfig::room_prior_sigma_m},
      {"room_factor_sigma_m", &SGraphConfig::room_factor_sigma_m},
      {"huber_plane_sigmas", &SGraphConfig::huber_plane_sigmas},
      {"huber_odometry_sigmas", &SGraphConfig::huber_odometry_sigmas},
      {"cauchy_wall_prior_sigmas", &SGraphConfig::cauchy_wall_prior_sigmas},
      {"huber_room_sigmas", &SGraphConfig::huber_room_sigmas},
  };
  for (const auto& [name, member] : positive) {
    if (std::isfinite(c.*member) && c.*member > 0) continue;
    warnings.push_back(std::string("config ") + name + " = " + std::to_string(c.*member) + " must be positive: using " +
                       std::to_string(defaults.*member));
    c.*member = defaults.*member;
  }
  const std::pair<const char*, double SGraphConfig::*> non_negative[] = {
      {"segment_margin_m", &SGraphConfig::segment_margin_m},
      {"opening_margin_m", &SGraphConfig::opening_margin_m},
      {"odometry_sigma_xy_per_m", &SGraphConfig::odometry_sigma_xy_per_m},
      {"odometry_sigma_yaw_per_rad", &SGraphConfig::odometry_sigma_yaw_per_rad},
      {"odometry_sigma_yaw_per_m_deg", &SGraphConfig::odometry_sigma_yaw_per_m_deg},
      {"loss_mahalanobis2", &SGraphConfig::loss_mahalanobis2},
      {"min_plan_fraction", &SGraphConfig::min_plan_fraction},
      {"loss_correction_m", &SGraphConfig::loss_correction_m},
  };
  for (const auto& [name, member] : non_negative) {
    if (std::isfinite(c.*member) && c.*member >= 0) continue;
    warnings.push_back(std::string("config ") + name + " = " + std::to_string(c.*member) + " must not be negative: using " +
                       std::to_string(defaults.*member));
    c.*member = defaults.*member;
  }
  // The newest keyframe must survive the slide that follows its optimization.
  if (c.window_keyframes < 2) {
    warnings.push_back("config window_keyframes = " + std::to_string(c.window_keyframes) + " must be at least 2: using 2");
    c.window_keyframes = 2;
  }
  const std::pair<const char*, int SGraphConfig::*> at_least_one[] = {
      {"new_plane_min_sightings", &SGraphConfig::new_plane_min_sightings},
      {"candidate_max_age_keyframes", &SGraphConfig::candidate_max_age_keyframes},
      {"max_iterations", &SGraphConfig::max_iterations},
      {"lost_after_keyframes", &SGraphConfig::lost_after_keyframes},
      {"recover_after_keyframes", &SGraphConfig::recover_after_keyframes},
      {"prior_max_walls", &SGraphConfig::prior_max_walls},
  };
  for (const auto& [name, member] : at_least_one) {
    if (c.*member >= 1) continue;
    warnings.push_back(std::string("config ") + name + " = " + std::to_string(c.*member) + " must be at least 1: using " +
                       std::to_string(defaults.*member));
    c.*member = defaults.*member;
  }
  return c;
}

}  // namespace detail
}  // namespace bimloc::sgraph
