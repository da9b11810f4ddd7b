// nlohmann::json says what went wrong in its own words ("[json.exception.out_of_range.403]
// key 'T_base_lidar' not found"); a user of bimloc gets them in ours ("missing key
// 'T_base_lidar'"), after the file name the caller puts first.
#pragma once

#include <exception>
#include <string>

namespace bimloc::sim {

// The problem of an exception thrown while reading or using a JSON document; other
// exceptions pass through as their what().
std::string jsonProblem(const std::exception& e);

}  // namespace bimloc::sim
