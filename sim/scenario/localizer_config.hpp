// The `localizer:` mapping of a scenario, and `--config FILE.yaml` of `bimloc run` and
// `bimloc localize`, mapped key by key onto bimloc::LocalizerConfig:
//
//   localizer:
//     method: sgraph            # sgraph | pf | pf-no-rooms
//     storey: auto              # not told the storey (the scenario's storey is the simulator's)
//     prior_rooms: [B.01]       # prior_pose: [x, y, yaw_deg], prior_sigma_m, prior_sigma_yaw_deg
//     planes: {voxel_size_m: 0.1, ...}     # every field of planes::PlaneExtractionConfig
//     pf: {particles: 6000, ...}           # every field of pf::ParticleFilterConfig
//     sgraph: {window_keyframes: 10, ...}  # every field of sgraph::SGraphConfig
//     storeys: {floor_tolerance_m: 0.6, ...}  # every field of storeys::StoreyFollowConfig
//     relocalize_sigma_m: 2.0
//
// The flat keys of earlier scenarios (particles, sigma_d_m, sigma_azimuth_deg,
// converged_updates, voxel_size_m) still work. Every key has a type and a range; an unknown
// key, a wrong type or a value out of range is a ScenarioError at FILE:LINE.
#pragma once

#include "sim/scenario/scenario.hpp"

#include <bimloc/localizer.hpp>

#include <yaml-cpp/yaml.h>

#include <map>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

namespace bimloc::sim {

struct LocalizerSettings {
  LocalizerConfig config;    // its seed and storey are the caller's to set
  bool storey_auto = false;  // storey: auto
};

// `block` over the defaults. `lines` holds the line of each dotted key (prefix "localizer.",
// as loadScenario records them); a key without one is reported at the file.
LocalizerSettings readLocalizerSettings(const nlohmann::json& block, const std::string& file, const std::map<std::string, int>& lines);

// The line of every key under the YAML mapping `node` into `lines`, named `prefix.key.subkey`.
void recordLines(const std::string& prefix, const YAML::Node& node, std::map<std::string, int>& lines);

// A `--config FILE.yaml`: a YAML mapping whose keys are those of `localizer:`, checked (errors
// at FILE:LINE of the config), as the block a scenario's `localizer:` would hold.
nlohmann::json loadLocalizerBlock(const std::string& path);
LocalizerSettings loadLocalizerConfig(const std::string& path);

// Every numeric or boolean key `localizer:` takes, dotted ("pf.particles"), with its value in
// `config` (the defaults unless given), for the README and the tests; then method, storey and
// the prior's lists.
std::vector<std::pair<std::string, std::string>> localizerKeys(const LocalizerConfig& config = {});

}  // namespace bimloc::sim
