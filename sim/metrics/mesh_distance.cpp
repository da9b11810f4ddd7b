#include "sim/metrics/mesh_distance.hpp"

#include "sim/world/embree_mesh.hpp"

#include <embree3/rtcore.h>

#include <cmath>
#include <limits>

namespace bimloc::sim {

Eigen::Vector3d closestPointOnTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                       const Eigen::Vector3d& c) {
  // The Voronoi regions of the vertices, then of the edges, else the face.
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = va + vb + vc;
  if (!(std::abs(denom) > 0)) return a;  // degenerate: a line or a point
  return a + ab * (vb / denom) + ac * (vc / denom);
}

struct MeshDistance::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  std::vector<Eigen::Vector3d> vertices;
  std::vector<std::array<std::uint32_t, 3>> triangles;
  ~Impl() {
    if (scene) rtcReleaseScene(scene);
    if (device) rtcReleaseDevice(device);
  }
};

namespace {

struct Query {
  const std::vector<Eigen::Vector3d>* vertices;
  const std::vector<std::array<std::uint32_t, 3>>* triangles;
  Eigen::Vector3d p;
  double best_sq = std::numeric_limits<double>::infinity();
};

}  // namespace

MeshDistance::MeshDistance(const bim::TriangleMesh& mesh) : impl_(std::make_unique<Impl>()) {
  Impl& m = *impl_;
  for (const auto& v : mesh.vertices) m.vertices.push_back(v.cast<double>());
  m.triangles = mesh.triangles;
  if (mesh.empty()) return;
  m.device = rtcNewDevice("threads=1");
  m.scene = rtcNewScene(m.device);
  RTCGeometry geometry = newTriangleGeometry(m.device, mesh);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(m.scene, geometry);
  rtcReleaseGeometry(geometry);
  rtcCommitScene(m.scene);
}

MeshDistance::~MeshDistance() = default;
MeshDistance::MeshDistance(MeshDistance&&) noexcept = default;

double MeshDistance::distance(const Eigen::Vector3d& p) const {
  const Impl& m = *impl_;
  if (!m.scene || !p.allFinite()) return std::numeric_limits<double>::infinity();
  RTCPointQuery query;
  query.x = static_cast<float>(p.x()), query.y = static_cast<float>(p.y()), query.z = static_cast<float>(p.z());
  query.time = 0.f;
  query.radius = std::numeric_limits<float>::infinity();
  RTCPointQueryContext context;
  rtcInitPointQueryContext(&context);
  Query q{&m.vertices, &m.triangles, p};
  // Each candidate triangle: its exact closest point; a closer one shrinks the search radius.
  const auto visit = [](RTCPointQueryFunctionArguments* args) -> bool {
    auto* at = static_cast<Query*>(args->userPtr);
    const auto& tri = (*at->triangles)[args->primID];
    const auto& v = *at->vertices;
    const Eigen::Vector3d c = closestPointOnTriangle(at->p, v[tri[0]], v[tri[1]], v[tri[2]]);
    const double d_sq = (c - at->p).squaredNorm();
    if (d_sq >= at->best_sq) return false;
    at->best_sq = d_sq;
    args->query->radius = static_cast<float>(std::sqrt(d_sq)) * (1.0f + 1e-6f) + 1e-6f;
    return true;
  };
  rtcPointQuery(m.scene, &query, &context, visit, &q);
  return std::sqrt(q.best_sq);
}

}  // namespace bimloc::sim
