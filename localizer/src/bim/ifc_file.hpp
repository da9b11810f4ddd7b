// Reading a plan's bytes and checking, before any parser sees them, that they are a complete
// ISO-10303-21 (STEP) file: a parser handed garbage or half a file gives nothing useful.
#pragma once

#include <string>

namespace bimloc::bim::detail {

struct PlanText {
  std::string text;
  std::string schema;  // from FILE_SCHEMA: "IFC2X3" or "IFC4"
};

// Throws BimError "PATH: problem" for a missing, unreadable, empty, binary, non-STEP,
// truncated or non-IFC file.
PlanText readPlanText(const std::string& path);

}  // namespace bimloc::bim::detail
