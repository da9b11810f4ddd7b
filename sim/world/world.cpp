#include "sim/world/world.hpp"

#include "sim/world/embree_mesh.hpp"
#include "sim/common/json_errors.hpp"
#include "sim/world/mesh_io.hpp"
#include "sim/world/site_mesh.hpp"
#include "sim/world/world_impl.hpp"

#include <bimloc/bim/building_json.hpp>
#include <bimloc/bim/ifc_reader.hpp>

#include <btBulletCollisionCommon.h>
#include <embree3/rtcore.h>

#include <filesystem>
#include <fstream>
#include <limits>
#include <mutex>
#include <stdexcept>

namespace bimloc::sim {
namespace fs = std::filesystem;

namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

Eigen::Vector3f normalFacing(const Eigen::Vector3f& ng, const Eigen::Vector3f& dir) {
  const Eigen::Vector3f n = ng.normalized();
  return n.dot(dir) > 0 ? -n : n;
}

}  // namespace

bool RayHit::hit() const { return range_m < kInf; }

void World::Impl::build() {
  device = rtcNewDevice(nullptr);
  if (!device) throw std::runtime_error(source + ": cannot create an Embree device");
  glass.resize(building.storeys.size());
  for (std::size_t s = 0; s < building.storeys.size(); ++s) {
    const auto& mesh = building.storeys[s].mesh;
    RTCScene scene = rtcNewScene(device);
    // Robust: rays graze wall corners and door jambs all the time.
    rtcSetSceneFlags(scene, RTC_SCENE_FLAG_ROBUST);
    opaque_geometry.push_back(RTC_INVALID_GEOMETRY_ID);
    if (!mesh.empty()) {
      RTCGeometry geometry = newTriangleGeometry(device, mesh);
      rtcCommitGeometry(geometry);
      opaque_geometry.back() = rtcAttachGeometry(scene, geometry);
      rtcReleaseGeometry(geometry);
    }
    if (!glass[s]) glass[s] = std::make_unique<GlassLayer>();
    attachGlass(device, scene, *glass[s]);
    rtcCommitScene(scene);
    scenes.push_back(scene);
    // The robot never walks through glass: Bullet has the glazing as solid as the rest.
    bullet.push_back(makeBullet({&building.storeys[s].mesh, &glass[s]->mesh}));
  }
  if (scenes.size() < 2) return;
  // The whole building as one flat scene of every storey's geometries (the same buffers and
  // filters, attached again), not as instances of the storeys' scenes: storeys overlap in
  // height (a facade filed under one storey stands through two, split levels), and a ray then
  // walked the BVH of every storey whose box it crossed. One BVH over every triangle costs about
  // what one storey's did (session 22's cost table).
  all_scene = rtcNewScene(device);
  rtcSetSceneFlags(all_scene, RTC_SCENE_FLAG_ROBUST);
  for (std::size_t s = 0; s < scenes.size(); ++s) {
    // Attached above in this order, ids from 0: the opaque mesh (if any), the glass (if any).
    const unsigned count = (building.storeys[s].mesh.empty() ? 0u : 1u) + (glass[s]->mesh.empty() ? 0u : 1u);
    for (unsigned id = 0; id < count; ++id) {
      RTCGeometry geometry = rtcGetGeometry(scenes[s], id);
      all_geometry.push_back({s, id});
      rtcAttachGeometryByID(all_scene, geometry, static_cast<unsigned>(all_geometry.size() - 1));
    }
  }
  rtcCommitScene(all_scene);
}

RTCScene World::Impl::scene(std::size_t storey) const {
  if (storey == World::kAllStoreys) return all_scene ? all_scene : scenes.at(0);
  return scenes.at(storey);
}

float World::Impl::dropout(std::size_t storey, unsigned geometry, unsigned triangle) const {
  if (storey == World::kAllStoreys) {
    if (!all_scene) storey = 0;  // one storey: its scene serves, ids unchanged
    else if (geometry >= all_geometry.size()) return 0.0f;
    else storey = all_geometry[geometry].storey, geometry = all_geometry[geometry].id;
  }
  if (geometry != opaque_geometry[storey]) return glass_dropout;
  if (storey >= triangle_dropout.size() || triangle >= triangle_dropout[storey].size()) return 0.0f;
  return triangle_dropout[storey][triangle];
}

