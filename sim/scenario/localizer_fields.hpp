// The localizer's settable fields, section by section: each YAML key of a `localizer:` block (or
// `--config FILE.yaml`), the field of LocalizerConfig it sets, and its range. One table per stage,
// read by sim/scenario/localizer_config.cpp; the tables only, no parsing.
#pragma once

#include <bimloc/localizer.hpp>

#include "sim/scenario/yaml_mapping.hpp"

#include <string>
#include <variant>
#include <vector>

namespace bimloc::sim::fields {

using detail::Range;

// One settable field: where it lives, its range (integers and booleans are numbers here too).
struct Field {
  std::string key;
  std::variant<double*, int*, bool*> target;
  Range range = Range::closed(-1e12, 1e12);
};

std::vector<Field> planeFields(planes::PlaneExtractionConfig& c);
std::vector<Field> pfFields(pf::ParticleFilterConfig& c);
std::vector<Field> sgraphFields(sgraph::SGraphConfig& c);
std::vector<Field> amclFields(peers::AmclConfig& c);
std::vector<Field> ndtFields(peers::NdtConfig& c);
std::vector<Field> storeyFields(storeys::StoreyFollowConfig& c);

}  // namespace bimloc::sim::fields
