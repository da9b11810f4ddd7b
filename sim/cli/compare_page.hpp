// The page of `bimloc compare --out DIR`: DIR/index.html, the comparison in one page that
// opens from the file system (no server, no network: the style and the script are inline,
// the pictures are files beside it). The verdict first, then the table per method with the
// best in each column highlighted, the two figures, the tables per start room whose values
// link to the runs, and every run's pictures (snapshots and error plot) per method.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace bimloc::cli {

// The page, from compareReport's object alone (its pictures' paths relative to the page).
std::string comparePage(const nlohmann::json& report);

// DIR/index.html, written atomically.
void writeComparePage(const nlohmann::json& report, const std::string& dir);

// The anchor of a run's method on the page (letters, digits, '-', '_').
std::string runAnchor(const std::string& run_name, const std::string& method);

}  // namespace bimloc::cli
