// inferRooms: a storey's rooms from its walls (for plans without IfcSpace).
//
//   levels        wall base heights; per level, the walls standing at probe_height_m
//   rasterize     wall boxes (or the exact shapes of walls that are not boxes) and barriers
//                 (curtain walls), cell_m
//   close gaps    closing by max_gap_m / 2: walls that don't quite meet at corners
//   outside       where a disk of diameter envelope_gap_m rolling in from the raster's border
//                 reaches (it does not pass entrances, windows, stair openings): not a room
//   seeds         4-connected components of the free space farther than door_width_m / 2
//                 from every wall: a doorway splits them, an open plan doesn't
//   watershed     seeds (and the exterior) grown back into all the free space, highest
//                 clearance first, so neighbours meet at the doorway; enclosed pockets no
//                 seed reaches are regions of their own
//   footprints    outline -> Douglas-Peucker -> edges snapped onto the wall faces
//   filter        too small (min_area_m2) or too thin (min_width_m) regions are dropped
#include <bimloc/bim/room_inference.hpp>

#include "extraction.hpp"
#include "room_footprint.hpp"
#include "room_raster.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace bimloc::bim {
namespace {

// The wall's footprint rectangle, never thinner than `min_thickness` so that thin walls
// still cut the raster whatever their angle.
Polygon2 wallBox(const Wall& wall, double min_thickness) {
  const Eigen::Vector2d s = wall.start.head<2>(), e = wall.end.head<2>();
  Eigen::Vector2d u = e - s;
  if (u.norm() < 1e-9) u = Eigen::Vector2d::UnitX();
  u.normalize();
  const Eigen::Vector2d left = 0.5 * std::max(wall.thickness_m, min_thickness) * Eigen::Vector2d(-u.y(), u.x());
  return {s - left, e - left, e + left, s + left};
}

// The section of a body by the plane z = height, as thin quads along the cut segments (the
// barriers are thin panels and mullions: their outline covers them).
void cutAt(const TriangleMesh& mesh, double height, double width, std::vector<Polygon2>& out) {
  for (const auto& t : mesh.triangles) {
    std::vector<Eigen::Vector2d> cut;
    for (int e = 0; e < 3; ++e) {
      const Eigen::Vector3d a = mesh.vertices[t[e]].cast<double>(), b = mesh.vertices[t[(e + 1) % 3]].cast<double>();
      if ((a.z() > height) == (b.z() > height)) continue;
      const double u = (height - a.z()) / (b.z() - a.z());
      cut.push_back((a + u * (b - a)).head<2>());
    }
    if (cut.size() != 2) continue;
    Eigen::Vector2d along = cut[1] - cut[0];
    if (along.norm() < 1e-9) continue;
    const Eigen::Vector2d side = 0.5 * width * Eigen::Vector2d(-along.y(), along.x()).normalized();
    along = 0.5 * width * along.normalized();
    out.push_back({cut[0] - along - side, cut[1] + along - side, cut[1] + along + side, cut[0] - along + side});
  }
}

std::string fmt(const char* format, double a, double b = 0, double c = 0, double d = 0) {
  char buffer[160];
  std::snprintf(buffer, sizeof buffer, format, a, b, c, d);
  return buffer;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v.empty() ? 0.0 : v.size() % 2 ? v[v.size() / 2] : 0.5 * (v[v.size() / 2 - 1] + v[v.size() / 2]);
}

void checkConfig(const RoomInferenceConfig& c) {
  if (!(c.cell_m > 0) || !(c.max_gap_m >= 0) || !(c.door_width_m >= 0) || !(c.envelope_gap_m >= 0) ||
      !(c.min_area_m2 >= 0) || !(c.min_width_m >= 0) || !(c.snap_distance_m >= 0) || c.max_cells < 100)
    throw std::invalid_argument("RoomInferenceConfig: lengths must be >= 0, cell_m > 0 and max_cells >= 100");
}

struct Region {
  std::size_t cells = 0;
  std::int32_t max_d2 = 0;
  Eigen::Vector2d sum = Eigen::Vector2d::Zero();
  std::size_t open_edges = 0;      // cell edges towards the exterior
  std::size_t boundary_edges = 0;  // cell edges towards anything else than the region
};

// A physical level of the storey: a floor height and the walls standing at its probe height.
struct Level {
  double floor_z = 0.0;
  std::vector<const Wall*> walls;  // standing at the probe height, of the storey or through it
  std::string others;              // the walls of other storeys among them, named
};

std::vector<Level> levelsOf(const Storey& storey, const RoomInferenceConfig& config) {
  std::vector<double> bases;
  for (const auto& w : storey.walls) bases.push_back(w.start.z());
  std::sort(bases.begin(), bases.end());
  std::vector<std::pair<double, std::size_t>> clusters;  // (lowest base, walls)
  for (std::size_t i = 0; i < bases.size();) {
    std::size_t j = i + 1;
    while (j < bases.size() && bases[j] - bases[j - 1] <= config.level_tolerance_m) ++j;
    clusters.emplace_back(bases[i], j - i);
    i = j;
  }
  // The height most walls start at is always a level (a round room has one wall); another
  // height needs enough of the storey's walls (not the few walls of a landing filed here).
  std::size_t most = 0;
  for (const auto& c : clusters) most = std::max(most, c.second);
  std::vector<Level> levels;
  for (const auto& [base, count] : clusters) {
    if (count != most && (count < config.min_level_walls || count < config.min_level_share * bases.size())) continue;
    Level level{base, {}, {}};
    const double probe = level.floor_z + config.probe_height_m;
    bool own = false;  // a wall starting at this level stands at its probe height (not a curb)
    for (const auto& w : storey.walls)
      if (w.start.z() <= probe && w.start.z() + w.height_m >= probe) {
        level.walls.push_back(&w);
        own |= std::abs(w.start.z() - base) <= config.level_tolerance_m;
      }
    if (own) levels.push_back(std::move(level));
  }
  return levels;
}

// The storey's walls that stand in none of its levels.
std::vector<const Wall*> unusedWalls(const Storey& storey, const std::vector<Level>& levels) {
  std::vector<const Wall*> unused;
  for (const auto& w : storey.walls) {
    bool used = false;
    for (const auto& level : levels) used |= std::find(level.walls.begin(), level.walls.end(), &w) != level.walls.end();
    if (!used) unused.push_back(&w);
  }
  return unused;
}

// The rooms of one level: regions of its free space, filtered, polygonized, snapped.
void inferLevel(const Storey& storey, const Level& level, const RoomInferenceConfig& config, const RoomBounds& bounds,
                InferredRooms& out) {
  const std::string where = "storey '" + storey.name + "'" + fmt(" (level at z = %.2f m): ", level.floor_z);
  std::vector<Polygon2> obstacles;
  std::vector<WallFace> faces;  // footprints snap to these (not to the fitted faces of approximated walls)
  std::vector<Wall> walls;
  for (const Wall* wall : level.walls) {
    const auto shape = bounds.shapes.find(wall->id);
    if (shape != bounds.shapes.end() && !shape->second.empty())
      obstacles.insert(obstacles.end(), shape->second.begin(), shape->second.end());
    else
      obstacles.push_back(wallBox(*wall, 1.5 * config.cell_m));
    if (!wall->approximated) faces.insert(faces.end(), wall->faces.begin(), wall->faces.end());
    walls.push_back(*wall);
  }
  const double probe = level.floor_z + config.probe_height_m;
  for (const auto& barrier : bounds.barriers) {
    // Another storey's barrier counts where it rises from below through this level's floor
    // (Jesse.1's façades, filed under level 0, stand through Level 1), not where it starts
    // above the floor: it is another floor's then (a "top of" level's is under level 0).
    if (!barrier.storey_id.empty() && barrier.storey_id != storey.id) {
      float base = std::numeric_limits<float>::infinity();
      for (const auto& v : barrier.mesh.vertices) base = std::min(base, v.z());
      if (base > level.floor_z + config.level_tolerance_m) continue;
    }
    cutAt(barrier.mesh, probe, 1.5 * config.cell_m, obstacles);
  }
  const detail::Segmentation seg = detail::segmentFreeSpace(obstacles, config);
  const double cell = seg.raster.cell_m;
  if (seg.coarsened)
    out.warnings.push_back(where + fmt("rooms inferred on a %.2f m raster instead of %.2f m (too large)", cell, config.cell_m));

  std::vector<Region> regions(static_cast<std::size_t>(seg.regions_end));
  for (std::size_t k = 0; k < seg.labels.size(); ++k) {
    if (seg.labels[k] <= detail::kExteriorLabel) continue;
    Region& r = regions[static_cast<std::size_t>(seg.labels[k])];
    ++r.cells;
    r.max_d2 = std::max(r.max_d2, seg.clearance_d2[k]);
    r.sum += seg.raster.centre(k);
    const int i = int(k % seg.raster.width), j = int(k / seg.raster.width);
    for (const auto& [di, dj] : {std::pair{1, 0}, {-1, 0}, {0, 1}, {0, -1}}) {
      const int ni = i + di, nj = j + dj;
      if (ni < 0 || nj < 0 || ni >= seg.raster.width || nj >= seg.raster.height) continue;
      const std::int32_t other = seg.labels[seg.raster.index(ni, nj)];
      if (other == seg.labels[k]) continue;
      ++r.boundary_edges;
      r.open_edges += other == detail::kExteriorLabel;
    }
  }
  for (std::int32_t label = detail::kExteriorLabel + 1; label < seg.regions_end; ++label) {
    const Region& region = regions[static_cast<std::size_t>(label)];
    if (region.cells == 0) continue;
    const double area = double(region.cells) * cell * cell;
    const double width = 2.0 * std::max(0.0, (std::sqrt(double(region.max_d2)) - 0.5) * cell);
    const Eigen::Vector2d at = region.sum / double(region.cells);
    const std::string name = where + fmt("free region at (%.2f, %.2f), %.2f m2", at.x(), at.y(), area);
    // A region out of the rolling disk's reach but outside all the same (between two wings
    // closer than the disk, an acute corner) is bounded by the outside more than by walls.
    if (double(region.open_edges) > config.max_open_fraction * double(region.boundary_edges)) {
      out.warnings.push_back(name + fmt(": not a room: open to the outside along %.0f%% of its boundary",
                                        100.0 * double(region.open_edges) / double(region.boundary_edges)));
      continue;
    }
    if (area < config.min_area_m2) {
      out.warnings.push_back(name + fmt(": not a room: smaller than %.2f m2", config.min_area_m2));
      continue;
    }
    if (width < config.min_width_m) {
      out.warnings.push_back(name + fmt(": not a room: too thin to walk in (%.2f m wide at most, < %.2f m)", width,
                                        config.min_width_m));
      continue;
    }
    Polygon2 footprint = detail::regionOutline(seg.raster, seg.labels, label);
    footprint = simplifyPolygon(detail::simplifyClosed(footprint, cell), 1e-6);
    footprint = simplifyPolygon(detail::snapToFaces(footprint, faces, config), 1e-4);
    if (footprint.size() < 3) {
      out.warnings.push_back(name + ": not a room: no outline");
      continue;
    }
    Room room;
    const std::string number = std::to_string(out.rooms.size() + 1);
    room.id = storey.id + "/R" + number;
    room.name = "R" + number;
    room.long_name = "inferred room " + number;
    room.source = "inferred";
    room.footprint = footprint;
    room.area_m2 = signedArea(footprint);
    room.centre = areaCentroid(footprint);
    room.floor_z = level.floor_z;
    detail::linkRoomByGeometry(room, walls, ExtractOptions{});
    // Height: to the top of the walls around it (median), else of the level's walls.
    std::vector<double> top;
    for (const auto& rw : room.walls)
      if (const Wall* w = storey.findWall(rw.wall_id)) top.push_back(w->start.z() + w->height_m);
    if (top.empty())
      for (const Wall* w : level.walls) top.push_back(w->start.z() + w->height_m);
    room.height_m = std::max(0.0, median(top) - room.floor_z);
    out.rooms.push_back(std::move(room));
  }
}

}  // namespace

