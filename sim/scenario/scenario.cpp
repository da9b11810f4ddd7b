#include "sim/scenario/scenario.hpp"

#include "sim/scenario/localizer_config.hpp"

#include "sim/scenario/scenario_sections.hpp"
#include "sim/scenario/yaml_mapping.hpp"

#include <cctype>
#include <cstdio>
#include <filesystem>
#include <fstream>

namespace bimloc::sim {
namespace {

namespace fs = std::filesystem;
using detail::Mapping;
using detail::Range;

// YAML is Unicode text; yaml-cpp passes any byte on, and a name that is not UTF-8 would fail
// far away (writing metadata.json) without the file's name. Refused here, with the line.
void requireUtf8(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    for (std::size_t i = 0; i < line.size();) {
      const auto byte = static_cast<unsigned char>(line[i]);
      const std::size_t length = byte < 0x80 ? 1 : (byte >> 5) == 0x6 ? 2 : (byte >> 4) == 0xE ? 3 : (byte >> 3) == 0x1E ? 4 : 0;
      bool valid = length > 0 && i + length <= line.size() && (byte >= 0x20 || byte == '\t' || byte == '\r');
      for (std::size_t k = 1; valid && k < length; ++k) valid = (static_cast<unsigned char>(line[i + k]) >> 6) == 0x2;
      if (valid && length > 1) {  // no overlong forms, surrogates or code points past U+10FFFF
        const auto second = static_cast<unsigned char>(line[i + 1]);
        valid = !(byte < 0xC2 || (byte == 0xE0 && second < 0xA0) || (byte == 0xED && second >= 0xA0) ||
                  (byte == 0xF0 && second < 0x90) || (byte == 0xF4 && second >= 0x90) || byte > 0xF4);
      }
      if (!valid) {
        char hex[8];
        std::snprintf(hex, sizeof hex, "0x%02X", byte);
        detail::fail(path, n, std::string("not UTF-8 text: byte ") + hex + " in column " + std::to_string(i + 1));
      }
      i += length;
    }
  }
}

YAML::Node parseFile(const std::string& path) {
  if (!fs::is_regular_file(path)) throw ScenarioError(path + ": no such scenario file");
  requireUtf8(path);
  try {
    return YAML::LoadFile(path);
  } catch (const YAML::BadFile&) {
    throw ScenarioError(path + ": cannot read the scenario file");
  } catch (const YAML::ParserException& e) {
    detail::fail(path, e.mark.line >= 0 ? e.mark.line + 1 : 0,
                 "YAML syntax error: " + e.msg + (e.mark.column >= 0 ? " (column " + std::to_string(e.mark.column + 1) + ")" : ""));
  }
}

// The world path as given, relative to the scenario file's folder unless absolute.
std::string resolveWorld(const Mapping& top) {
  top.require("world");
  std::string given;
  top.read("world", given);
  const fs::path base = fs::path(top.file()).parent_path();
  const fs::path world = fs::path(given).is_absolute() ? fs::path(given) : (base / given).lexically_normal();
  if (!fs::exists(world)) top.fail("world", "world '" + given + "' not found (no file or folder " + world.string() + ")");
  return world.string();
}

std::string readStorey(const Mapping& top) {
  if (!top.has("storey")) return "0";
  const YAML::Node& v = top.value("storey");
  if (!v.IsScalar() || v.Scalar().empty())
    top.fail("storey", "storey must be a storey name, GlobalId or index, got " + detail::describe(v));
  return v.Scalar();
}

std::uint64_t readSeed(const Mapping& top) {
  if (!top.has("seed")) return 0;
  const YAML::Node& v = top.value("seed");
  const std::string text = v.IsScalar() && v.Tag() != "!" ? v.Scalar() : std::string();
  bool digits = !text.empty() && text.size() <= 20;
  for (const char c : text) digits = digits && std::isdigit(static_cast<unsigned char>(c));
  if (!digits || (text.size() == 20 && text > "18446744073709551615"))
    top.fail("seed", "seed must be an integer in [0, 18446744073709551615], got " + detail::describe(v));
  return std::stoull(text);
}

}  // namespace

Scenario loadScenario(const std::string& path) {
  const YAML::Node doc = parseFile(path);
  if (!doc.IsDefined() || doc.IsNull())
    throw ScenarioError(path + ":1: empty scenario (it needs at least 'world' and 'start')");
  const Mapping top(path, doc, "", 1,
                    {"name", "world", "storey", "start", "motion", "duration_s", "sensor", "odometry", "localizer",
                     "seed", "site", "expect"});
  Scenario s;
  s.file = path;
  s.name = fs::path(path).stem().string();
  top.read("name", s.name);
  s.world = resolveWorld(top);
  s.lines["world"] = top.line("world");
  s.storey = readStorey(top);
  s.lines["storey"] = top.line("storey");
  s.start = detail::readStart(top, s.lines);
  s.motion = detail::readMotion(top, s.lines);
  top.read("duration_s", s.duration_s, Range::positive(3600.0));
  s.sensor = detail::readSensor(top);
  s.odometry = detail::readOdometry(top);
  if (top.has("localizer")) {
    if (!top.value("localizer").IsMap() && !top.value("localizer").IsNull())
      top.fail("localizer", "localizer must be a mapping (key: value lines), got " + detail::describe(top.value("localizer")));
    s.localizer = detail::toJson(path, top.value("localizer"));
    if (s.localizer.is_null()) s.localizer = nlohmann::json::object();
    recordLines("localizer", top.value("localizer"), s.lines);
  }
  // `storey: auto`: the localizer is not told which storey (the simulator still needs it).
  if (s.storey == "auto" && !s.localizer.contains("storey")) s.localizer["storey"] = "auto";
  s.seed = readSeed(top);
  s.site = detail::readSite(top, s.lines);
  for (PersonPath& person : s.site.people.paths)  // a person walks the robot's storey unless told
    if (person.storey.empty() && s.storey != "auto") person.storey = s.storey;
  s.expect = detail::readExpect(top);
  for (const auto& key : top.given()) s.lines.emplace(key, top.line(key));
  readLocalizerSettings(s.localizer, path, s.lines);  // a key the localizer would reject fails here, at its line
  return s;
}

}  // namespace bimloc::sim
