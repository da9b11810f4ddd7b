#include "sim/common/json_errors.hpp"

#include <nlohmann/json.hpp>

namespace bimloc::sim {

std::string jsonProblem(const std::exception& e) {
  const auto* error = dynamic_cast<const nlohmann::json::exception*>(&e);
  std::string text = e.what();
  if (!error) return text;
  // Drop the "[json.exception.KIND.ID] " prefix: it is the library's, not the user's.
  if (text.rfind("[json.exception.", 0) == 0) {
    const auto close = text.find("] ");
    if (close != std::string::npos) text = text.substr(close + 2);
  }
  if (dynamic_cast<const nlohmann::json::parse_error*>(error)) return "not valid JSON: " + text;
  if (dynamic_cast<const nlohmann::json::out_of_range*>(error) && error->id == 403) {  // key 'X' not found
    const auto first = text.find('\''), last = text.rfind('\'');
    if (first != std::string::npos && last > first) return "missing key " + text.substr(first, last - first + 1);
  }
  if (dynamic_cast<const nlohmann::json::out_of_range*>(error) && error->id == 401) return "an array is too short (" + text + ")";
  if (dynamic_cast<const nlohmann::json::type_error*>(error)) return "a value of the wrong type (" + text + ")";
  return text;
}

}  // namespace bimloc::sim
