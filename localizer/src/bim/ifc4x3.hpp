// IFC 4.3 (FILE_SCHEMA IFC4X3, ISO 16739-1:2024) read through IFC4's schema. The IFC++ that
// Debian ships knows IFC2X3 and IFC4 only, and reads not one entity of a file that names IFC4X3.
// IFC 4.3 keeps IFC4's building entities with their attributes, but for seven whose attribute
// lists it changed, and adds entities (alignments, infrastructure, IfcBuiltElement): the text
// is rewritten to IFC4's where the two differ (thirteen rewrites, ifc4x3.cpp), and what IFC4
// has no entity for is left to the reader, which skips and names it like any instance it
// cannot read.
#pragma once

#include <string>
#include <vector>

namespace bimloc::bim::detail {

struct Ifc4x3AsIfc4 {
  std::string text;                   // FILE_SCHEMA 'IFC4', the rewritten instances in place, every line where it was
  std::vector<std::string> warnings;  // what was rewritten, by entity type and count
};

// The rewrite, by the table in ifc4x3.cpp (an instance already written as IFC4 writes it is
// left as it is). `schema` is the file's FILE_SCHEMA, for the warning.
Ifc4x3AsIfc4 rewriteIfc4x3AsIfc4(const std::string& text, const std::string& schema);

}  // namespace bimloc::bim::detail
