#include "sim/runner/run_scenario.hpp"

namespace bimloc::sim {

LocalizerSettings localizerSettings(const Scenario& s) {
  LocalizerSettings out = readLocalizerSettings(s.localizer, s.file, s.lines);
  out.config.seed = s.seed;  // every stage seeded from the scenario's seed (Localizer derives them)
  return out;
}

}  // namespace bimloc::sim
