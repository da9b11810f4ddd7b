// What the text of a STEP file says, read independently of IFC++: each instance's id, line,
// type and the '#N' references among its arguments, and the values no number can be. IFC++
// turns a reference to an entity of the wrong type (a polyline point that is a polyline, a
// profile or an IfcSpace) into a null pointer, drops instances it cannot read, keeps one of two
// instances with the same id and follows reference cycles without end: comparing its model with
// what the text names is how every such instance is found before the geometry converter runs.
#pragma once

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace bimloc::bim::detail {

struct StepInstance {
  int id = 0;
  int line = 0;              // 1-based line of the '#N='
  std::string type;          // the entity type as written, e.g. IFCPOLYLINE
  std::vector<int> refs;     // '#N' among its arguments, outside strings and comments, in order
  std::string problem;       // its first value that cannot be read: "holds 'NaN', which is no finite number"
};

struct StepScan {
  std::vector<StepInstance> instances;  // sorted by id, then by line (a duplicate id follows)
  std::vector<std::string> malformed;   // "line L: ..." for DATA statements that are no instance
};

StepScan scanStep(const std::string& text);

// (instance id, number of '#N' references among its arguments), sorted by id, for the
// instances that name at least one.
std::vector<std::pair<int, int>> stepReferenceCounts(const std::string& text);

// Each instance the text itself shows to be unusable, by id, with why: defined more than once,
// holding a non-finite or unreadable value, or on a cycle of references (a placement relative to
// itself through others, a boolean operand that is its own result).
std::map<int, std::string> stepProblems(const StepScan& scan);

}  // namespace bimloc::bim::detail
