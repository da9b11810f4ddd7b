// Strict reading of a scenario's YAML: every mapping declares its keys, every value has a type
// and a range, and every problem is a ScenarioError naming the file and the (1-based) line.
#pragma once

#include "sim/scenario/scenario.hpp"

#include <yaml-cpp/yaml.h>

#include <nlohmann/json.hpp>

#include <map>
#include <string>
#include <utility>
#include <vector>

namespace bimloc::sim::detail {

// 1-based line of a node, or 0 when yaml-cpp has none (a key given without a value).
int lineOf(const YAML::Node& node);

// "FILE:LINE: message" (or "FILE: message" for line 0).
[[noreturn]] void fail(const std::string& file, int line, const std::string& message);

// The candidate closest to a mistyped word, or "" when none is close enough to be a typo.
std::string nearestWord(const std::string& word, const std::vector<std::string>& candidates);

// An allowed interval of a number; open ends exclude the bound.
struct Range {
  double lo, hi;
  bool lo_open = false, hi_open = false;
  static Range closed(double lo, double hi) { return {lo, hi, false, false}; }
  static Range positive(double hi) { return {0.0, hi, true, false}; }  // (0, hi]
  bool contains(double v) const;
  std::string str() const;
};

// "'got 5'", "got a list", ...: what a node is, for type errors.
std::string describe(const YAML::Node& node);

// A YAML value converted to JSON: plain scalars become numbers or booleans when they read as
// one, quoted scalars stay strings. A mapping with a non-scalar key fails at its line.
nlohmann::json toJson(const std::string& file, const YAML::Node& node);

// One mapping of the scenario. Opening it checks its keys: an unknown or repeated key fails at
// once, with the nearest valid key as a suggestion.
class Mapping {
 public:
  // `path` is the mapping's dotted name ("" for the document, "motion.gait", ...); `line` is
  // used when the node itself has no mark.
  Mapping(const std::string& file, const YAML::Node& node, const std::string& path, int line,
          std::vector<std::string> keys);

  const std::string& file() const { return file_; }
  bool has(const std::string& key) const { return entries_.count(key) > 0; }
  const YAML::Node& value(const std::string& key) const;
  int line(const std::string& key) const;  // the value's line, or the key's when the value has none
  int line() const { return line_; }       // the mapping's own line
  std::string name(const std::string& key) const;  // "motion.max_speed_mps"
  std::vector<std::string> given() const;          // the keys present, in file order

  [[noreturn]] void fail(const std::string& key, const std::string& message) const;
  void require(const std::string& key) const;
  // Keys that do not go together with the mapping's `kind` (e.g. waypoints for a tour).
  void onlyWith(const std::string& key, const std::string& what) const;

  // Each reader leaves `out` untouched when the key is absent.
  void read(const std::string& key, double& out, const Range& range) const;
  void read(const std::string& key, bool& out) const;
  void read(const std::string& key, std::string& out) const;
  // A plain scalar of one of `choices` (the message suggests the nearest).
  void readChoice(const std::string& key, std::string& out, const std::vector<std::string>& choices) const;
  // A list of numbers of length min_size..max_size (a flow list [x, y] or a block list).
  std::vector<double> numbers(const YAML::Node& node, const std::string& what, int fallback_line,
                              std::size_t min_size, std::size_t max_size, const Range& range) const;
  Mapping mapping(const std::string& key, std::vector<std::string> keys) const;  // absent: empty

 private:
  struct Entry {
    YAML::Node key, value;
    int key_line = 0;
    std::size_t order = 0;
  };
  std::string file_, path_;
  int line_ = 0;
  std::map<std::string, Entry> entries_;
};

// The value of a plain scalar, with the type named in the error.
double scalarNumber(const Mapping& m, const YAML::Node& node, const std::string& what, int fallback_line);

}  // namespace bimloc::sim::detail
