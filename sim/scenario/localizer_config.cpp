#include "sim/scenario/localizer_config.hpp"

#include "sim/scenario/yaml_mapping.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <variant>

namespace bimloc::sim {
namespace {

using detail::Range;

// One settable field: where it lives, its range (integers and booleans are numbers here too).
struct Field {
  std::string key;
  std::variant<double*, int*, bool*> target;
  Range range = Range::closed(-1e12, 1e12);
};

Range closed(double lo, double hi) { return Range::closed(lo, hi); }
Range positive(double hi) { return Range::positive(hi); }

std::vector<Field> planeFields(planes::PlaneExtractionConfig& c) {
  return {{"voxel_size_m", &c.voxel_size_m, closed(0.01, 1)},
          {"min_range_m", &c.min_range_m, closed(0, 100)},
          {"max_range_m", &c.max_range_m, positive(1000)},
          {"ransac_iterations", &c.ransac_iterations, closed(1, 1e6)},
          {"distance_threshold_m", &c.distance_threshold_m, positive(1)},
          {"min_inliers", &c.min_inliers, closed(3, 1e7)},
          {"min_extent_m", &c.min_extent_m, closed(0, 100)},
          {"vertical_tolerance_deg", &c.vertical_tolerance_deg, closed(0, 45)},
          {"horizontal_tolerance_deg", &c.horizontal_tolerance_deg, closed(0, 45)},
          {"max_planes", &c.max_planes, closed(1, 1000)}};
}

std::vector<Field> pfFields(pf::ParticleFilterConfig& c) {
  return {{"particles", &c.particles, closed(10, 1e6)},
          {"tracking_particles", &c.tracking_particles, closed(1, 1e6)},
          {"neighbour_rooms", &c.neighbour_rooms},
          {"motion_noise_xy_per_m", &c.motion_noise_xy_per_m, closed(0, 10)},
          {"motion_noise_yaw_per_rad", &c.motion_noise_yaw_per_rad, closed(0, 10)},
          {"motion_noise_yaw_per_m_rad", &c.motion_noise_yaw_per_m_rad, closed(0, 10)},
          {"sigma_azimuth_deg", &c.sigma_azimuth_deg, closed(0.01, 90)},
          {"sigma_elevation_deg", &c.sigma_elevation_deg, closed(0.01, 90)},
          {"sigma_d_m", &c.sigma_d_m, closed(1e-3, 10)},
          {"gate_mahalanobis2", &c.gate_mahalanobis2, positive(1e6)},
          {"segment_margin_m", &c.segment_margin_m, closed(0, 100)},
          {"likelihood_power", &c.likelihood_power, positive(1)},
          {"update_min_translation_m", &c.update_min_translation_m, closed(0, 100)},
          {"update_min_rotation_deg", &c.update_min_rotation_deg, closed(0, 360)},
          {"max_static_scans", &c.max_static_scans, closed(1, 1e6)},
          {"anneal_start", &c.anneal_start, closed(1, 100)},
          {"anneal_rate", &c.anneal_rate, positive(1)},
          {"use_hypotheses", &c.use_hypotheses},
          {"initial_hypothesis_fraction", &c.initial_hypothesis_fraction, closed(0, 1)},
          {"injection_fraction", &c.injection_fraction, closed(0, 1)},
          {"injection_margin", &c.injection_margin, closed(0, 1e6)},
          {"max_hypotheses", &c.max_hypotheses, closed(1, 1e6)},
          {"evidence_faces", &c.evidence_faces, closed(0, 100)},
          {"evidence_window_m", &c.evidence_window_m, positive(1000)},
          {"evidence_max_scans", &c.evidence_max_scans, closed(1, 1e5)},
          {"evidence_spacing_m", &c.evidence_spacing_m, closed(0, 100)},
          {"evidence_spacing_deg", &c.evidence_spacing_deg, closed(0, 360)},
          {"evidence_max_candidates", &c.evidence_max_candidates, closed(1, 1e5)},
          {"evidence_proposals", &c.evidence_proposals, closed(1, 1e5)},
          {"evidence_drift_fraction", &c.evidence_drift_fraction, closed(0, 1)},
          {"evidence_yaw_drift_rad_per_m", &c.evidence_yaw_drift_rad_per_m, closed(0, 1)},
          {"evidence_plan_tolerance_m", &c.evidence_plan_tolerance_m, closed(0, 10)},
          {"evidence_injection_fraction", &c.evidence_injection_fraction, closed(0, 1)},
          {"resample_ess_fraction", &c.resample_ess_fraction, closed(0, 1)},
          {"roughening_xy_m", &c.roughening_xy_m, closed(0, 10)},
          {"roughening_yaw_deg", &c.roughening_yaw_deg, closed(0, 180)},
          {"converged_position_m", &c.converged_position_m, positive(100)},
          {"converged_yaw_deg", &c.converged_yaw_deg, positive(180)},
          {"converged_updates", &c.converged_updates, closed(1, 1000)},
          {"outside_rooms_penalty", &c.outside_rooms_penalty, closed(0, 1e6)},
          {"min_observations", &c.min_observations, closed(1, 100)},
          {"prior_sigma_m", &c.prior_sigma_m, closed(1e-3, 1e4)},
          {"prior_sigma_yaw_deg", &c.prior_sigma_yaw_deg, closed(0.01, 180)}};
}

std::vector<Field> sgraphFields(sgraph::SGraphConfig& c) {
  return {{"keyframe_spacing_m", &c.keyframe_spacing_m, positive(100)},
          {"keyframe_spacing_deg", &c.keyframe_spacing_deg, positive(360)},
          {"window_keyframes", &c.window_keyframes, closed(2, 1000)},
          {"plane_sigma_azimuth_deg", &c.plane_sigma_azimuth_deg, positive(90)},
          {"plane_sigma_elevation_deg", &c.plane_sigma_elevation_deg, positive(90)},
          {"plane_sigma_d_m", &c.plane_sigma_d_m, positive(10)},
          {"association_sigma_azimuth_deg", &c.association_sigma_azimuth_deg, positive(90)},
          {"association_sigma_d_m", &c.association_sigma_d_m, positive(10)},
          {"association_gate_mahalanobis2", &c.association_gate_mahalanobis2, positive(1e6)},
          {"segment_margin_m", &c.segment_margin_m, closed(0, 100)},
          {"new_plane_min_sightings", &c.new_plane_min_sightings, closed(1, 1000)},
          {"candidate_max_age_keyframes", &c.candidate_max_age_keyframes, closed(1, 1e5)},
          {"room_match_distance_m", &c.room_match_distance_m, positive(100)},
          {"merge_max_offset_m", &c.merge_max_offset_m, closed(0, 100)},
          {"odometry_sigma_xy_per_m", &c.odometry_sigma_xy_per_m, closed(0, 10)},
          {"odometry_sigma_xy_floor_m", &c.odometry_sigma_xy_floor_m, positive(10)},
          {"odometry_sigma_yaw_per_rad", &c.odometry_sigma_yaw_per_rad, closed(0, 10)},
          {"odometry_sigma_yaw_per_m_deg", &c.odometry_sigma_yaw_per_m_deg, closed(0, 90)},
          {"odometry_sigma_yaw_floor_deg", &c.odometry_sigma_yaw_floor_deg, positive(90)},
          {"odometry_jump_m", &c.odometry_jump_m, positive(1000)},
          {"odometry_jump_deg", &c.odometry_jump_deg, positive(360)},
          {"initial_sigma_xy_m", &c.initial_sigma_xy_m, positive(100)},
          {"initial_sigma_yaw_deg", &c.initial_sigma_yaw_deg, positive(180)},
          {"wall_prior_sigma_m", &c.wall_prior_sigma_m, positive(10)},
          {"wall_prior_sigma_deg", &c.wall_prior_sigma_deg, positive(90)},
          {"wall_thickness_sigma_m", &c.wall_thickness_sigma_m, positive(10)},
          {"room_prior_sigma_m", &c.room_prior_sigma_m, positive(100)},
          {"room_factor_sigma_m", &c.room_factor_sigma_m, positive(10)},
          {"wall_evidence_min_sigma_m", &c.wall_evidence_min_sigma_m, positive(10)},
          {"wall_evidence_min_sigma_deg", &c.wall_evidence_min_sigma_deg, positive(90)},
          {"huber_plane_sigmas", &c.huber_plane_sigmas, positive(1e3)},
          {"huber_odometry_sigmas", &c.huber_odometry_sigmas, positive(1e3)},
          {"huber_room_sigmas", &c.huber_room_sigmas, positive(1e3)},
          {"cauchy_wall_prior_sigmas", &c.cauchy_wall_prior_sigmas, positive(1e3)},
          {"max_iterations", &c.max_iterations, closed(1, 1000)},
          {"min_plan_associations", &c.min_plan_associations, closed(0, 100)},
          {"min_plan_fraction", &c.min_plan_fraction, closed(0, 1)},
          {"loss_mahalanobis2", &c.loss_mahalanobis2, positive(1e6)},
          {"loss_correction_m", &c.loss_correction_m, positive(100)},
          {"lost_after_keyframes", &c.lost_after_keyframes, closed(1, 1000)},
          {"recover_after_keyframes", &c.recover_after_keyframes, closed(1, 1000)}};
}

std::vector<Field> amclFields(peers::AmclConfig& c) {
  return {{"min_particles", &c.min_particles, closed(1, 1e6)},
          {"max_particles", &c.max_particles, closed(1, 1e6)},
          {"kld_err", &c.kld_err, positive(1)},
          {"kld_z", &c.kld_z, positive(10)},
          {"update_min_d_m", &c.update_min_d_m, closed(0, 100)},
          {"update_min_a_rad", &c.update_min_a_rad, closed(0, 2 * M_PI)},
          {"resample_interval", &c.resample_interval, closed(1, 1000)},
          {"recovery", &c.recovery},
          {"recovery_alpha_slow", &c.recovery_alpha_slow, closed(0, 1)},
          {"recovery_alpha_fast", &c.recovery_alpha_fast, closed(0, 1)},
          {"z_hit", &c.z_hit, closed(0, 1)},
          {"z_rand", &c.z_rand, closed(0, 1)},
          {"sigma_hit_m", &c.sigma_hit_m, positive(10)},
          {"likelihood_max_dist_m", &c.likelihood_max_dist_m, positive(100)},
          {"max_beams", &c.max_beams, closed(1, 100000)},
          {"laser_min_range_m", &c.laser_min_range_m, closed(0, 100)},
          {"laser_max_range_m", &c.laser_max_range_m, positive(1000)},
          {"odom_alpha1", &c.odom_alpha1, closed(0, 10)},
          {"odom_alpha2", &c.odom_alpha2, closed(0, 10)},
          {"odom_alpha3", &c.odom_alpha3, closed(0, 10)},
          {"odom_alpha4", &c.odom_alpha4, closed(0, 10)},
          {"band_min_m", &c.band_min_m, closed(-10, 10)},
          {"band_max_m", &c.band_max_m, closed(-10, 10)},
          {"map_resolution_m", &c.map_resolution_m, closed(0.01, 1)},
          {"map_doors", &c.map_doors},
          {"free_clearance_m", &c.free_clearance_m, closed(0, 10)},
          {"scan_angle_increment_deg", &c.scan_angle_increment_deg, closed(0.05, 10)},
          {"use_initial_pose", &c.use_initial_pose},
          {"initial_pose_x_m", &c.initial_pose_x_m, closed(-1e6, 1e6)},
          {"initial_pose_y_m", &c.initial_pose_y_m, closed(-1e6, 1e6)},
          {"initial_pose_yaw_deg", &c.initial_pose_yaw_deg, closed(-360, 360)},
          {"initial_sigma_xy_m", &c.initial_sigma_xy_m, closed(0, 1e4)},
          {"initial_sigma_yaw_deg", &c.initial_sigma_yaw_deg, closed(0, 180)},
          {"converged_xy_std_m", &c.converged_xy_std_m, positive(100)},
          {"converged_yaw_std_deg", &c.converged_yaw_std_deg, positive(180)},
          {"lost_xy_std_m", &c.lost_xy_std_m, positive(100)},
          {"lost_yaw_std_deg", &c.lost_yaw_std_deg, positive(180)}};
}

std::vector<Field> ndtFields(peers::NdtConfig& c) {
  return {{"map_spacing_m", &c.map_spacing_m, closed(0.02, 2)},
          {"ndt_resolution_m", &c.ndt_resolution_m, closed(0.1, 10)},
          {"ndt_step_size_m", &c.ndt_step_size_m, positive(10)},
          {"ndt_max_iterations", &c.ndt_max_iterations, closed(1, 1000)},
          {"ndt_epsilon_m", &c.ndt_epsilon_m, positive(1)},
          {"downsample_m", &c.downsample_m, closed(0.01, 2)},
          {"ndt_max_points", &c.ndt_max_points, closed(10, 1e7)},
          {"max_range_m", &c.max_range_m, positive(1000)},
          {"update_min_d_m", &c.update_min_d_m, closed(0, 100)},
          {"update_min_a_rad", &c.update_min_a_rad, closed(0, 2 * M_PI)},
          {"fitness_max_distance_m", &c.fitness_max_distance_m, positive(100)},
          {"max_fitness_m2", &c.max_fitness_m2, positive(100)},
          {"min_inlier_fraction", &c.min_inlier_fraction, closed(0, 1)},
          {"lost_after_bad_scans", &c.lost_after_bad_scans, closed(1, 1e6)},
          {"grid_resolution_m", &c.grid_resolution_m, closed(0.05, 10)},
          {"pyramid_levels", &c.pyramid_levels, closed(1, 12)},
          {"scan_min_z_m", &c.scan_min_z_m, closed(-10, 10)},
          {"scan_max_z_m", &c.scan_max_z_m, closed(-10, 10)},
          {"base_height_m", &c.base_height_m, closed(-10, 10)},
          {"global_window_m", &c.global_window_m, closed(0, 1000)},
          {"global_period_s", &c.global_period_s, closed(0, 1e4)},
          {"min_scan_cells", &c.min_scan_cells, closed(1, 1e6)},
          {"min_hit_fraction", &c.min_hit_fraction, closed(0, 1)},
          {"min_margin_fraction", &c.min_margin_fraction, closed(0, 1)},
          {"distinct_m", &c.distinct_m, closed(0, 1000)},
          {"distinct_deg", &c.distinct_deg, closed(0, 180)}};
}

// The field named `key` of `fields`, under another name (an alias keeps its field's range).
Field alias(const std::string& name, const std::vector<Field>& fields, const std::string& key) {
  for (const Field& f : fields)
    if (f.key == key) return {name, f.target, f.range};
  throw std::logic_error("no localizer field " + key);
}

std::vector<Field> topFields(LocalizerConfig& c) {
  const auto pf = pfFields(c.pf);
  return {{"relocalize_sigma_m", &c.relocalize_sigma_m, positive(1e4)},
          {"relocalize_sigma_yaw_deg", &c.relocalize_sigma_yaw_deg, positive(180)},
          alias("prior_sigma_m", pf, "prior_sigma_m"),
          alias("prior_sigma_yaw_deg", pf, "prior_sigma_yaw_deg"),
          // The flat keys of the first scenarios, kept.
          alias("particles", pf, "particles"),
          alias("sigma_d_m", pf, "sigma_d_m"),
          alias("sigma_azimuth_deg", pf, "sigma_azimuth_deg"),
          alias("converged_updates", pf, "converged_updates"),
          alias("voxel_size_m", planeFields(c.planes), "voxel_size_m")};
}

const std::vector<std::string> kOtherTopKeys{"method", "storey", "prior_rooms", "prior_pose", "planes", "pf", "sgraph", "amcl", "ndt"};

struct Reader {
  const std::string& file;
  const std::map<std::string, int>& lines;

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    const auto it = lines.find(key);
    detail::fail(file, it == lines.end() ? 0 : it->second, key + ": " + message);
  }

