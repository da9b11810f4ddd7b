#include "sim/scenario/yaml_mapping.hpp"
#include "sim/common/printable.hpp"

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>

namespace bimloc::sim::detail {
namespace {

std::size_t editDistance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] == b[j - 1] ? 0 : 1)});
      diagonal = up;
    }
  }
  return row[b.size()];
}

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const auto& w : words) out += (out.empty() ? "" : ", ") + w;
  return out;
}

std::string formatNumber(double v) {
  char text[32];
  std::snprintf(text, sizeof text, "%g", v);
  return text;
}

// A plain (unquoted) scalar read whole as a finite number.
bool parseNumber(const YAML::Node& node, double& out) {
  if (!node.IsScalar() || node.Tag() == "!") return false;
  const std::string& s = node.Scalar();
  if (s.empty()) return false;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(s.c_str(), &end);
  if (*end != '\0' || errno == ERANGE || !std::isfinite(v)) return false;
  out = v;
  return true;
}

// A plain scalar that reads as NaN or infinity: YAML's .nan and .inf, C's nan and inf, or a
// literal too large for a double.
bool isNonFiniteNumber(const YAML::Node& node) {
  if (!node.IsScalar() || node.Tag() == "!") return false;
  std::string s = node.Scalar();
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  if (!s.empty() && (s[0] == '+' || s[0] == '-')) s.erase(0, 1);
  if (s == ".nan" || s == ".inf" || s == "nan" || s == "inf" || s == "infinity") return true;
  char* end = nullptr;
  errno = 0;
  const double v = std::strtod(node.Scalar().c_str(), &end);
  return !node.Scalar().empty() && *end == '\0' && (errno == ERANGE || !std::isfinite(v)) && std::abs(v) > 1.0;
}

bool parseBool(const YAML::Node& node, bool& out) {
  if (!node.IsScalar() || node.Tag() == "!") return false;
  std::string s = node.Scalar();
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  // YAML 1.1's words, without its single letters y/n (too easy to mean something else).
  if (s == "true" || s == "yes" || s == "on") return out = true, true;
  if (s == "false" || s == "no" || s == "off") return out = false, true;
  return false;
}

}  // namespace

int lineOf(const YAML::Node& node) {
  if (!node.IsDefined()) return 0;
  const int line = node.Mark().line;
  return line >= 0 ? line + 1 : 0;
}

void fail(const std::string& file, int line, const std::string& message) {
  throw ScenarioError(file + (line > 0 ? ":" + std::to_string(line) : std::string()) + ": " + message);
}

std::string nearestWord(const std::string& word, const std::vector<std::string>& candidates) {
  std::string best;
  std::size_t best_distance = std::string::npos;
  for (const auto& c : candidates) {
    // "speed" for "max_speed_mps": a key without its prefix or unit is a likely slip.
    if (word.size() >= 3 && c.find(word) != std::string::npos) return c;
    const std::size_t d = editDistance(word, c);
    if (d < best_distance) best_distance = d, best = c;
  }
  return best_distance <= std::max<std::size_t>(2, best.size() / 3) ? best : std::string();
}

bool Range::contains(double v) const {
  return (lo_open ? v > lo : v >= lo) && (hi_open ? v < hi : v <= hi);
}

std::string Range::str() const {
  return (lo_open ? "(" : "[") + formatNumber(lo) + ", " + formatNumber(hi) + (hi_open ? ")" : "]");
}

std::string describe(const YAML::Node& node) {
  if (!node.IsDefined() || node.IsNull()) return "nothing";
  if (node.IsSequence()) return "a list";
  if (node.IsMap()) return "a mapping";
  return "'" + node.Scalar() + "'";
}

