#include "sim/scenario/localizer_config.hpp"

#include "sim/scenario/localizer_fields.hpp"
#include "sim/scenario/yaml_mapping.hpp"

#include <cmath>
#include <filesystem>
#include <sstream>
#include <stdexcept>
#include <variant>

namespace bimloc::sim {
namespace {

using detail::Range;
using fields::Field;
using fields::planeFields;
using fields::pfFields;
using fields::sgraphFields;
using fields::amclFields;
using fields::ndtFields;
using fields::storeyFields;
Range positive(double hi) { return Range::positive(hi); }

// The field named `key` of `fields`, under another name (an alias keeps its field's range).
Field alias(const std::string& name, const std::vector<Field>& fields, const std::string& key) {
  for (const Field& f : fields)
    if (f.key == key) return {name, f.target, f.range};
  throw std::logic_error("no localizer field " + key);
}

std::vector<Field> topFields(LocalizerConfig& c) {
  const auto pf = pfFields(c.pf);
  return {{"relocalize_sigma_m", &c.relocalize_sigma_m, positive(1e4)},
          {"relocalize_sigma_yaw_deg", &c.relocalize_sigma_yaw_deg, positive(180)},
          alias("prior_sigma_m", pf, "prior_sigma_m"),
          alias("prior_sigma_yaw_deg", pf, "prior_sigma_yaw_deg"),
          // The flat keys of the first scenarios, kept.
          alias("particles", pf, "particles"),
          alias("sigma_d_m", pf, "sigma_d_m"),
          alias("sigma_azimuth_deg", pf, "sigma_azimuth_deg"),
          alias("converged_updates", pf, "converged_updates"),
          alias("voxel_size_m", planeFields(c.planes), "voxel_size_m")};
}

const std::vector<std::string> kOtherTopKeys{"method", "storey", "prior_rooms", "prior_pose", "planes", "pf", "sgraph", "amcl", "ndt", "storeys"};

struct Reader {
  const std::string& file;
  const std::map<std::string, int>& lines;

  [[noreturn]] void fail(const std::string& key, const std::string& message) const {
    const auto it = lines.find(key);
    detail::fail(file, it == lines.end() ? 0 : it->second, key + ": " + message);
  }

  void set(const Field& f, const nlohmann::json& value, const std::string& name) const {
    if (std::holds_alternative<bool*>(f.target)) {
      if (!value.is_boolean()) fail(name, "expected true or false, got " + value.dump());
      *std::get<bool*>(f.target) = value.get<bool>();
      return;
    }
    if (!value.is_number()) fail(name, "expected a number, got " + value.dump());
    const double v = value.get<double>();
    if (!std::isfinite(v) || !f.range.contains(v)) fail(name, value.dump() + " is outside " + f.range.str());
    if (auto* i = std::get_if<int*>(&f.target)) {
      if (v != std::floor(v)) fail(name, "expected a whole number, got " + value.dump());
      **i = static_cast<int>(v);
    } else {
      *std::get<double*>(f.target) = v;
    }
  }

