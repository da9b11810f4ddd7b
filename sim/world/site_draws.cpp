#include "sim/world/site_draws.hpp"
#include "sim/common/angles.hpp"

#include "sim/common/seeded_random.hpp"
#include "sim/world/site_mesh.hpp"

#include <cmath>
#include <limits>
#include <stdexcept>

namespace bimloc::sim {
namespace {

// A hosted element's centre lies in its wall's body, give or take the frame's reveal.
constexpr double kHostTolerance_m = 0.05;

}  // namespace

std::vector<const bim::Wall*> wallsNamed(const bim::Building& building, const std::string& id) {
  std::vector<const bim::Wall*> by_id, by_name;
  for (const auto& storey : building.storeys)
    for (const auto& w : storey.walls) {
      if (w.id == id) by_id.push_back(&w);
      if (w.name == id) by_name.push_back(&w);
    }
  return by_id.empty() ? by_name : by_id;
}

std::vector<std::string> wallWords(const bim::Building& building) {
  std::vector<std::string> words;
  for (const auto& storey : building.storeys)
    for (const auto& w : storey.walls) {
      words.push_back(w.id);
      if (!w.name.empty()) words.push_back(w.name);
    }
  return words;
}

std::vector<std::string> doorWords(const std::vector<PlanStorey>& plan) {
  std::vector<std::string> words;
  for (const auto& storey : plan)
    for (const auto& p : storey.parts)
      if (isDoorPart(p)) {
        words.push_back(p.id);
        if (!p.name.empty()) words.push_back(p.name);
      }
  return words;
}

Eigen::Affine3d wallMotion(const bim::Wall& wall, const WallTruth& truth) {
  const Eigen::Vector3d c(0.5 * (wall.start.x() + wall.end.x()), 0.5 * (wall.start.y() + wall.end.y()), 0.0);
  Eigen::Vector3d n0 = wall.faces[0].plane.n;
  n0.z() = 0.0;
  n0.normalize();
  return Eigen::Translation3d(c + truth.offset_m * n0) * Eigen::AngleAxisd(truth.angle_deg * kDegToRad, Eigen::Vector3d::UnitZ()) *
         Eigen::Translation3d(-c);
}

Eigen::Vector2d partCentre(const PlanStorey& plan, const bim::MeshPart& part) {
  Eigen::Vector2d lo = Eigen::Vector2d::Constant(std::numeric_limits<double>::infinity()), hi = -lo;
  for (std::uint32_t v = part.first_vertex; v < part.first_vertex + part.vertex_count; ++v) {
    lo = lo.cwiseMin(plan.mesh.vertices[v].head<2>().cast<double>());
    hi = hi.cwiseMax(plan.mesh.vertices[v].head<2>().cast<double>());
  }
  return 0.5 * (lo + hi);
}

int hostWall(const bim::Storey& storey, const PlanStorey& plan, const bim::MeshPart& part) {
  if (part.vertex_count == 0) return -1;
  const Eigen::Vector2d centre = partCentre(plan, part);
  int best = -1;
  double best_across = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < storey.walls.size(); ++i) {
    const bim::Wall& w = storey.walls[i];
    const Eigen::Vector2d a = w.start.head<2>(), b = w.end.head<2>();
    const double length = (b - a).norm();
    if (length <= 0.0) continue;
    const Eigen::Vector2d u = (b - a) / length;
    const double along = (centre - a).dot(u);
    const double across = std::abs((centre - a).dot(Eigen::Vector2d(-u.y(), u.x())));
    if (along < -kHostTolerance_m || along > length + kHostTolerance_m) continue;
    if (across > 0.5 * w.thickness_m + kHostTolerance_m || across >= best_across) continue;
    best = static_cast<int>(i), best_across = across;
  }
  return best;
}

SiteTruth drawSite(const bim::Building& building, const std::vector<PlanStorey>& plan, const SiteConfig& config,
                   std::uint64_t seed) {
  SiteTruth truth;
  truth.preset = config.preset;
  truth.seed = seed;
  const SiteWalls& walls = config.walls;
  SeededRandom wall_random(seed, RandomStream::SiteWalls);
  for (std::size_t s = 0; s < building.storeys.size(); ++s)
    for (const auto& w : building.storeys[s].walls) {
      // A curtain wall is built as drawn: its body is its parts' (plates, members), which the
      // world does not move with it; no draw taken, so the other walls' draws are as before.
      if (w.ifc_type == "IfcCurtainWall") {
        truth.walls.push_back({w.id, w.name, s, 0.0, 0.0, false});
        continue;
      }
      const double shifted = wall_random.uniform(), offset = wall_random.uniform(-1.0, 1.0),
                   angle = wall_random.uniform(-1.0, 1.0), missing = wall_random.uniform();
      WallTruth t{w.id, w.name, s, 0.0, 0.0, false};
      if (shifted < walls.fraction) t.offset_m = offset * walls.max_offset_m, t.angle_deg = angle * walls.max_angle_deg;
      t.missing = missing < walls.missing_fraction;
      if (t.missing) t.offset_m = 0.0, t.angle_deg = 0.0;
      truth.walls.push_back(t);
    }
  for (const auto& edit : walls.edits) {
    const auto named = wallsNamed(building, edit.id);
    if (named.empty()) throw std::invalid_argument("site.walls.edit: no wall '" + edit.id + "' in the plan");
    for (const bim::Wall* w : named)
      if (w->ifc_type == "IfcCurtainWall")
        throw std::invalid_argument("site.walls.edit: '" + edit.id + "' is a curtain wall (" + w->id +
                                    "): its panels and mullions cannot be moved or left out as one wall");
    for (const bim::Wall* w : named)
      for (auto& t : truth.walls)
        if (t.id == w->id) t.offset_m = edit.offset_m.value_or(0.0), t.angle_deg = edit.angle_deg.value_or(0.0), t.missing = edit.missing;
  }

  const SiteDoors& doors = config.doors;
  SeededRandom door_random(seed, RandomStream::SiteDoors);
  for (std::size_t s = 0; s < plan.size(); ++s)
    for (const auto& p : plan[s].parts) {
      if (!isDoorPart(p)) continue;
      const double u = door_random.uniform();
      DoorTruth d{p.id, p.name, s, DoorState::Open, "", partCentre(plan[s], p)};
      d.state = u < doors.shut_fraction                          ? DoorState::Shut
                : u < doors.shut_fraction + doors.ajar_fraction ? DoorState::Ajar
                                                                 : DoorState::Open;
      const int host = hostWall(building.storeys[s], plan[s], p);
      if (host >= 0) d.wall_id = building.storeys[s].walls[static_cast<std::size_t>(host)].id;
      truth.doors.push_back(d);
    }
  for (const auto& edit : doors.edits) {
    bool found = false;
    for (auto& d : truth.doors)
      if (d.id == edit.id) d.state = edit.state, found = true;
    if (!found)
      for (auto& d : truth.doors)
        if (d.name == edit.id) d.state = edit.state, found = true;
    if (!found) throw std::invalid_argument("site.doors.edit: no door '" + edit.id + "' in the plan");
  }
  return truth;
}

}  // namespace bimloc::sim