std::unique_ptr<BulletStorey> World::Impl::makeBullet(const std::vector<bim::TriangleMesh*>& meshes) {
  auto b = std::make_unique<BulletStorey>();
  b->config = std::make_unique<btDefaultCollisionConfiguration>();
  b->dispatcher = std::make_unique<btCollisionDispatcher>(b->config.get());
  b->broadphase = std::make_unique<btDbvtBroadphase>();
  b->world = std::make_unique<btCollisionWorld>(b->dispatcher.get(), b->broadphase.get(), b->config.get());
  for (bim::TriangleMesh* mesh : meshes) {
    if (mesh->empty()) continue;
    // Bullet reads the mesh in place: vertices as float triples, indices as int triples.
    static_assert(sizeof(Eigen::Vector3f) == 3 * sizeof(float), "packed vertices");
    auto& body = b->bodies.emplace_back();
    body.arrays = std::make_unique<btTriangleIndexVertexArray>(
        static_cast<int>(mesh->triangles.size()), reinterpret_cast<int*>(mesh->triangles.data()), 3 * sizeof(int),
        static_cast<int>(mesh->vertices.size()), reinterpret_cast<btScalar*>(mesh->vertices.data()), 3 * sizeof(float));
    body.shape = std::make_unique<btBvhTriangleMeshShape>(body.arrays.get(), true);
    body.object = std::make_unique<btCollisionObject>();
    body.object->setCollisionShape(body.shape.get());
    b->world->addCollisionObject(body.object.get());
  }
  b->world->updateAabbs();
  return b;
}

World::Impl::~Impl() {
  // Bullet's objects first (they point into the meshes), then Embree's scenes.
  bullet.clear();
  if (all_scene) rtcReleaseScene(all_scene);
  for (RTCScene s : scenes) rtcReleaseScene(s);
  if (device) rtcReleaseDevice(device);
}

World::World(std::unique_ptr<Impl> impl) : impl_(std::move(impl)) {}
World::World(World&&) noexcept = default;
World& World::operator=(World&&) noexcept = default;
World::~World() = default;

World World::fromPlan(const std::string& ifc_path) {
  auto impl = std::make_unique<Impl>();
  impl->source = ifc_path;
  // With the doors, by element: a site may hang them (withSite); the plan's own world leaves
  // them out, doorways not doors (see ExtractOptions::door_leaves), and is then exactly the
  // mesh an extraction without door leaves makes.
  impl->building = bim::readIfc(ifc_path);
  auto plan = std::make_shared<std::vector<PlanStorey>>();
  for (auto& storey : impl->building.storeys) {
    plan->push_back({std::move(storey.mesh), std::move(storey.mesh_parts)});
    ComposedStorey exact = exactStorey(plan->back());
    storey.mesh = std::move(exact.mesh);
    storey.mesh_parts = std::move(exact.parts);
  }
  impl->plan = plan;
  impl->truth = exactSiteTruth(impl->building, plan.get());
  impl->build();
  return World(std::move(impl));
}

World World::fromExtractDir(const std::string& dir) {
  const std::string json_path = (fs::path(dir) / "building.json").string();
  std::ifstream in(json_path);
  if (!in) throw std::runtime_error(json_path + ": cannot open (is this a folder written by 'bimloc extract --out'?)");
  nlohmann::json doc;
  try {
    doc = nlohmann::json::parse(in);
  } catch (const std::exception& e) {
    throw std::runtime_error(json_path + ": " + jsonProblem(e));
  }
  auto impl = std::make_unique<Impl>();
  impl->source = dir;
  try {
    impl->building = bim::buildingFromJson(doc);
  } catch (const std::exception& e) {
    throw std::runtime_error(json_path + ": " + jsonProblem(e));
  }
  for (std::size_t s = 0; s < impl->building.storeys.size(); ++s) {
    const auto& mesh = doc["storeys"][s]["mesh"];
    if (mesh.is_string()) impl->building.storeys[s].mesh = loadMesh((fs::path(dir) / mesh.get<std::string>()).string());
  }
  impl->truth = exactSiteTruth(impl->building, nullptr);
  impl->build();
  return World(std::move(impl));
}

