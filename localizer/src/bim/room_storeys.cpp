// Inferred rooms that are a lower storey's space seen again (see room_inference.hpp).
#include <bimloc/bim/room_inference.hpp>

#include <cstdio>

namespace bimloc::bim {
namespace {

std::string where(const Room& r) {
  char buffer[96];
  std::snprintf(buffer, sizeof buffer, " (%.1f m2 at (%.2f, %.2f))", r.area_m2, r.centre.x(), r.centre.y());
  return buffer;
}

}  // namespace

std::vector<std::string> dropRoomsOfLowerStoreys(std::vector<Storey>& storeys, const RoomInferenceConfig& config) {
  std::vector<std::string> warnings;
  for (std::size_t a = 0; a < storeys.size(); ++a) {
    auto& rooms = storeys[a].rooms;
    for (auto r = rooms.begin(); r != rooms.end();) {
      if (r->source != "inferred") {
        ++r;
        continue;
      }
      const double probe = r->floor_z + config.probe_height_m;
      double covered = 0.0;
      std::string under;
      for (std::size_t b = 0; b < a; ++b)
        for (const auto& q : storeys[b].rooms) {
          if (q.floor_z >= r->floor_z - config.level_tolerance_m || q.floor_z + q.height_m < probe) continue;
          const double iou = polygonIoU(r->footprint, q.footprint, 0.05);
          if (iou <= 0) continue;
          covered += iou * (r->area_m2 + q.area_m2) / (1.0 + iou);  // the intersection's area
          if (under.empty()) under = storeys[b].name;
        }
      if (covered > config.max_overlap_of_lower * r->area_m2) {
        warnings.push_back("storey '" + storeys[a].name + "': inferred room " + r->name +
                           where(*r) +
                           " dropped: it lies in rooms of storey '" + under +
                           "', whose walls stand through it (not a floor of its own)");
        r = rooms.erase(r);
      } else {
        ++r;
      }
    }
  }
  return warnings;
}

}  // namespace bimloc::bim