  void set(const Field& f, const nlohmann::json& value, const std::string& name) const {
    if (std::holds_alternative<bool*>(f.target)) {
      if (!value.is_boolean()) fail(name, "expected true or false, got " + value.dump());
      *std::get<bool*>(f.target) = value.get<bool>();
      return;
    }
    if (!value.is_number()) fail(name, "expected a number, got " + value.dump());
    const double v = value.get<double>();
    if (!std::isfinite(v) || !f.range.contains(v)) fail(name, value.dump() + " is outside " + f.range.str());
    if (auto* i = std::get_if<int*>(&f.target)) {
      if (v != std::floor(v)) fail(name, "expected a whole number, got " + value.dump());
      **i = static_cast<int>(v);
    } else {
      *std::get<double*>(f.target) = v;
    }
  }

  // Every key of `block` must be one of `fields` (or of `others`, read by the caller).
  void section(const nlohmann::json& block, const std::string& prefix, const std::vector<Field>& fields,
               const std::vector<std::string>& others = {}) const {
    if (!block.is_object()) fail(prefix, "expected a mapping (key: value lines)");
    std::vector<std::string> keys = others;
    for (const Field& f : fields) keys.push_back(f.key);
    for (const auto& [key, value] : block.items()) {
      const std::string name = prefix + "." + key;
      bool done = std::find(others.begin(), others.end(), key) != others.end();
      for (const Field& f : fields)
        if (f.key == key) set(f, value, name), done = true;
      if (!done) {
        const std::string guess = detail::nearestWord(key, keys);
        std::string list;
        for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
        fail(name, "unknown key" + (guess.empty() ? " (keys of " + prefix + ": " + list + ")" : " (did you mean '" + guess + "'?)"));
      }
    }
  }
};

}  // namespace

