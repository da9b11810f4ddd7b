// A tiny ISO-10303-21 (STEP physical file) line writer: numbered entity instances
// `#id=ENTITY(args);` and the formatting of STEP values. Header-only because it is a
// handful of one-liners used by the IFC4 writer alone.
#pragma once

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <vector>

namespace bimloc::worldgen::step {

// A STEP REAL always carries a decimal point ("2." not "2"). Ten decimals is far below the
// file's 1e-5 precision, and printing fixed-point keeps the output byte-identical run to run.
inline std::string real(double value) {
  if (std::fabs(value) < 5e-11) return "0.";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.10f", value);
  std::string s(buf);
  while (s.back() == '0') s.pop_back();  // "%.10f" always prints a '.', so this stops there
  return s;
}

inline std::string integer(long value) { return std::to_string(value); }
inline std::string ref(int id) { return "#" + std::to_string(id); }
inline std::string enumeration(const std::string& name) { return "." + name + "."; }
inline const char* unset() { return "$"; }
inline const char* derived() { return "*"; }

// Plain ASCII only (the callers check); the apostrophe is doubled, the backslash escaped.
inline std::string str(const std::string& text) {
  std::string out = "'";
  for (char c : text) {
    if (c == '\'') out += "''";
    else if (c == '\\') out += "\\\\";
    else out += c;
  }
  return out + "'";
}

inline std::string list(const std::vector<std::string>& items) {
  std::string out = "(";
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? "," : "") + items[i];
  return out + ")";
}

inline std::string refs(const std::vector<int>& ids) {
  std::vector<std::string> items;
  for (int id : ids) items.push_back(ref(id));
  return list(items);
}

inline std::string reals(std::initializer_list<double> values) {
  std::vector<std::string> items;
  for (double v : values) items.push_back(real(v));
  return list(items);
}

// The DATA section under construction; ids are handed out in order, so equal input
// produces equal text.
class File {
 public:
  int add(const std::string& entity, const std::vector<std::string>& args) {
    const int id = next_id_++;
    data_ += ref(id) + "=" + entity + list(args) + ";\n";
    return id;
  }

  // The complete file; `name` and `timestamp` go into FILE_NAME.
  std::string text(const std::string& name, const std::string& timestamp,
                   const std::string& schema) const {
    std::string out = "ISO-10303-21;\nHEADER;\n";
    out += "FILE_DESCRIPTION(('ViewDefinition [DesignTransferView]'),'2;1');\n";
    out += "FILE_NAME(" + str(name) + "," + str(timestamp) +
           ",('bimloc'),('bimloc'),'bimloc worldgen','bimloc worldgen','');\n";
    out += "FILE_SCHEMA((" + str(schema) + "));\nENDSEC;\nDATA;\n";
    out += data_;
    out += "ENDSEC;\nEND-ISO-10303-21;\n";
    return out;
  }

 private:
  int next_id_ = 1;
  std::string data_;
};

}  // namespace bimloc::worldgen::step