World World::fromMesh(const std::string& mesh_path) {
  auto impl = std::make_unique<Impl>();
  impl->source = mesh_path;
  bim::Storey storey;
  storey.name = fs::path(mesh_path).stem().string();
  storey.mesh = loadMesh(mesh_path);
  impl->building.file = mesh_path;
  impl->building.storeys.push_back(std::move(storey));
  impl->truth = exactSiteTruth(impl->building, nullptr);
  impl->build();
  return World(std::move(impl));
}

World World::fromBuilding(bim::Building building) {
  auto impl = std::make_unique<Impl>();
  impl->source = building.file.empty() ? std::string("(building made in code)") : building.file;
  impl->building = std::move(building);
  impl->truth = exactSiteTruth(impl->building, nullptr);
  impl->build();
  return World(std::move(impl));
}

World World::load(const std::string& path) {
  if (fs::is_directory(path)) return fromExtractDir(path);
  std::string ext = fs::path(path).extension().string();
  for (char& c : ext) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (ext == ".ifc") return fromPlan(path);
  return fromMesh(path);
}

const std::string& World::source() const { return impl_->source; }
const bim::Building& World::building() const { return impl_->building; }
std::size_t World::storeyCount() const { return impl_->building.storeys.size(); }
std::size_t World::triangleCount(std::size_t storey) const {
  return impl_->building.storeys.at(storey).mesh.triangles.size();
}

std::size_t World::storeyIndex(const std::string& name_or_index) const {
  const auto& storeys = impl_->building.storeys;
  if (const bim::Storey* s = impl_->building.findStorey(name_or_index))
    return static_cast<std::size_t>(s - storeys.data());
  throw std::invalid_argument(impl_->building.storeyLookupError(name_or_index));
}

void* World::embreeScene(std::size_t storey) const { return impl_->scene(storey); }

RayHit World::castRay(std::size_t storey, const Eigen::Vector3f& origin, const Eigen::Vector3f& dir, float t_min,
                      float t_max) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  RTCRayHit rh{};
  rh.ray.org_x = origin.x(), rh.ray.org_y = origin.y(), rh.ray.org_z = origin.z();
  rh.ray.dir_x = dir.x(), rh.ray.dir_y = dir.y(), rh.ray.dir_z = dir.z();
  rh.ray.tnear = t_min, rh.ray.tfar = t_max;
  rh.ray.mask = 0xFFFFFFFFu;
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(impl_->scene(storey), &context, &rh);
  RayHit hit;
  if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) {
    hit.range_m = kInf;
    return hit;
  }
  hit.range_m = rh.ray.tfar;
  hit.normal = normalFacing({rh.hit.Ng_x, rh.hit.Ng_y, rh.hit.Ng_z}, dir);
  hit.dropout = impl_->any_dropout ? impl_->dropout(storey, rh.hit.geomID, rh.hit.primID) : 0.0f;
  return hit;
}

void World::castRays16(std::size_t storey, const Eigen::Vector3f origins[16], const Eigen::Vector3f dirs[16], float t_min,
                       float t_max, RayHit hits[16], int count) const {
  RTCIntersectContext context;
  rtcInitIntersectContext(&context);
  context.flags = RTC_INTERSECT_CONTEXT_FLAG_COHERENT;
  alignas(64) RTCRayHit16 rh;
  alignas(64) int valid[16];
  for (int i = 0; i < 16; ++i) {
    valid[i] = i < count ? -1 : 0;
    rh.ray.org_x[i] = origins[i].x(), rh.ray.org_y[i] = origins[i].y(), rh.ray.org_z[i] = origins[i].z();
    rh.ray.dir_x[i] = dirs[i].x(), rh.ray.dir_y[i] = dirs[i].y(), rh.ray.dir_z[i] = dirs[i].z();
    rh.ray.tnear[i] = t_min, rh.ray.tfar[i] = t_max;
    rh.ray.mask[i] = 0xFFFFFFFFu, rh.ray.time[i] = 0.0f, rh.ray.flags[i] = 0, rh.ray.id[i] = static_cast<unsigned>(i);
    rh.hit.geomID[i] = RTC_INVALID_GEOMETRY_ID;
  }
  rtcIntersect16(valid, impl_->scene(storey), &context, &rh);
  for (int i = 0; i < count; ++i) {
    if (rh.hit.geomID[i] == RTC_INVALID_GEOMETRY_ID) {
      hits[i].range_m = kInf;
      hits[i].dropout = 0.0f;
      continue;
    }
    hits[i].range_m = rh.ray.tfar[i];
    hits[i].normal = normalFacing({rh.hit.Ng_x[i], rh.hit.Ng_y[i], rh.hit.Ng_z[i]}, dirs[i]);
    hits[i].dropout = impl_->any_dropout ? impl_->dropout(storey, rh.hit.geomID[i], rh.hit.primID[i]) : 0.0f;
  }
}

