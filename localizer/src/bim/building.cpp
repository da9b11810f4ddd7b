#include <bimloc/bim/building.hpp>

#include <bimloc/bim/geometry2d.hpp>

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

const Storey* Building::findStorey(const std::string& name_or_index) const {
  for (const auto& s : storeys)
    if (s.name == name_or_index || s.id == name_or_index) return &s;
  char* end = nullptr;
  const long index = std::strtol(name_or_index.c_str(), &end, 10);
  if (!name_or_index.empty() && *end == '\0' && index >= 0 && index < static_cast<long>(storeys.size()))
    return &storeys[static_cast<std::size_t>(index)];
  return nullptr;
}

}  // namespace bimloc::bim
