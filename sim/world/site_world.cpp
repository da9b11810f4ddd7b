// World::withSite: the plan's world as a site. The draws (site_draws), then per storey the
// plan's elements kept, dropped, moved with their wall or glazed (site_mesh), door leaves and
// partitions added, and the Embree scenes and Bullet worlds built from the result.
#include "sim/common/angles.hpp"
#include "sim/world/site_clutter.hpp"
#include "sim/world/site_draws.hpp"
#include "sim/world/site_mesh.hpp"
#include "sim/world/site_partitions.hpp"
#include "sim/world/site_people.hpp"
#include "sim/world/world_impl.hpp"

#include "sim/common/seeded_random.hpp"

#include <cmath>
#include <limits>
#include <map>
#include <stdexcept>

namespace bimloc::sim {
namespace {


struct DoorBox {  // a door's extent in its host wall's frame (plan)
  double along_min, along_max, across_min, across_max, z_min, z_max;
};

DoorBox doorBox(const PlanStorey& plan, const bim::MeshPart& door, const bim::Wall& wall) {
  const Eigen::Vector2d a = wall.start.head<2>(), u = (wall.end.head<2>() - a).normalized(), n(-u.y(), u.x());
  const double inf = std::numeric_limits<double>::infinity();
  DoorBox box{inf, -inf, inf, -inf, inf, -inf};
  for (std::uint32_t v = door.first_vertex; v < door.first_vertex + door.vertex_count; ++v) {
    const Eigen::Vector3d p = plan.mesh.vertices[v].cast<double>();
    const double along = (p.head<2>() - a).dot(u), across = (p.head<2>() - a).dot(n);
    box.along_min = std::min(box.along_min, along), box.along_max = std::max(box.along_max, along);
    box.across_min = std::min(box.across_min, across), box.across_max = std::max(box.across_max, across);
    box.z_min = std::min(box.z_min, p.z()), box.z_max = std::max(box.z_max, p.z());
  }
  return box;
}

// A shut leaf fills the doorway in the wall's middle plane; an ajar one is turned about the
// jamb at the wall's start end, swinging out on the side the wall's left (+n) side faces.
void appendDoorLeaf(ComposedStorey& out, const PlanStorey& plan, const bim::MeshPart& door, const bim::Wall& wall,
                    const Eigen::Affine3d& motion, DoorState state, const SiteDoors& config) {
  const DoorBox box = doorBox(plan, door, wall);
  const Eigen::Vector2d s = wall.start.head<2>(), u = (wall.end.head<2>() - s).normalized(), n(-u.y(), u.x());
  const double mid = 0.5 * (box.across_min + box.across_max), width = box.along_max - box.along_min;
  Eigen::Vector2d a = s + box.along_min * u + mid * n, b = s + box.along_max * u + mid * n;
  if (state == DoorState::Ajar) {
    const double angle = config.ajar_angle_deg * kDegToRad;
    a = s + box.along_min * u + (box.across_max + 0.5 * config.leaf_thickness_m) * n;
    b = a + width * (std::cos(angle) * u + std::sin(angle) * n);
  }
  const auto moved = [&](const Eigen::Vector2d& p) { return (motion * Eigen::Vector3d(p.x(), p.y(), 0.0)).head<2>().eval(); };
  appendBox(out, door.id, "DoorLeaf", moved(a), moved(b), config.leaf_thickness_m, box.z_min, box.z_max);
}

// Dark elements: a fraction of the storey's opaque elements, each drawn from the seed in part order,
// (their own stream), whose triangles lose returns with sensor.dark_dropout; opaque glass with glass_dropout.
std::vector<float> darkTriangles(const ComposedStorey& storey, std::size_t index, const SiteSensor& sensor,
                                 std::uint64_t seed, std::vector<std::string>& dark) {
  std::vector<float> table;
  const bool darks = sensor.dark_fraction > 0.0 && sensor.dark_dropout > 0.0;
  if (!darks && sensor.glass_dropout <= 0.0) return table;
  table.assign(storey.mesh.triangles.size(), 0.0f);
  SeededRandom random(seed ^ (0xDA7Cull * (index + 1)), RandomStream::SiteSensor);
  for (const bim::MeshPart& part : storey.parts) {
    const bool is_dark = random.uniform() < sensor.dark_fraction && darks;
    // Glass left opaque (no pass fraction) is still glass to the sensor: it loses returns too.
    const double p = std::max(is_dark ? sensor.dark_dropout : 0.0, glassClass(part).empty() ? 0.0 : sensor.glass_dropout);
    if (is_dark) dark.push_back(part.id);
    if (p <= 0.0) continue;
    for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count && t < table.size(); ++t)
      table[t] = static_cast<float>(p);
  }
  return table;
}

}  // namespace

SiteTruth exactSiteTruth(const bim::Building& building, const std::vector<PlanStorey>* plan) {
  if (plan) return drawSite(building, *plan, SiteConfig{}, 0);
  SiteTruth truth;
  for (std::size_t s = 0; s < building.storeys.size(); ++s)
    for (const auto& w : building.storeys[s].walls) truth.walls.push_back({w.id, w.name, s, 0.0, 0.0, false});
  return truth;
}

ComposedStorey exactStorey(const PlanStorey& plan) {
  std::vector<PartEdit> edits(plan.parts.size());
  for (std::size_t i = 0; i < plan.parts.size(); ++i) edits[i].drop = isDoorPart(plan.parts[i]);
  return composeStorey(plan, edits);
}