  // Every key of `block` must be one of `fields` (or of `others`, read by the caller).
  void section(const nlohmann::json& block, const std::string& prefix, const std::vector<Field>& fields,
               const std::vector<std::string>& others = {}) const {
    if (!block.is_object()) fail(prefix, "expected a mapping (key: value lines)");
    std::vector<std::string> keys = others;
    for (const Field& f : fields) keys.push_back(f.key);
    for (const auto& [key, value] : block.items()) {
      const std::string name = prefix + "." + key;
      bool done = std::find(others.begin(), others.end(), key) != others.end();
      for (const Field& f : fields)
        if (f.key == key) set(f, value, name), done = true;
      if (!done) {
        const std::string guess = detail::nearestWord(key, keys);
        std::string list;
        for (const auto& k : keys) list += (list.empty() ? "" : ", ") + k;
        fail(name, "unknown key" + (guess.empty() ? " (keys of " + prefix + ": " + list + ")" : " (did you mean '" + guess + "'?)"));
      }
    }
  }
};

}  // namespace

LocalizerSettings readLocalizerSettings(const nlohmann::json& block, const std::string& file, const std::map<std::string, int>& lines) {
  LocalizerSettings out;
  LocalizerConfig& c = out.config;
  const Reader read{file, lines};
  if (block.is_null()) return out;
  read.section(block, "localizer", topFields(c), kOtherTopKeys);
  if (block.contains("method")) {
    const auto& v = block["method"];
    const auto m = v.is_string() ? methodFromString(v.get<std::string>()) : std::nullopt;
    if (!m) read.fail("localizer.method", "expected sgraph, pf, pf-no-rooms, amcl or ndt, got " + v.dump());
    c.method = *m;
  }
  if (block.contains("storey")) {
    // The localizer is not told the storey; the storey itself is the scenario's `storey:`.
    if (block["storey"] != "auto") read.fail("localizer.storey", "only 'auto' (the storey found from the scans); the simulator's storey is the scenario's `storey:`");
    out.storey_auto = true;
  }
  if (block.contains("prior_rooms")) {
    // The start was in one of these rooms (what a user knows: "we start in flat B").
    const auto& v = block["prior_rooms"];
    const auto list = v.is_string() ? nlohmann::json::array({v}) : v;
    if (!list.is_array() || list.empty()) read.fail("localizer.prior_rooms", "expected a room name or a list of them");
    for (const auto& r : list) {
      if (!r.is_string()) read.fail("localizer.prior_rooms", "expected room names, got " + r.dump());
      c.pf.prior_rooms.push_back(r.get<std::string>());
    }
  }
  if (block.contains("prior_pose")) {
    // [x, y, yaw_deg] of the start in the map frame; prior_sigma_m and prior_sigma_yaw_deg widen it.
    const auto& v = block["prior_pose"];
    if (!v.is_array() || v.size() != 3 || !v[0].is_number() || !v[1].is_number() || !v[2].is_number())
      read.fail("localizer.prior_pose", "expected [x, y, yaw_deg], got " + v.dump());
    c.pf.prior_pose = Eigen::Vector3d(v[0].get<double>(), v[1].get<double>(), v[2].get<double>() * M_PI / 180.0);
    if (!c.pf.prior_pose->allFinite()) read.fail("localizer.prior_pose", "not finite");
  }
  if (block.contains("planes")) read.section(block["planes"], "localizer.planes", planeFields(c.planes));
  if (block.contains("pf")) read.section(block["pf"], "localizer.pf", pfFields(c.pf));
  if (block.contains("sgraph")) read.section(block["sgraph"], "localizer.sgraph", sgraphFields(c.sgraph));
  if (block.contains("amcl")) read.section(block["amcl"], "localizer.amcl", amclFields(c.amcl));
  if (block.contains("ndt")) read.section(block["ndt"], "localizer.ndt", ndtFields(c.ndt));
  if (block.contains("storeys")) read.section(block["storeys"], "localizer.storeys", storeyFields(c.storeys));
  return out;
}

void recordLines(const std::string& prefix, const YAML::Node& node, std::map<std::string, int>& lines) {
  if (!node.IsMap()) return;
  for (const auto& kv : node) {
    if (!kv.first.IsScalar()) continue;
    const std::string name = prefix + "." + kv.first.Scalar();
    lines[name] = detail::lineOf(kv.first);
    recordLines(name, kv.second, lines);
  }
}

nlohmann::json loadLocalizerBlock(const std::string& path) {
  if (!std::filesystem::is_regular_file(path)) throw ScenarioError(path + ": no such config file");
  YAML::Node doc;
  try {
    doc = YAML::LoadFile(path);
  } catch (const YAML::ParserException& e) {
    detail::fail(path, e.mark.line >= 0 ? e.mark.line + 1 : 0, "YAML syntax error: " + e.msg);
  } catch (const YAML::Exception& e) {
    throw ScenarioError(path + ": cannot read the config file");
  }
  if (!doc.IsNull() && !doc.IsMap()) detail::fail(path, detail::lineOf(doc), "expected a mapping of localizer keys");
  std::map<std::string, int> lines;
  recordLines("localizer", doc, lines);
  nlohmann::json block = doc.IsNull() ? nlohmann::json::object() : detail::toJson(path, doc);
  readLocalizerSettings(block, path, lines);
  return block;
}

LocalizerSettings loadLocalizerConfig(const std::string& path) { return readLocalizerSettings(loadLocalizerBlock(path), path, {}); }

std::vector<std::pair<std::string, std::string>> localizerKeys(const LocalizerConfig& config) {
  LocalizerConfig c = config;  // the fields point into this copy
  std::vector<std::pair<std::string, std::string>> out;
  const auto add = [&out](const std::string& prefix, const std::vector<Field>& fields) {
    for (const Field& f : fields) {
      std::ostringstream v;
      std::visit([&v](auto* p) { v << std::boolalpha << *p; }, f.target);
      out.emplace_back(prefix + f.key, v.str());
    }
  };
  add("", topFields(c));
  add("planes.", planeFields(c.planes));
  add("pf.", pfFields(c.pf));
  add("sgraph.", sgraphFields(c.sgraph));
  add("amcl.", amclFields(c.amcl));
  add("ndt.", ndtFields(c.ndt));
  add("storeys.", storeyFields(c.storeys));
  out.emplace_back("method", toString(c.method));
  out.emplace_back("storey", "auto, or told by the caller");
  out.emplace_back("prior_rooms", "[]");
  out.emplace_back("prior_pose", "none; [x, y, yaw_deg]");
  return out;
}

}  // namespace bimloc::sim
