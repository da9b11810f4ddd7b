// The one place that speaks IFC++: parses the plan and converts its geometry to a RawModel.
#pragma once

#include "ifc_file.hpp"
#include "raw_model.hpp"

namespace bimloc::bim::detail {

// Throws BimError when IFC++ cannot make a model of the text.
RawModel readRawModel(const PlanText& plan, const std::string& path);

}  // namespace bimloc::bim::detail