namespace {

// YAML aliases make a document a graph: an alias inside its own anchor is a cycle, and aliases
// of aliases expand exponentially (a "billion laughs"). A scenario's free-form section is a
// few dozen values a few levels deep; these bounds are far beyond that and far below harm.
constexpr int kMaxDepth = 32;
constexpr std::size_t kMaxValues = 100000;

nlohmann::json toJsonBounded(const std::string& file, const YAML::Node& node, int depth, std::size_t& values) {
  if (++values > kMaxValues)
    fail(file, lineOf(node), "the section expands to more than " + std::to_string(kMaxValues) +
                                 " values (aliases of aliases?): refused");
  if (depth > kMaxDepth)
    fail(file, lineOf(node), "values nested more than " + std::to_string(kMaxDepth) +
                                 " levels deep (an alias inside its own anchor?): refused");
  if (!node.IsDefined() || node.IsNull()) return nullptr;
  if (node.IsSequence()) {
    nlohmann::json out = nlohmann::json::array();
    for (const auto& item : node) out.push_back(toJsonBounded(file, item, depth + 1, values));
    return out;
  }
  if (node.IsMap()) {
    nlohmann::json out = nlohmann::json::object();
    for (const auto& kv : node) {
      if (!kv.first.IsScalar()) fail(file, lineOf(kv.first), "keys must be plain words, got " + describe(kv.first));
      // JSON holds UTF-8 only: a damaged byte would throw later, far from its line.
      if (!isValidUtf8(kv.first.Scalar()))
        fail(file, lineOf(kv.first), "the key '" + printable(kv.first.Scalar()) + "' is not valid UTF-8");
      out[kv.first.Scalar()] = toJsonBounded(file, kv.second, depth + 1, values);
    }
    return out;
  }
  bool b = false;
  if (parseBool(node, b)) return b;
  double v = 0.0;
  // No setting means anything by NaN or infinity (1e999 overflows to it): refused here, where
  // the line is known, rather than passed on as a string to each consumer of the section.
  if (isNonFiniteNumber(node)) fail(file, lineOf(node), "'" + node.Scalar() + "' is not a finite number");
  if (parseNumber(node, v)) {
    const std::string& s = node.Scalar();
    const bool integral = s.find_first_of(".eE") == std::string::npos && std::abs(v) < 9e15;
    return integral ? nlohmann::json(static_cast<long long>(v)) : nlohmann::json(v);
  }
  if (!isValidUtf8(node.Scalar())) fail(file, lineOf(node), "'" + printable(node.Scalar()) + "' is not valid UTF-8");
  return node.Scalar();
}

}  // namespace

nlohmann::json toJson(const std::string& file, const YAML::Node& node) {
  std::size_t values = 0;
  return toJsonBounded(file, node, 0, values);
}

Mapping::Mapping(const std::string& file, const YAML::Node& node, const std::string& path, int line,
                 std::vector<std::string> keys)
    : file_(file), path_(path), line_(lineOf(node) > 0 ? lineOf(node) : line) {
  if (!node.IsDefined() || node.IsNull()) return;  // "motion:" alone: every default
  if (!node.IsMap())
    detail::fail(file_, line_, (path_.empty() ? "the scenario" : path_) + " must be a mapping (key: value lines), got " +
                                   describe(node));
  std::size_t order = 0;
  for (const auto& kv : node) {
    const int key_line = lineOf(kv.first) > 0 ? lineOf(kv.first) : line_;
    if (!kv.first.IsScalar()) detail::fail(file_, key_line, "keys must be plain words, got " + describe(kv.first));
    const std::string& key = kv.first.Scalar();
    if (std::find(keys.begin(), keys.end(), key) == keys.end()) {
      const std::string where = path_.empty() ? "" : " in '" + path_ + "'";
      const std::string guess = nearestWord(key, keys);
      detail::fail(file_, key_line,
                   "unknown key '" + key + "'" + where +
                       (guess.empty() ? " (valid keys: " + joined(keys) + ")" : " (did you mean '" + guess + "'?)"));
    }
    const auto previous = entries_.find(key);
    if (previous != entries_.end())
      detail::fail(file_, key_line,
                   "key '" + name(key) + "' given twice (first at line " + std::to_string(previous->second.key_line) + ")");
    entries_[key] = Entry{kv.first, kv.second, key_line, order++};
  }
}

const YAML::Node& Mapping::value(const std::string& key) const { return entries_.at(key).value; }

