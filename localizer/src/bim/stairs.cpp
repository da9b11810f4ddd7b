// Stairs and ramps read from the plan (issue 31): each flight's run line, rise, going, steps and
// the storeys its ends stand on. The numbers come from the IfcStairFlight's attributes where
// they are sane, else from the body: its horizontal upward faces are the treads.
#include "stairs.hpp"

#include <algorithm>
#include <cmath>
#include <unordered_map>

namespace bimloc::bim::detail {
namespace {

// Sane ranges of a step (building codes ask 0.14-0.22 m rise, 0.21-0.37 m going; wider here,
// to keep steep attic stairs and generous ones, and drop what is another unit's number).
constexpr double kMinRiserM = 0.08, kMaxRiserM = 0.30;
constexpr double kMinGoingM = 0.10, kMaxGoingM = 0.60;
constexpr int kMaxRisers = 60;
// How close a floor (a storey's elevation, a landing's top) must be to a flight's end to be the
// floor that end stands on: storeys give the structural level, the stair the finished one.
constexpr double kFloorToleranceM = 0.12;
// Up-facing faces closer in height than this belong to one step.
constexpr double kMergeStepM = 0.1;
// How far a flight's end may be from a storey's elevation to stand on that storey: the storey's
// level is often the structural one, the stair's the finished floor (FZK-Haus: 0.13 m apart).
constexpr double kStoreyToleranceM = 0.2;

double stepMedian(std::vector<double> v) {
  if (v.empty()) return 0.0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

bool isFloorAt(double z, const std::vector<double>& floors) {
  return std::any_of(floors.begin(), floors.end(), [z](double f) { return std::abs(f - z) <= kFloorToleranceM; });
}

// The extent of xy points across direction d (perpendicular to it): [min, max] of p·(d rotated 90°).
std::pair<double, double> acrossExtent(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& d) {
  const Eigen::Vector2d across(-d.y(), d.x());
  double lo = std::numeric_limits<double>::infinity(), hi = -lo;
  for (const auto& p : points) lo = std::min(lo, p.dot(across)), hi = std::max(hi, p.dot(across));
  return {lo, hi};
}

bool sameFlightSizes(double a, double b, double relative) { return std::abs(a - b) <= relative * std::max(a, b); }

}  // namespace

std::vector<TreadLevel> treadLevels(const TriangleMesh& body, bool either_side) {
  struct Face {
    double z, area;
    Eigen::Vector2d centroid;
    std::array<Eigen::Vector2d, 3> corners;
  };
  std::vector<Face> faces;
  for (const auto& t : body.triangles) {
    const Eigen::Vector3d a = body.vertices[t[0]].cast<double>(), b = body.vertices[t[1]].cast<double>(),
                          c = body.vertices[t[2]].cast<double>();
    const Eigen::Vector3d n = (b - a).cross(c - a);
    const double norm = n.norm();
    const double up = either_side ? std::abs(n.z()) : n.z();
    if (norm < 1e-9 || up < 0.98 * norm) continue;  // up-facing and horizontal within ~11°
    faces.push_back({(a.z() + b.z() + c.z()) / 3.0, norm / 2.0, ((a + b + c) / 3.0).head<2>(),
                     {a.head<2>(), b.head<2>(), c.head<2>()}});
  }
  std::sort(faces.begin(), faces.end(), [](const Face& x, const Face& y) { return x.z < y.z; });
  std::vector<TreadLevel> levels;
  for (const auto& f : faces) {
    if (levels.empty() || f.z - levels.back().z_m > 0.01) levels.push_back({f.z, 0.0, Eigen::Vector2d::Zero(), {}});
    auto& level = levels.back();
    level.centroid = (level.centroid * level.area_m2 + f.centroid * f.area) / (level.area_m2 + f.area);
    level.area_m2 += f.area;
    level.corners.insert(level.corners.end(), f.corners.begin(), f.corners.end());
  }
  return levels;
}

std::optional<BodyFlight> flightFromBody(const TriangleMesh& body, const std::vector<double>& floors,
                                         std::string& problem) {
  auto flight = flightFromFaces(body, floors, false, problem);
  if (flight || body.empty()) return flight;
  // A surface model of open shells (ArchiCAD 11's stairs) faces its triangles either way:
  // take the horizontal ones whichever way they face (a tread's underside merges into it).
  std::string either_problem;
  flight = flightFromFaces(body, floors, true, either_problem);
  if (flight) problem.clear();
  return flight;
}

std::optional<BodyFlight> flightFromFaces(const TriangleMesh& body, const std::vector<double>& floors, bool either_side,
                                          std::string& problem) {
  problem.clear();
  if (body.empty()) {
    problem = "no body";
    return std::nullopt;
  }
  double z_min = std::numeric_limits<double>::infinity();
  for (const auto& v : body.vertices) z_min = std::min(z_min, double(v.z()));
  // Treads: the upward faces above the bottom. Faces less than a riser apart are one step (the
  // tread and its nosing, Revit; a tread board on its carriage, ArchiCAD): its top face counts.
  // Then the small ones go (railing tops, a handrail's), against the larger treads' area.
  std::vector<TreadLevel> levels;
  for (auto& level : treadLevels(body, either_side)) {
    if (level.z_m <= z_min + 0.03) continue;
    if (!levels.empty() && level.z_m - levels.back().z_m < kMergeStepM) {
      // The upper face, unless it is a speck over a tread (a post's top): then the tread.
      if (level.area_m2 >= 0.5 * levels.back().area_m2) {
        level.area_m2 = std::max(level.area_m2, levels.back().area_m2);
        levels.back() = std::move(level);
      }
    } else {
      levels.push_back(std::move(level));
    }
  }
  std::vector<double> areas;
  for (const auto& l : levels) areas.push_back(l.area_m2);
  std::sort(areas.begin(), areas.end());
  const double typical_area = areas.empty() ? 0.0 : areas[areas.size() * 3 / 4];
  levels.erase(std::remove_if(levels.begin(), levels.end(), [&](const TreadLevel& l) { return l.area_m2 < 0.5 * typical_area; }),
               levels.end());
  if (levels.size() < 2) {
    problem = "the body has " + std::to_string(levels.size()) + " horizontal step face(s): no flight of steps";
    return std::nullopt;
  }
  std::vector<double> rises;
  for (std::size_t k = 1; k < levels.size(); ++k) rises.push_back(levels[k].z_m - levels[k - 1].z_m);
  const double h = stepMedian(rises);
  if (!(h >= kMinRiserM && h <= kMaxRiserM)) {
    problem = "the step faces are " + std::to_string(h) + " m apart: not a stair's rise";
    return std::nullopt;
  }
  // The bottom floor: the body's base when the first tread is one rise above it, else a rise
  // below the first tread (a body reaching below the floor, a sloped soffit).
  const double bottom_z = sameFlightSizes(levels.front().z_m - z_min, h, 0.35) ? z_min : levels.front().z_m - h;
  // The last level is the top floor (or landing) when a floor is there, or when it is much larger
  // than a tread; else it is the last tread, and the floor is a rise above it.
  const bool last_is_floor = isFloorAt(levels.back().z_m, floors) ||
                             (!isFloorAt(levels.back().z_m + h, floors) && levels.back().area_m2 > 2.0 * typical_area);
  const double top_z = last_is_floor ? levels.back().z_m : levels.back().z_m + h;
  std::vector<TreadLevel> treads(levels.begin(), levels.end() - (last_is_floor ? 1 : 0));
  if (treads.size() < 2) {
    problem = "the body has one tread: the direction of its run is unknown";
    return std::nullopt;
  }
  BodyFlight flight;
  flight.risers = static_cast<int>(std::lround((top_z - bottom_z) / h));
  flight.riser_height_m = (top_z - bottom_z) / flight.risers;
  // Going: the walking line's length from tread to tread (a straight flight's tread depth; a
  // winding one's on the line through the treads' centres).
  double path = 0.0;
  for (std::size_t k = 1; k < treads.size(); ++k) path += (treads[k].centroid - treads[k - 1].centroid).norm();
  flight.going_m = path / static_cast<double>(treads.size() - 1);
  if (!(flight.going_m >= kMinGoingM && flight.going_m <= kMaxGoingM)) {
    problem = "the treads are " + std::to_string(flight.going_m) + " m apart: not a stair's going";
    return std::nullopt;
  }
  // The run line: half a going before the first tread's centre to half a going after the
  // last one's, shifted across to the middle of the treads' width.
  const Eigen::Vector2d d_first = (treads[1].centroid - treads[0].centroid).normalized();
  const Eigen::Vector2d d_last = (treads.back().centroid - treads[treads.size() - 2].centroid).normalized();
  std::vector<double> widths;
  for (std::size_t k = 0; k < treads.size(); ++k) {
    const Eigen::Vector2d d =
        (treads[std::min(k + 1, treads.size() - 1)].centroid - treads[k == 0 ? 0 : k - 1].centroid).normalized();
    const auto [lo, hi] = acrossExtent(treads[k].corners, d);
    widths.push_back(hi - lo);
  }
  flight.width_m = stepMedian(widths);
  const auto middle = [](const TreadLevel& t, const Eigen::Vector2d& d) -> Eigen::Vector2d {  // a value: an Eigen expression would refer to `across`, gone on return
    const auto [lo, hi] = acrossExtent(t.corners, d);
    const Eigen::Vector2d across(-d.y(), d.x());
    return t.centroid + across * ((lo + hi) / 2.0 - t.centroid.dot(across));
  };
  const Eigen::Vector2d b = middle(treads.front(), d_first) - d_first * flight.going_m / 2.0;
  const Eigen::Vector2d t = middle(treads.back(), d_last) + d_last * flight.going_m / 2.0;
  flight.bottom = {b.x(), b.y(), bottom_z};
  flight.top = {t.x(), t.y(), top_z};
  return flight;
}

std::optional<BodyFlight> rampFromBody(const TriangleMesh& body, std::string& problem) {
  problem.clear();
  // The walking surface: faces up, sloped between 0.5° and 25° (ramps rise 1:20 to 1:8; steeper
  // is no ramp a base drives up). The run goes up their area-weighted slope.
  const double cos_flat = std::cos(0.5 * M_PI / 180.0), cos_steep = std::cos(25.0 * M_PI / 180.0);
  Eigen::Vector2d uphill = Eigen::Vector2d::Zero();
  std::vector<Eigen::Vector3d> surface;
  for (const auto& t : body.triangles) {
    const Eigen::Vector3d a = body.vertices[t[0]].cast<double>(), b = body.vertices[t[1]].cast<double>(),
                          c = body.vertices[t[2]].cast<double>();
    const Eigen::Vector3d n = (b - a).cross(c - a);  // length: twice the area
    const double norm = n.norm();
    if (norm < 1e-9 || n.z() >= cos_flat * norm || n.z() < cos_steep * norm) continue;
    uphill -= n.head<2>();  // z rises against the normal's horizontal part; area-weighted
    surface.insert(surface.end(), {a, b, c});
  }
  if (surface.empty() || uphill.norm() < 1e-9) {
    problem = "the body has no sloped walking surface (0.5° to 25°): no ramp";
    return std::nullopt;
  }
  const Eigen::Vector2d d = uphill.normalized(), across(-d.y(), d.x());
  double s0 = std::numeric_limits<double>::infinity(), s1 = -s0, z0 = s0, z1 = -s0, w0 = s0, w1 = -s0;
  for (const auto& p : surface) {
    const double s = p.head<2>().dot(d), w = p.head<2>().dot(across);
    s0 = std::min(s0, s), s1 = std::max(s1, s), w0 = std::min(w0, w), w1 = std::max(w1, w);
    z0 = std::min(z0, p.z()), z1 = std::max(z1, p.z());
  }
  BodyFlight ramp;
  ramp.width_m = w1 - w0;
  const Eigen::Vector2d b = d * s0 + across * (w0 + w1) / 2, t = d * s1 + across * (w0 + w1) / 2;
  ramp.bottom = {b.x(), b.y(), z0};
  ramp.top = {t.x(), t.y(), z1};
  return ramp;
}

int storeyAt(double z, const std::vector<Storey>& storeys) {
  int best = -1;
  double best_gap = kStoreyToleranceM;
  for (std::size_t s = 0; s < storeys.size(); ++s) {
    const double gap = std::abs(storeys[s].elevation_m - z);
    if (gap <= best_gap) best = static_cast<int>(s), best_gap = gap;
  }
  return best;
}

std::optional<StairFlight> stairFlightOf(const RawProduct& flight, const TriangleMesh& body,
                                         const std::vector<double>& floors, std::string& problem) {
  problem.clear();
  StairFlight out;
  out.id = flight.global_id;
  out.name = flight.name;
  out.ifc_type = flight.ifc_class;
  std::string body_problem;
  const bool ramp = flight.ifc_class == "IfcRamp" || flight.ifc_class == "IfcRampFlight";
  const auto shape = ramp ? rampFromBody(body, body_problem) : flightFromBody(body, floors, body_problem);
  if (!shape) {
    problem = "no usable body (" + body_problem + ")";
    return std::nullopt;
  }
  out.bottom = shape->bottom;
  out.top = shape->top;
  out.width_m = shape->width_m;
  out.risers = shape->risers;
  out.riser_height_m = shape->riser_height_m;
  out.going_m = shape->going_m;
  out.source = "body";
  if (!flight.flight) return out;
  // The attributes, where sane and in agreement with the body's rise: the risers' count first
  // (no unit to get wrong), then each length.
  const FlightAttributes& a = *flight.flight;
  const double rise = out.rise_m();
  std::vector<std::string> used, ignored;
  if (a.risers && *a.risers >= 1 && *a.risers <= kMaxRisers &&
      std::abs(rise / *a.risers - shape->riser_height_m) < 0.25 * shape->riser_height_m) {
    out.risers = *a.risers;
    out.riser_height_m = rise / out.risers;
    used.push_back("NumberOfRisers " + std::to_string(*a.risers));
  } else if (a.risers) {
    ignored.push_back("NumberOfRisers " + std::to_string(*a.risers));
  }
  if (a.riser_height_m && *a.riser_height_m >= kMinRiserM && *a.riser_height_m <= kMaxRiserM &&
      std::abs(*a.riser_height_m * out.risers - rise) < 0.05) {
    out.riser_height_m = *a.riser_height_m;
    used.push_back("RiserHeight");
  } else if (a.riser_height_m) {
    ignored.push_back("RiserHeight " + std::to_string(*a.riser_height_m) + " m");
  }
  if (a.tread_length_m && *a.tread_length_m >= kMinGoingM && *a.tread_length_m <= kMaxGoingM &&
      std::abs(*a.tread_length_m - out.going_m) < 0.05) {
    out.going_m = *a.tread_length_m;
    used.push_back("TreadLength");
  } else if (a.tread_length_m) {
    ignored.push_back("TreadLength " + std::to_string(*a.tread_length_m) + " m");
  }
  out.source = used.empty() ? "body" : ignored.empty() && used.size() == 3 ? "attributes" : "attributes+body";
  if (!ignored.empty()) {
    problem = "attributes ignored, the body's numbers used instead (rise " + std::to_string(rise) + " m, " +
              std::to_string(shape->risers) + " risers, going " + std::to_string(shape->going_m) + " m):";
    for (const auto& i : ignored) problem += " " + i;
  }
  return out;
}

std::vector<StairFlight> stairFlightsOf(const RawModel& raw, const std::vector<Storey>& storeys,
                                        const std::function<const TriangleMesh&(const RawProduct&)>& body_of,
                                        std::vector<std::string>& warnings) {
  std::vector<StairFlight> flights;
  std::unordered_map<int, std::vector<const RawProduct*>> parts;  // stair entity id -> its elements
  std::unordered_map<int, const RawProduct*> element_by_id;
  for (const auto& p : raw.elements) {
    element_by_id[p.entity_id] = &p;
    if (p.whole_entity_id != 0) parts[p.whole_entity_id].push_back(&p);
  }
  std::size_t unusable = 0, considered = 0;
  for (const auto& stair : raw.stairs) {
    const bool ramp = stair.ifc_class == "IfcRamp";
    const std::string flight_class = ramp ? "IfcRampFlight" : "IfcStairFlight";
    std::vector<const RawProduct*> own_flights;
    std::vector<double> floors;
    for (const auto& s : storeys) floors.push_back(s.elevation_m);
    for (const auto* part : parts[stair.entity_id]) {
      if (part->ifc_class == flight_class) own_flights.push_back(part);
      if (part->ifc_class == "IfcSlab" && part->predefined_type == "LANDING") {
        double top = -std::numeric_limits<double>::infinity();
        for (const auto& v : body_of(*part).vertices) top = std::max(top, double(v.z()));
        if (std::isfinite(top)) floors.push_back(top);
      }
    }
    if (own_flights.empty()) {  // not decomposed: the stair's own body is its one flight
      const auto it = element_by_id.find(stair.entity_id);
      own_flights.push_back(it == element_by_id.end() ? &stair : it->second);
    }
    for (const auto* f : own_flights) {
      ++considered;
      std::string problem;
      auto flight = stairFlightOf(*f, body_of(*f), floors, problem);
      if (!flight) {
        ++unusable;
        warnings.push_back(describeProduct(*f) + ": stair flight skipped: " + problem);
        continue;
      }
      if (!problem.empty()) warnings.push_back(describeProduct(*f) + ": " + problem);
      flight->stair_id = stair.global_id;
      flight->bottom_storey = storeyAt(flight->bottom.z(), storeys);
      flight->top_storey = storeyAt(flight->top.z(), storeys);
      flights.push_back(std::move(*flight));
    }
  }
  if (unusable > 0)
    warnings.push_back(std::to_string(unusable) + " of " + std::to_string(considered) +
                       " stair and ramp flights skipped (see above): not in Building::stairs");
  return flights;
}

}  // namespace bimloc::bim::detail
