#include <bimloc/bim/building.hpp>

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <cstdlib>

namespace bimloc::bim {

const char* toString(WallAxis axis) { return axis == WallAxis::X ? "x" : "y"; }

const Wall* Storey::findWall(const std::string& wall_id) const {
  for (const auto& w : walls)
    if (w.id == wall_id) return &w;
  return nullptr;
}

const Room* Storey::roomAt(const Eigen::Vector2d& p) const {
  for (const auto& r : rooms)
    if (pointInPolygon(r.footprint, p)) return &r;
  return nullptr;
}

const Room* Storey::findRoom(const std::string& name_or_id) const {
  for (const auto& r : rooms)
    if (r.id == name_or_id || r.name == name_or_id) return &r;
  for (const auto& r : rooms)
    if (r.long_name == name_or_id) return &r;
  return nullptr;
}

namespace {

std::size_t namedAlike(const std::vector<Storey>& storeys, const std::string& name) {
  return static_cast<std::size_t>(std::count_if(storeys.begin(), storeys.end(), [&](const Storey& s) { return s.name == name; }));
}

}  // namespace

const Storey* Building::findStorey(const std::string& name_or_index) const {
  if (name_or_index.empty()) return nullptr;
  for (const auto& s : storeys)
    if (s.id == name_or_index) return &s;
  const Storey* named = nullptr;
  for (const auto& s : storeys)
    if (s.name == name_or_index) {
      if (named) return nullptr;  // two storeys of that name: which one is not said
      named = &s;
    }
  if (named) return named;
  // A label storeyLabel gave: "name [#index]".
  for (std::size_t i = 0; i < storeys.size(); ++i)
    if (storeyLabel(i) == name_or_index) return &storeys[i];
  char* end = nullptr;
  const long index = std::strtol(name_or_index.c_str(), &end, 10);
  if (*end == '\0' && index >= 0 && index < static_cast<long>(storeys.size())) return &storeys[static_cast<std::size_t>(index)];
  return nullptr;
}

std::string Building::storeyLabel(std::size_t index) const {
  const Storey& s = storeys.at(index);
  if (s.name.empty()) return "#" + std::to_string(index);
  return namedAlike(storeys, s.name) > 1 ? s.name + " [#" + std::to_string(index) + "]" : s.name;
}

std::string Building::storeyLookupError(const std::string& name_or_index) const {
  const std::string plan = file.empty() ? std::string() : file + ": ";  // the message names the plan it was asked of
  std::string list;
  for (std::size_t i = 0; i < storeys.size(); ++i) list += (i ? ", " : "") + std::to_string(i) + " '" + storeyLabel(i) + "'";
  const std::size_t alike = name_or_index.empty() ? 0 : namedAlike(storeys, name_or_index);
  if (alike > 1) {
    std::string which;
    for (std::size_t i = 0; i < storeys.size(); ++i)
      if (storeys[i].name == name_or_index)
        which += std::string(which.empty() ? "" : ", ") + "#" + std::to_string(i) + " (GlobalId " + storeys[i].id + ")";
    return plan + std::to_string(alike) + " storeys are named '" + name_or_index + "' (" + which +
           "; a site of several buildings?): give its index, its GlobalId or its label (storeys: " + list + ")";
  }
  return plan + "no storey '" + name_or_index + "' (storeys: " + list + ")";
}

}  // namespace bimloc::bim
