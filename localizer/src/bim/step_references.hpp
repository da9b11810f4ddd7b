// The entity references each instance of a STEP file names in its text. IFC++ turns a
// reference to an entity of the wrong type (a polyline point that is a polyline, a profile or
// an IfcSpace) into a null pointer, which its geometry converter then dereferences: comparing
// what the text names with what IFC++ resolved finds every such instance before conversion.
#pragma once

#include <string>
#include <utility>
#include <vector>

namespace bimloc::bim::detail {

// (instance id, number of '#N' references among its arguments, outside strings and comments),
// sorted by id, for the instances that name at least one.
std::vector<std::pair<int, int>> stepReferenceCounts(const std::string& text);

}  // namespace bimloc::bim::detail
