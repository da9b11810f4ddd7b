// Reading a plan's bytes and checking, before any parser sees them, that they are a complete
// ISO-10303-21 (STEP) file: a parser handed garbage or half a file gives nothing useful.
#pragma once

#include <string>
#include <vector>

namespace bimloc::bim::detail {

struct PlanText {
  std::string text;    // an IFC 4.3 file's rewritten as IFC4 (ifc4x3.hpp)
  std::string schema;  // from FILE_SCHEMA: "IFC2X3", "IFC4" or "IFC4X3"
  std::vector<std::string> warnings;  // what reading it as it is read changed
};

// Throws BimError "PATH: problem" for a missing, unreadable, empty, binary, non-STEP,
// truncated or non-IFC file.
PlanText readPlanText(const std::string& path);

}  // namespace bimloc::bim::detail