RayHit World::bulletRay(std::size_t storey, const Eigen::Vector3d& from, const Eigen::Vector3d& to) const {
  const btVector3 a(btScalar(from.x()), btScalar(from.y()), btScalar(from.z()));
  const btVector3 b(btScalar(to.x()), btScalar(to.y()), btScalar(to.z()));
  btCollisionWorld::ClosestRayResultCallback callback(a, b);
  {
    const auto& bullet = *impl_->bullet.at(storey);
    const std::lock_guard<std::mutex> lock(bullet.mutex);
    bullet.world->rayTest(a, b, callback);
  }
  RayHit hit;
  if (!callback.hasHit()) {
    hit.range_m = kInf;
    return hit;
  }
  hit.range_m = static_cast<float>(callback.m_closestHitFraction * (to - from).norm());
  const btVector3& n = callback.m_hitNormalWorld;
  hit.normal = normalFacing({float(n.x()), float(n.y()), float(n.z())}, (to - from).cast<float>());
  return hit;
}

bool World::sweepClear(std::size_t storey, const Eigen::Vector3d& from, const Eigen::Vector3d& to, double radius_m,
                       Eigen::Vector3d* contact) const {
  const auto& b = *impl_->bullet.at(storey);
  if (b.bodies.empty()) return true;
  btSphereShape sphere{static_cast<btScalar>(radius_m)};
  btTransform start, end;
  start.setIdentity(), end.setIdentity();
  start.setOrigin(btVector3(btScalar(from.x()), btScalar(from.y()), btScalar(from.z())));
  end.setOrigin(btVector3(btScalar(to.x()), btScalar(to.y()), btScalar(to.z())));
  btCollisionWorld::ClosestConvexResultCallback callback(start.getOrigin(), end.getOrigin());
  {
    const std::lock_guard<std::mutex> lock(b.mutex);
    b.world->convexSweepTest(&sphere, start, end, callback);
  }
  if (!callback.hasHit()) return true;
  if (contact) {
    const btVector3& p = callback.m_hitPointWorld;
    *contact = Eigen::Vector3d(p.x(), p.y(), p.z());
  }
  return false;
}

namespace {
// Records the first contact of a contactTest; ignores touching within Bullet's margin.
struct FirstContact : btCollisionWorld::ContactResultCallback {
  bool hit = false;
  btVector3 point{0, 0, 0};
  btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper*, int, int,
                           const btCollisionObjectWrapper*, int, int) override {
    if (cp.getDistance() < 0 && !hit) hit = true, point = cp.getPositionWorldOnB();
    return 0;
  }
};
}  // namespace

bool World::sphereClear(std::size_t storey, const Eigen::Vector3d& centre, double radius_m,
                        Eigen::Vector3d* contact) const {
  const auto& b = *impl_->bullet.at(storey);
  if (b.bodies.empty()) return true;
  btSphereShape sphere{static_cast<btScalar>(radius_m)};
  btCollisionObject body;
  body.setCollisionShape(&sphere);
  btTransform pose;
  pose.setIdentity();
  pose.setOrigin(btVector3(btScalar(centre.x()), btScalar(centre.y()), btScalar(centre.z())));
  body.setWorldTransform(pose);
  FirstContact callback;
  {
    const std::lock_guard<std::mutex> lock(b.mutex);
    b.world->contactTest(&body, callback);
  }
  if (callback.hit && contact) *contact = Eigen::Vector3d(callback.point.x(), callback.point.y(), callback.point.z());
  return !callback.hit;
}

bool World::floorBelow(std::size_t storey, const Eigen::Vector3d& from, double max_drop_m, double* floor_z) const {
  const Eigen::Vector3d down(0, 0, -1);
  const RayHit hit = bulletRay(storey, from, from + max_drop_m * down);
  if (!hit.hit()) return false;
  if (floor_z) *floor_z = from.z() - hit.range_m;
  return true;
}

}  // namespace bimloc::sim
