// The check of a --site / --sites value: a typo gets the nearest preset, as in scenario files.
#pragma once

#include "sim/scenario/yaml_mapping.hpp"
#include "sim/world/site_config.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <string>

namespace bimloc::cli {

inline CLI::Validator sitePresetCheck() {
  return CLI::Validator(
      [](std::string& v) {
        const auto& names = sim::sitePresetNames();
        if (std::find(names.begin(), names.end(), v) != names.end()) return std::string();
        const std::string guess = sim::detail::nearestWord(v, names);
        return "no site preset '" + v + "' (exact, as_built, construction, heavy)" +
               (guess.empty() ? std::string() : "; did you mean '" + guess + "'?");
      },
      "PRESET");
}

}  // namespace bimloc::cli