LocalizerSettings readLocalizerSettings(const nlohmann::json& block, const std::string& file, const std::map<std::string, int>& lines) {
  LocalizerSettings out;
  LocalizerConfig& c = out.config;
  const Reader read{file, lines};
  if (block.is_null()) return out;
  read.section(block, "localizer", topFields(c), kOtherTopKeys);
  if (block.contains("method")) {
    const auto& v = block["method"];
    const auto m = v.is_string() ? methodFromString(v.get<std::string>()) : std::nullopt;
    if (!m) read.fail("localizer.method", "expected sgraph, pf, pf-no-rooms, amcl or ndt, got " + v.dump());
    c.method = *m;
  }
  if (block.contains("storey")) {
    // The localizer is not told the storey; the storey itself is the scenario's `storey:`.
    if (block["storey"] != "auto") read.fail("localizer.storey", "only 'auto' (the storey found from the scans); the simulator's storey is the scenario's `storey:`");
    out.storey_auto = true;
  }
  if (block.contains("prior_rooms")) {
    // The start was in one of these rooms (what a user knows: "we start in flat B").
    const auto& v = block["prior_rooms"];
    const auto list = v.is_string() ? nlohmann::json::array({v}) : v;
    if (!list.is_array() || list.empty()) read.fail("localizer.prior_rooms", "expected a room name or a list of them");
    for (const auto& r : list) {
      if (!r.is_string()) read.fail("localizer.prior_rooms", "expected room names, got " + r.dump());
      c.pf.prior_rooms.push_back(r.get<std::string>());
    }
  }
  if (block.contains("prior_pose")) {
    // [x, y, yaw_deg] of the start in the map frame; prior_sigma_m and prior_sigma_yaw_deg widen it.
    const auto& v = block["prior_pose"];
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
      read.fail("localizer.prior_pose", "expected [x, y, yaw_deg], got " + v.dump());
    c.pf.prior_pose = Eigen::Vector3d(v[0].get<double>(), v[1].get<double>(), v[2].get<double>() * M_PI / 180.0);
    if (!c.pf.prior_pose->allFinite()) read.fail("localizer.prior_pose", "not finite");
  }
  if (block.contains("planes")) read.section(block["planes"], "localizer.planes", planeFields(c.planes));
  if (block.contains("pf")) read.section(block["pf"], "localizer.pf", pfFields(c.pf));
  if (block.contains("sgraph")) read.section(block["sgraph"], "localizer.sgraph", sgraphFields(c.sgraph));
  if (block.contains("amcl")) read.section(block["amcl"], "localizer.amcl", amclFields(c.amcl));
  if (block.contains("ndt")) read.section(block["ndt"], "localizer.ndt", ndtFields(c.ndt));
  return out;
}

