// World's insides, shared by world.cpp (loading, queries) and site_world.cpp (the site
// variants of a plan's world).
#pragma once

#include "sim/world/glass_layer.hpp"
#include "sim/world/site_truth.hpp"
#include "sim/world/world.hpp"

#include <btBulletCollisionCommon.h>
#include <embree3/rtcore.h>

#include <memory>
#include <mutex>
#include <vector>

namespace bimloc::sim {

// One storey's Bullet collision world. Bullet keeps raw pointers between these objects, so
// they live together, in this order, and are never moved.
struct BulletStorey {
  struct Body {  // one mesh: the opaque one, and the glazing
    std::unique_ptr<btTriangleIndexVertexArray> arrays;
    std::unique_ptr<btBvhTriangleMeshShape> shape;
    std::unique_ptr<btCollisionObject> object;
  };
  std::unique_ptr<btDefaultCollisionConfiguration> config;
  std::unique_ptr<btCollisionDispatcher> dispatcher;
  std::unique_ptr<btDbvtBroadphase> broadphase;
  std::unique_ptr<btCollisionWorld> world;
  std::vector<Body> bodies;
  ~BulletStorey() {  // the world's destructor would touch objects already gone
    if (world)
      for (auto& body : bodies) world->removeCollisionObject(body.object.get());
  }
  // Queries from parallel runs (`--jobs`) share the world, and Bullet's queries are not
  // thread-safe: contactTest allocates its collision algorithm from the dispatcher's pool, and
  // the broadphase's ray and sweep tests share one traversal stack. Unserialized, two runs
  // planning at once crashed in libBulletCollision.
  mutable std::mutex mutex;
};

// One storey's plan mesh with door leaves, by element: what every site of the plan is made from.
struct PlanStorey {
  bim::TriangleMesh mesh;
  std::vector<bim::MeshPart> parts;
};

struct World::Impl {
  std::string source;
  bim::Building building;  // the plan; storeys[s].mesh is the world's opaque mesh (plan or site)
  // The plan's meshes by element (shared by a plan's world and its sites); null for a mesh
  // file or an extract folder, whose meshes are not split by element.
  std::shared_ptr<const std::vector<PlanStorey>> plan;
  std::vector<std::unique_ptr<GlassLayer>> glass;  // per storey (empty: no glass passes rays)
  SiteTruth truth;
  // Sensor dropout (SiteSensor): per storey, per opaque triangle (empty: none), and for glass.
  std::vector<std::vector<float>> triangle_dropout;
  float glass_dropout = 0.0f;
  bool any_dropout = false;  // any of the above non-zero: the plan's world skips the look-up
  std::vector<unsigned> opaque_geometry;  // per storey: the opaque mesh's Embree geometry id
  RTCDevice device = nullptr;
  std::vector<RTCScene> scenes;
  // Every storey's geometries in one scene: World::kAllStoreys. Null for a single storey
  // (scenes[0] serves). all_geometry[id]: the storey and the geometry id there of its id.
  RTCScene all_scene = nullptr;
  struct StoreyGeometry {
    std::size_t storey = 0;
    unsigned id = 0;
  };
  std::vector<StoreyGeometry> all_geometry;
  RTCScene scene(std::size_t storey) const;
  std::vector<std::unique_ptr<BulletStorey>> bullet;

  ~Impl();
  void build();
  float dropout(std::size_t storey, unsigned geometry, unsigned triangle) const;
  static std::unique_ptr<BulletStorey> makeBullet(const std::vector<bim::TriangleMesh*>& meshes);
};

// The plan's own site (nothing moved, every door open) and its storey mesh: the plan's
// elements without the doors (site_world.cpp). plan is null for a world not read from IFC.
SiteTruth exactSiteTruth(const bim::Building& building, const std::vector<PlanStorey>* plan);
struct ComposedStorey;
ComposedStorey exactStorey(const PlanStorey& plan);

}  // namespace bimloc::sim