int Mapping::line(const std::string& key) const {
  const auto it = entries_.find(key);
  if (it == entries_.end()) return line_;
  const int value_line = lineOf(it->second.value);
  return value_line > 0 ? value_line : it->second.key_line;
}

std::string Mapping::name(const std::string& key) const { return path_.empty() ? key : path_ + "." + key; }

std::vector<std::string> Mapping::given() const {
  std::vector<std::pair<std::size_t, std::string>> keys;
  for (const auto& [k, e] : entries_) keys.emplace_back(e.order, k);
  std::sort(keys.begin(), keys.end());
  std::vector<std::string> out;
  for (const auto& k : keys) out.push_back(k.second);
  return out;
}

void Mapping::fail(const std::string& key, const std::string& message) const {
  detail::fail(file_, line(key), message);
}

void Mapping::require(const std::string& key) const {
  if (!has(key)) detail::fail(file_, line_, "missing required key '" + name(key) + "'");
}

void Mapping::onlyWith(const std::string& key, const std::string& what) const {
  if (has(key)) fail(key, "'" + name(key) + "' is only used with " + what);
}

double scalarNumber(const Mapping& m, const YAML::Node& node, const std::string& what, int fallback_line) {
  double v = 0.0;
  if (!parseNumber(node, v)) {
    const int line = lineOf(node) > 0 ? lineOf(node) : fallback_line;
    detail::fail(m.file(), line, what + " must be a number, got " + describe(node));
  }
  return v;
}

void Mapping::read(const std::string& key, double& out, const Range& range) const {
  if (!has(key)) return;
  const double v = scalarNumber(*this, value(key), name(key), line(key));
  if (!range.contains(v)) fail(key, name(key) + " must be in " + range.str() + ", got " + value(key).Scalar());
  out = v;
}

void Mapping::read(const std::string& key, bool& out) const {
  if (!has(key)) return;
  if (!parseBool(value(key), out)) fail(key, name(key) + " must be true or false, got " + describe(value(key)));
}

void Mapping::read(const std::string& key, std::string& out) const {
  if (!has(key)) return;
  const YAML::Node& v = value(key);
  if (!v.IsScalar() || v.Scalar().empty()) fail(key, name(key) + " must be a text, got " + describe(v));
  out = v.Scalar();
}

void Mapping::readChoice(const std::string& key, std::string& out, const std::vector<std::string>& choices) const {
  if (!has(key)) return;
  std::string v;
  read(key, v);
  if (std::find(choices.begin(), choices.end(), v) == choices.end()) {
    const std::string guess = nearestWord(v, choices);
    fail(key, name(key) + " must be one of " + joined(choices) + ", got '" + v + "'" +
                  (guess.empty() ? "" : " (did you mean '" + guess + "'?)"));
  }
  out = v;
}

std::vector<double> Mapping::numbers(const YAML::Node& node, const std::string& what, int fallback_line,
                                     std::size_t min_size, std::size_t max_size, const Range& range) const {
  const int line = lineOf(node) > 0 ? lineOf(node) : fallback_line;
  const std::string size = min_size == max_size ? std::to_string(min_size)
                                                : std::to_string(min_size) + " or " + std::to_string(max_size);
  if (!node.IsSequence() || node.size() < min_size || node.size() > max_size)
    detail::fail(file_, line,
                 what + " must be a list of " + size + " numbers, got " +
                     (node.IsSequence() ? std::to_string(node.size()) + " item(s)" : describe(node)));
  std::vector<double> out;
  for (const auto& item : node) {
    const double v = scalarNumber(*this, item, what, line);
    if (!range.contains(v)) detail::fail(file_, line, what + " values must be in " + range.str() + ", got " + item.Scalar());
    out.push_back(v);
  }
  return out;
}

Mapping Mapping::mapping(const std::string& key, std::vector<std::string> keys) const {
  if (!has(key)) return Mapping(file_, YAML::Node(), name(key), line_, std::move(keys));
  return Mapping(file_, value(key), name(key), line(key), std::move(keys));
}

}  // namespace bimloc::sim::detail