World World::withSite(const SiteConfig& config, std::uint64_t seed) const {
  if (!impl_->plan)
    throw std::invalid_argument(impl_->source + ": a site (site: in the scenario, --site) needs the world as an IFC plan: "
                                "the meshes of an extract folder or a mesh file are not split by element");
  auto impl = std::make_unique<Impl>();
  impl->source = impl_->source;
  impl->building = impl_->building;
  impl->plan = impl_->plan;
  const auto& plan = *impl_->plan;
  impl->truth = drawSite(impl->building, plan, config, seed);
  SiteTruth& truth = impl->truth;
  std::map<std::string, std::size_t> glass_count;
  std::size_t first_wall = 0, door = 0;
  for (std::size_t s = 0; s < plan.size(); ++s) {
    const bim::Storey& storey = impl->building.storeys[s];
    std::map<std::string, std::size_t> wall_index;
    std::vector<Eigen::Affine3d> motions;
    for (std::size_t i = 0; i < storey.walls.size(); ++i) {
      wall_index[storey.walls[i].id] = i;
      motions.push_back(wallMotion(storey.walls[i], truth.walls[first_wall + i]));
    }
    const auto missing = [&](std::size_t i) { return truth.walls[first_wall + i].missing; };
    std::vector<PartEdit> edits(plan[s].parts.size());
    struct Leaf {
      std::size_t part;
      int host;
      DoorState state;
    };
    std::vector<Leaf> leaves;
    std::vector<Eigen::Vector2d> door_centres;
    for (std::size_t p = 0; p < plan[s].parts.size(); ++p) {
      const bim::MeshPart& part = plan[s].parts[p];
      PartEdit& edit = edits[p];
      const auto own = wall_index.find(part.id);
      const std::string glazed = glassClass(part);
      const bool hosted = isDoorPart(part) || glazed == "IfcWindow";
      const int host = own != wall_index.end() ? static_cast<int>(own->second) : hosted ? hostWall(storey, plan[s], part) : -1;
      if (host >= 0) {
        edit.drop = missing(static_cast<std::size_t>(host));  // a window in a wall not built is not there either
        edit.moved = true;
        edit.transform = motions[static_cast<std::size_t>(host)];
      }
      if (isDoorPart(part)) {
        DoorTruth& d = truth.doors[door++];
        edit.drop = true;  // the plan's door (frame and leaf) is never drawn: see appendDoorLeaf
        if (host >= 0) {
          const bim::Wall& w = storey.walls[static_cast<std::size_t>(host)];
          const DoorBox box = doorBox(plan[s], part, w);
          const Eigen::Vector2d c = w.start.head<2>() + 0.5 * (box.along_min + box.along_max) * (w.end - w.start).head<2>().normalized();
          door_centres.push_back((motions[static_cast<std::size_t>(host)] * Eigen::Vector3d(c.x(), c.y(), 0)).head<2>());
        }
        if (d.state == DoorState::Open) continue;
        if (host < 0 || missing(static_cast<std::size_t>(host))) {
          truth.warnings.push_back("door " + d.id + (d.name.empty() ? "" : " '" + d.name + "'") + ": left open (" +
                                   (host < 0 ? "in no wall of the plan" : "its wall is not built") + "), not " + toString(d.state));
          d.state = DoorState::Open;
          continue;
        }
        leaves.push_back({p, host, d.state});
        continue;
      }
      if (!glazed.empty() && !edit.drop) {
        const auto it = config.glass.pass_fraction.find(glazed);
        if (it != config.glass.pass_fraction.end() && it->second > 0.0) {
          edit.pass_fraction = static_cast<float>(it->second);
          ++glass_count[glazed];
        }
      }
    }
    ComposedStorey composed = composeStorey(plan[s], edits);
    for (const Leaf& leaf : leaves)
      appendDoorLeaf(composed, plan[s], plan[s].parts[leaf.part], storey.walls[static_cast<std::size_t>(leaf.host)],
                     motions[static_cast<std::size_t>(leaf.host)], leaf.state, config.doors);
    placePartitions(storey, s, config.walls, motions, door_centres, seed, composed, truth);
    placeClutter(storey, s, config.clutter, motions, door_centres, seed, composed, truth);
    impl->triangle_dropout.push_back(darkTriangles(composed, s, config.sensor, seed, truth.dark));
    composed.glass.seed = seed;
    impl->building.storeys[s].mesh = std::move(composed.mesh);
    impl->building.storeys[s].mesh_parts = std::move(composed.parts);
    impl->glass.push_back(std::make_unique<GlassLayer>(std::move(composed.glass)));
    first_wall += storey.walls.size();
  }
  for (const auto& [type, fraction] : config.glass.pass_fraction)
    if (fraction > 0.0) truth.glass.push_back({type, fraction, glass_count[type]});
  truth.sensor = config.sensor;
  impl->glass_dropout = static_cast<float>(config.sensor.glass_dropout);
  impl->any_dropout = impl->glass_dropout > 0.0f;
  for (const auto& table : impl->triangle_dropout) impl->any_dropout = impl->any_dropout || !table.empty();
  impl->build();
  World world(std::move(impl));
  // People walk the site as built (its walls, shut doors, clutter): placed in the built world.
  placePeople(world, config.people, seed, world.impl_->truth);
  return world;
}

const SiteTruth& World::siteTruth() const { return impl_->truth; }

}  // namespace bimloc::sim
