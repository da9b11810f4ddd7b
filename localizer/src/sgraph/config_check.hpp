#pragma once

#include <bimloc/sgraph/sgraph_tracker.hpp>

#include <string>
#include <vector>

namespace bimloc::sgraph::detail {

// The config with every unusable value replaced by its default, each named in `warnings`.
SGraphConfig checkedConfig(const SGraphConfig& config, std::vector<std::string>& warnings);

}  // namespace bimloc::sgraph::detail
