#include "ifc4x3.hpp"

#include <algorithm>
#include <array>
#include <cctype>
#include <cstddef>
#include <map>
#include <string_view>

namespace bimloc::bim::detail {
// Named, not anonymous: the unity build compiles this file in one unit with others, whose
// anonymous helpers could share these names.
namespace ifc4x3_text {

// Where IFC 4.3 (IFC4X3_ADD2) and IFC4 (ADD2 TC1) differ for an entity both have, or 4.3 has an
// entity IFC4 reads under another name: the attribute lists of the two schemas compared entity
// by entity (every other common entity has the same attributes in the same order, but for
// renames of the same type and place). `args` is the count in IFC 4.3; an instance with any
// other count is left as written (an exporter that writes IFC4's lists under a 4.3 header).
struct Rule {
  std::string_view type;     // as written in the file, upper case
  std::string_view name;     // for the warning
  std::size_t args;          // attributes in IFC 4.3
  std::string_view as;       // the IFC4 entity written instead; empty: the same
  std::vector<std::size_t> drop;  // attributes (0-based) IFC4 does not have
  std::string_view append;   // an attribute IFC4 has after them and IFC 4.3 does not; empty: none
  std::string_view what;     // the rewrite, for the warning
};

const std::vector<Rule>& rules() {
  static const std::vector<Rule> table = {
      {"IFCCARTESIANPOINTLIST2D", "IfcCartesianPointList2D", 2, "", {1}, "", "TagList dropped"},
      {"IFCCARTESIANPOINTLIST3D", "IfcCartesianPointList3D", 2, "", {1}, "", "TagList dropped"},
      {"IFCANNOTATION", "IfcAnnotation", 8, "", {7}, "", "PredefinedType dropped"},
      {"IFCDERIVEDUNIT", "IfcDerivedUnit", 4, "", {3}, "", "Name dropped"},
      {"IFCGRIDPLACEMENT", "IfcGridPlacement", 3, "", {0}, "", "PlacementRelTo dropped"},
      {"IFCRELINTERFERESELEMENTS", "IfcRelInterferesElements", 10, "", {9}, "", "InterferenceSpace dropped"},
      {"IFCVIRTUALELEMENT", "IfcVirtualElement", 9, "", {8}, "", "PredefinedType dropped"},
      // IFC 4.3 before ADD2 gave IfcMapConversion ScaleY and ScaleZ; ADD2 moved them to a subtype.
      {"IFCMAPCONVERSION", "IfcMapConversion", 10, "", {8, 9}, "", "ScaleY, ScaleZ dropped"},
      {"IFCMAPCONVERSIONSCALED", "IfcMapConversionScaled", 11, "IFCMAPCONVERSION", {8, 9, 10}, "",
       "as IfcMapConversion, FactorX-Z dropped"},
      // IFC 4.3's generic built element is IFC4's proxy: the same attributes, and a predefined type.
      {"IFCBUILTELEMENT", "IfcBuiltElement", 8, "IFCBUILDINGELEMENTPROXY", {}, "$", "as IfcBuildingElementProxy"},
      {"IFCBUILTELEMENTTYPE", "IfcBuiltElementType", 9, "IFCBUILDINGELEMENTPROXYTYPE", {}, ".NOTDEFINED.",
       "as IfcBuildingElementProxyType"},
      {"IFCTRIANGULATEDIRREGULARNETWORK", "IfcTriangulatedIrregularNetwork", 6, "IFCTRIANGULATEDFACESET", {5}, "",
       "as IfcTriangulatedFaceSet, Flags dropped"},
  };
  return table;
}

bool isStepBlank(char c) { return c == ' ' || c == '\t' || c == '\r' || c == '\n' || c == '\f' || c == '\v'; }
bool isTypeChar(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

// Past the /* comment */ that starts at `p`; `p` itself where none does.
std::size_t pastComment(const std::string& t, std::size_t p) {
  if (p + 1 >= t.size() || t[p] != '/' || t[p + 1] != '*') return p;
  const auto close = t.find("*/", p + 2);
  return close == std::string::npos ? t.size() : close + 2;
}

// Past blanks and comments from `p`.
std::size_t pastBlank(const std::string& t, std::size_t p) {
  for (;;) {
    while (p < t.size() && isStepBlank(t[p])) ++p;
    const std::size_t after = pastComment(t, p);
    if (after == p) return p;
    p = after;
  }
}

// Past a quoted string ('' inside is a quote; "..." is a binary) starting at `p`.
std::size_t pastString(const std::string& t, std::size_t p) {
  const char quote = t[p];
  for (++p; p < t.size(); ++p)
    if (t[p] == quote) {
      if (quote == '\'' && p + 1 < t.size() && t[p + 1] == '\'') {
        ++p;
        continue;
      }
      return p + 1;
    }
  return t.size();
}

// The arguments of the list opened at `open` ('('): each one's [begin, end), and the closing
// parenthesis; npos when the list does not close.
std::size_t splitArguments(const std::string& t, std::size_t open, std::vector<std::pair<std::size_t, std::size_t>>& args) {
  args.clear();
  int depth = 0;
  std::size_t start = open + 1;
  for (std::size_t p = open; p < t.size();) {
    const char c = t[p];
    if (c == '\'' || c == '"') {
      p = pastString(t, p);
      continue;
    }
    if (const std::size_t after = pastComment(t, p); after != p) {
      p = after;
      continue;
    }
    if (c == ';') return std::string::npos;  // a statement ends inside the list: not one to rewrite
    if (c == '(') ++depth;
    if (c == ')' && --depth == 0) {
      if (pastBlank(t, start) < p || !args.empty()) args.emplace_back(start, p);
      return p;
    }
    if (c == ',' && depth == 1) args.emplace_back(start, p), start = p + 1;
    ++p;
  }
  return std::string::npos;
}

std::string_view trimmedArgument(const std::string& t, std::pair<std::size_t, std::size_t> a) {
  while (a.first < a.second && isStepBlank(t[a.first])) ++a.first;
  while (a.second > a.first && isStepBlank(t[a.second - 1])) --a.second;
  return std::string_view(t).substr(a.first, a.second - a.first);
}

bool isLogical(std::string_view v) { return v == ".T." || v == ".F." || v == ".U." || v == ".t." || v == ".f." || v == ".u."; }

// Past the statement that starts at `p` (its ';' outside strings and comments).
std::size_t pastStatement(const std::string& t, std::size_t p) {
  while (p < t.size()) {
    const char c = t[p];
    if (c == '\'' || c == '"') {
      p = pastString(t, p);
    } else if (const std::size_t after = pastComment(t, p); after != p) {
      p = after;
    } else if (c == ';') {
      return p + 1;
    } else {
      ++p;
    }
  }
  return p;
}

}  // namespace ifc4x3_text

Ifc4x3AsIfc4 rewriteIfc4x3AsIfc4(const std::string& text, const std::string& schema) {
  using namespace ifc4x3_text;
  Ifc4x3AsIfc4 out;
  std::vector<std::size_t> rewritten(rules().size(), 0);  // instances, by rule
  std::string& o = out.text;
  o.reserve(text.size());
  // FILE_SCHEMA's first name, as IFC4.
  std::size_t copied = 0;
  const auto header_end = text.find("ENDSEC;");
  const auto at = text.find("FILE_SCHEMA");
  if (at != std::string::npos && at < header_end) {
    const auto open = text.find('\'', at), close = open == std::string::npos ? open : text.find('\'', open + 1);
    if (close != std::string::npos && close < header_end && text.find('\n', open) > close)
      o.append(text, 0, open + 1), o += "IFC4", copied = close;
  }
  const auto data = text.find("DATA;", header_end == std::string::npos ? 0 : header_end);
  std::vector<std::pair<std::size_t, std::size_t>> args;
  std::size_t triangulated_reordered = 0;
  for (std::size_t p = data == std::string::npos ? text.size() : data + 5; p < text.size();) {
    p = pastBlank(text, p);
    if (p >= text.size() || text.compare(p, 6, "ENDSEC") == 0) break;
    const std::size_t next = pastStatement(text, p);
    if (text[p] != '#') {
      p = next;
      continue;
    }
    ++p;
    while (p < text.size() && std::isdigit(static_cast<unsigned char>(text[p]))) ++p;
    p = pastBlank(text, p);
    if (p >= text.size() || text[p] != '=') {
      p = next;
      continue;
    }
    p = pastBlank(text, p + 1);
    const std::size_t type_begin = p;
    while (p < text.size() && isTypeChar(text[p])) ++p;
    const std::size_t type_end = p;
    // The type in upper case, without an allocation per instance: no rule's name is this long.
    std::array<char, 40> upper{};
    if (type_end - type_begin >= upper.size()) {
      p = next;
      continue;
    }
    for (std::size_t k = type_begin; k < type_end; ++k)
      upper[k - type_begin] = static_cast<char>(std::toupper(static_cast<unsigned char>(text[k])));
    const std::string_view type(upper.data(), type_end - type_begin);
    p = pastBlank(text, p);
    const auto rule = std::find_if(rules().begin(), rules().end(), [&](const Rule& r) { return r.type == type; });
    const bool triangulated = type == "IFCTRIANGULATEDFACESET";
    if (type.empty() || p >= text.size() || text[p] != '(' || (rule == rules().end() && !triangulated)) {
      p = next;
      continue;
    }
    const std::size_t close = splitArguments(text, p, args);
    if (close == std::string::npos || close > next) {
      p = next;
      continue;
    }
    std::vector<std::pair<std::size_t, std::size_t>> kept;
    std::string dropped_newlines;
    std::string_view as = type;
    std::string_view append;
    if (rule != rules().end()) {
      if (args.size() != rule->args) {
        p = next;
        continue;
      }
      for (std::size_t k = 0; k < args.size(); ++k) {
        if (std::find(rule->drop.begin(), rule->drop.end(), k) == rule->drop.end()) {
          kept.push_back(args[k]);
        } else {
          dropped_newlines.append(static_cast<std::size_t>(std::count(text.begin() + static_cast<std::ptrdiff_t>(args[k].first),
                                                                      text.begin() + static_cast<std::ptrdiff_t>(args[k].second), '\n')),
                                  '\n');
        }
      }
      if (!rule->as.empty()) as = rule->as;
      append = rule->append;
      ++rewritten[static_cast<std::size_t>(rule - rules().begin())];
    } else {
      kept = args;
    }
    bool changed = rule != rules().end();
    // A draft of IFC 4.3 put Closed before Normals; IFC4 and IFC4X3_ADD2 put it after. The
    // normals are a list and Closed a logical: a logical second, or no value second and a list
    // third, is the draft's order.
    if ((triangulated || as == "IFCTRIANGULATEDFACESET") && kept.size() == 5) {
      const auto second = trimmedArgument(text, kept[1]), third = trimmedArgument(text, kept[2]);
      if (isLogical(second) || (second == "$" && !third.empty() && third.front() == '(')) {
        std::swap(kept[1], kept[2]);
        ++triangulated_reordered;
        changed = true;
      }
    }
    if (!changed) {  // already as IFC4 writes it
      p = next;
      continue;
    }
    o.append(text, copied, type_begin - copied);
    o += as;
    o.append(text, type_end, p - type_end + 1);  // up to its '(', blanks and comments as they were
    for (std::size_t k = 0; k < kept.size(); ++k) {
      if (k > 0) o += ',';
      o.append(text, kept[k].first, kept[k].second - kept[k].first);
    }
    if (!append.empty()) o += kept.empty() ? "" : ",", o += append;
    o += ')';
    o += dropped_newlines;  // every later instance stays on its line, which warnings name
    copied = close + 1;
    p = next;
  }
  o.append(text, copied, std::string::npos);
  // The warning's parts by name, as a sorted map of them would list them.
  std::map<std::string, std::size_t> counts;
  for (std::size_t k = 0; k < rules().size(); ++k)
    if (rewritten[k] > 0) counts[std::string(rules()[k].name) + " (" + std::string(rules()[k].what) + ")"] = rewritten[k];
  if (triangulated_reordered > 0)
    counts["IfcTriangulatedFaceSet (Closed put after Normals, as IFC4 has it)"] += triangulated_reordered;
  std::string line = "FILE_SCHEMA '" + schema + "' read as IFC4 (the IFC++ bimloc links knows IFC2X3 and IFC4), ";
  if (counts.empty()) {
    line += "no instance needed rewriting";
  } else {
    line += "rewritten where IFC 4.3 differs:";
    bool first = true;
    for (const auto& [what, n] : counts) line += (first ? " " : ", ") + std::to_string(n) + " " + what, first = false;
  }
  out.warnings.push_back(line + "; entities IFC4 has not are skipped");
  return out;
}

}  // namespace bimloc::bim::detail