void recordLines(const std::string& prefix, const YAML::Node& node, std::map<std::string, int>& lines) {
  if (!node.IsMap()) return;
  for (const auto& kv : node) {
    if (!kv.first.IsScalar()) continue;
    const std::string name = prefix + "." + kv.first.Scalar();
    lines[name] = detail::lineOf(kv.first);
    recordLines(name, kv.second, lines);
  }
}

nlohmann::json loadLocalizerBlock(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw ScenarioError(path + ": no such config file");
  YAML::Node doc;
  try {
    doc = YAML::LoadFile(path);
  } catch (const YAML::ParserException& e) {
    detail::fail(path, e.mark.line >= 0 ? e.mark.line + 1 : 0, "YAML syntax error: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw ScenarioError(path + ": cannot read the config file");
  }
  if (!doc.IsNull() && !doc.IsMap()) detail::fail(path, detail::lineOf(doc), "expected a mapping of localizer keys");
  std::map<std::string, int> lines;
  recordLines("localizer", doc, lines);
  nlohmann::json block = doc.IsNull() ? nlohmann::json::object() : detail::toJson(path, doc);
  readLocalizerSettings(block, path, lines);
  return block;
}

LocalizerSettings loadLocalizerConfig(const std::string& path) { return readLocalizerSettings(loadLocalizerBlock(path), path, {}); }

std::vector<std::pair<std::string, std::string>> localizerKeys(const LocalizerConfig& config) {
  LocalizerConfig c = config;  // the fields point into this copy
  std::vector<std::pair<std::string, std::string>> out;
  const auto add = [&out](const std::string& prefix, const std::vector<Field>& fields) {
    for (const Field& f : fields) {
      std::ostringstream v;
      std::visit([&v](auto* p) { v << std::boolalpha << *p; }, f.target);
      out.emplace_back(prefix + f.key, v.str());
    }
  };
  add("", topFields(c));
  add("planes.", planeFields(c.planes));
  add("pf.", pfFields(c.pf));
  add("sgraph.", sgraphFields(c.sgraph));
  add("amcl.", amclFields(c.amcl));
  add("ndt.", ndtFields(c.ndt));
  out.emplace_back("method", toString(c.method));
  out.emplace_back("storey", "auto, or told by the caller");
  out.emplace_back("prior_rooms", "[]");
  out.emplace_back("prior_pose", "none; [x, y, yaw_deg]");
  return out;
}

}  // namespace bimloc::sim
