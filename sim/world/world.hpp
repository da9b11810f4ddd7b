// The simulated building: one Embree scene per storey for the lidar, and one Bullet
// collision world of the same mesh for the base. Built from an IFC plan (through the
// extraction), from the output folder of `bimloc extract`, or from a single mesh file.
#pragma once

#include "sim/world/site_config.hpp"
#include "sim/world/site_truth.hpp"

#include <bimloc/bim/building.hpp>

#include <Eigen/Core>
#include <memory>
#include <string>

namespace bimloc::sim {

struct RayHit {
  float range_m = 0.0f;  // +inf when the ray hits nothing within its range
  Eigen::Vector3f normal = Eigen::Vector3f::Zero();  // unit geometric normal, facing the ray
  float dropout = 0.0f;  // probability the sensor loses this return (a site's glass, dark surfaces)
  bool hit() const;
};

class World {
 public:
  // An IFC plan: extraction, then the storey meshes, without doors (doorways are open, as on a
  // site before the doors are hung).
  static World fromPlan(const std::string& ifc_path);
  // A folder written by `bimloc extract --out` (building.json + storey meshes).
  static World fromExtractDir(const std::string& dir);
  // One mesh file (PLY, OBJ, glTF, STL, DAE) as a single storey at elevation 0, no rooms.
  static World fromMesh(const std::string& mesh_path);
  // A building made in code (tests): its storeys' meshes as they are, in world coordinates,
  // its rooms and stairs as given; no site can be built from it.
  static World fromBuilding(bim::Building building);
  // Any of the three, by what the path is.
  static World load(const std::string& path);

  // The same plan built as a site (sim/world/site_config.hpp): walls shifted, turned or not
  // built, temporary partitions, glass passing rays, door leaves shut or ajar, all drawn from
  // `seed` (the same seed gives the same world, bit for bit). building() stays the plan; only
  // what the lidar and the base meet differs. Needs a world read from an IFC plan;
  // std::invalid_argument otherwise, and for an edit naming no wall or door of the plan.
  World withSite(const SiteConfig& config, std::uint64_t seed) const;
  // What this world is against its plan: every wall's offset, angle and whether it is built,
  // partitions, doors, glass (all zero / open for a plan's own world).
  const SiteTruth& siteTruth() const;

  World(World&&) noexcept;
  World& operator=(World&&) noexcept;
  ~World();

  const std::string& source() const;
  const bim::Building& building() const;  // storeys, rooms, walls (no rooms for a mesh world)
  std::size_t storeyCount() const;
  // Index of a storey by name, GlobalId or index; throws std::invalid_argument listing them.
  std::size_t storeyIndex(const std::string& name_or_index) const;
  std::size_t triangleCount(std::size_t storey) const;
  // The storey index of the whole building for the lidar (castRay, castRays16, embreeScene):
  // every storey's mesh at once, each in world coordinates, so a base climbing the stairs sees
  // the storey it leaves and the one it reaches (issue 31). Bullet's queries take real storeys.
  static constexpr std::size_t kAllStoreys = static_cast<std::size_t>(-1);

  // Embree: the first hit of the ray origin + t dir (dir unit), t in [t_min, t_max].
  RayHit castRay(std::size_t storey, const Eigen::Vector3f& origin, const Eigen::Vector3f& dir,
                 float t_min, float t_max) const;
  // Embree, up to 16 rays in one packet (the first `count`): coherent rays, such as one
  // laser over 16 consecutive firings, share most of their traversal.
  void castRays16(std::size_t storey, const Eigen::Vector3f origins[16], const Eigen::Vector3f dirs[16],
                  float t_min, float t_max, RayHit hits[16], int count = 16) const;
  // The bare Embree scene handle (RTCScene), for the benchmark's plain loop.
  void* embreeScene(std::size_t storey) const;

  // Bullet: the same ray through btCollisionWorld::rayTest (the second implementation).
  RayHit bulletRay(std::size_t storey, const Eigen::Vector3d& from, const Eigen::Vector3d& to) const;
  // Bullet: can a sphere of radius_m move from `from` to `to` without touching the mesh?
  // On contact, `contact` (if given) receives the first point touched.
  bool sweepClear(std::size_t storey, const Eigen::Vector3d& from, const Eigen::Vector3d& to, double radius_m,
                  Eigen::Vector3d* contact = nullptr) const;
  // Bullet: does a sphere of radius_m at `centre` stay clear of the mesh? A static overlap test:
  // sweeps do not report a triangle the sphere already cuts at their start.
  bool sphereClear(std::size_t storey, const Eigen::Vector3d& centre, double radius_m,
                   Eigen::Vector3d* contact = nullptr) const;
  // Bullet: z of the first surface below `from` (the floor under the base), if any within max_drop_m.
  bool floorBelow(std::size_t storey, const Eigen::Vector3d& from, double max_drop_m, double* floor_z) const;

 private:
  struct Impl;
  explicit World(std::unique_ptr<Impl> impl);
  std::unique_ptr<Impl> impl_;
};

}  // namespace bimloc::sim