InferredRooms inferRooms(const Storey& storey, const RoomInferenceConfig& config, const RoomBounds& bounds) {
  checkConfig(config);
  InferredRooms out;
  std::vector<Level> levels = levelsOf(storey, config);
  std::vector<const Wall*> strays;  // walls of other storeys that stand in none of their levels
  for (const Storey* other : bounds.other_storeys) {
    if (!other || other == &storey) continue;
    const auto unused = unusedWalls(*other, levelsOf(*other, config));
    strays.insert(strays.end(), unused.begin(), unused.end());
  }
  for (auto& level : levels) {
    std::vector<double> tops;
    for (const Wall* w : level.walls)
      if (std::abs(w->start.z() - level.floor_z) <= config.level_tolerance_m) tops.push_back(w->start.z() + w->height_m);
    const double ceiling = median(tops), probe = level.floor_z + config.probe_height_m;
    for (const Wall* w : strays)
      if (w->start.z() <= probe && w->start.z() + w->height_m >= ceiling - config.ceiling_tolerance_m) {
        level.walls.push_back(w);
        level.others += (level.others.empty() ? "" : ", ") + w->id + (w->name.empty() ? "" : " '" + w->name + "'");
      }
  }
  // Walls no level's rooms see: named, since they bound no inferred room.
  std::string unused;
  for (const Wall* w : unusedWalls(storey, levels))
    unused += (unused.empty() ? "" : ", ") + w->id + (w->name.empty() ? "" : " '" + w->name + "'");
  if (!unused.empty())
    out.warnings.push_back("storey '" + storey.name + "': walls not standing " + fmt("%.2f m", config.probe_height_m) +
                           " above a floor of the storey (curbs, walls under the roof, or fewer than " +
                           std::to_string(config.min_level_walls) + " walls at their height) bound none of its inferred rooms: " +
                           unused);
  for (const auto& level : levels) {
    if (!level.others.empty())
      out.warnings.push_back("storey '" + storey.name + "'" + fmt(" (level at z = %.2f m): ", level.floor_z) +
                             "walls filed under another storey bound its rooms (they stand through it): " + level.others);
    inferLevel(storey, level, config, bounds, out);
  }
  return out;
}

}  // namespace bimloc::bim
