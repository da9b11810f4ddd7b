#include "ifc_file.hpp"

#include "ifc4x3.hpp"

#include <bimloc/bim/ifc_reader.hpp>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <sys/stat.h>

namespace bimloc::bim::detail {
namespace {

[[noreturn]] void fail(const std::string& path, const std::string& problem) {
  throw BimError(path + ": " + problem);
}

std::string readAll(const std::string& path) {
  struct stat info {};
  if (::stat(path.c_str(), &info) != 0) fail(path, std::string("cannot open: ") + std::strerror(errno));
  if (S_ISDIR(info.st_mode)) fail(path, "cannot read: is a directory");
  std::ifstream in(path, std::ios::binary);
  if (!in) fail(path, std::string("cannot open: ") + std::strerror(errno));
  std::ostringstream buffer;
  buffer << in.rdbuf();
  if (in.bad()) fail(path, "read error");
  return buffer.str();
}

std::size_t skipBlank(const std::string& text, std::size_t pos) {
  // A UTF-8 byte order mark, then whitespace.
  if (text.compare(pos, 3, "\xEF\xBB\xBF") == 0) pos += 3;
  while (pos < text.size() && std::isspace(static_cast<unsigned char>(text[pos]))) ++pos;
  return pos;
}

std::string fileSchema(const std::string& path, const std::string& text) {
  const auto header_end = text.find("ENDSEC;");
  const auto at = text.find("FILE_SCHEMA");
  if (at == std::string::npos || at > header_end) fail(path, "not an IFC file: no FILE_SCHEMA in the STEP header");
  const auto open = text.find('\'', at);
  const auto close = open == std::string::npos ? open : text.find('\'', open + 1);
  if (close == std::string::npos) fail(path, "not an IFC file: unreadable FILE_SCHEMA");
  std::string schema = text.substr(open + 1, close - open - 1);
  std::transform(schema.begin(), schema.end(), schema.begin(), ::toupper);
  if (schema.rfind("IFC2X3", 0) == 0) return "IFC2X3";
  // IFC 4.3 (ISO 16739-1:2024) is read through IFC4 (ifc4x3.hpp). IFC4X1 and IFC4X2 were drafts
  // for alignments and bridges, schemas of their own: the IFC++ that Debian ships knows none of
  // them and read not one entity ("Unsupported IFC version: ").
  if (schema.rfind("IFC4X3", 0) == 0) return schema;
  if (schema.rfind("IFC4X", 0) == 0)
    fail(path, "unsupported schema '" + schema + "' (bimloc reads IFC2X3, IFC4 and IFC4X3; export the plan as one of them)");
  if (schema.rfind("IFC4", 0) == 0) return "IFC4";
  fail(path, "unsupported schema '" + schema + "' (bimloc reads IFC2X3, IFC4 and IFC4X3)");
}

}  // namespace

PlanText readPlanText(const std::string& path) {
  std::string text = readAll(path);
  if (text.empty()) fail(path, "empty file");
  // STEP files are 7-bit text; a NUL byte means binary data (or a zipped .ifcZIP).
  if (text.find('\0') != std::string::npos) fail(path, "not an IFC file: binary data");
  const auto begin = skipBlank(text, 0);
  if (text.compare(begin, 13, "ISO-10303-21;") != 0)
    fail(path, "not an IFC file: does not start with ISO-10303-21;");
  const auto end = text.rfind("END-ISO-10303-21;");
  if (end == std::string::npos) fail(path, "truncated: no END-ISO-10303-21; at the end of the file");
  if (text.find("DATA;") == std::string::npos) fail(path, "not an IFC file: no DATA section");
  std::string schema = fileSchema(path, text);
  if (schema.rfind("IFC4X3", 0) != 0) return {std::move(text), std::move(schema), {}};
  Ifc4x3AsIfc4 as_ifc4 = rewriteIfc4x3AsIfc4(text, schema);
  return {std::move(as_ifc4.text), "IFC4X3", std::move(as_ifc4.warnings)};
}

}  // namespace bimloc::bim::detail
