#include "sim/world/glass_layer.hpp"

#include "sim/world/embree_mesh.hpp"

#include <embree3/rtcore.h>

#include <cstring>
#include <stdexcept>

namespace bimloc::sim {
namespace {

std::uint64_t mix(std::uint64_t z) {  // SplitMix64's finaliser
  z += 0x9e3779b97f4a7c15ULL;
  z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
  z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
  return z ^ (z >> 31);
}

std::uint32_t bits(float f) {
  std::uint32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}

void glassFilter(const RTCFilterFunctionNArguments* args) {
  const auto* layer = static_cast<const GlassLayer*>(args->geometryUserPtr);
  const unsigned n = args->N;
  for (unsigned i = 0; i < n; ++i) {
    if (args->valid[i] != -1) continue;
    const unsigned prim = RTCHitN_primID(args->hit, n, i);
    const float origin[3] = {RTCRayN_org_x(args->ray, n, i), RTCRayN_org_y(args->ray, n, i), RTCRayN_org_z(args->ray, n, i)};
    const float dir[3] = {RTCRayN_dir_x(args->ray, n, i), RTCRayN_dir_y(args->ray, n, i), RTCRayN_dir_z(args->ray, n, i)};
    if (glassPasses(*layer, layer->element_of_triangle[prim], origin, dir)) args->valid[i] = 0;
  }
}

}  // namespace

bool glassPasses(const GlassLayer& layer, std::uint32_t element, const float origin[3], const float dir[3]) {
  const float fraction = layer.pass_fraction[element];
  if (fraction <= 0.0f) return false;
  if (fraction >= 1.0f) return true;
  std::uint64_t h = mix(layer.seed ^ mix(element));
  for (int k = 0; k < 3; ++k) h = mix(h ^ (std::uint64_t(bits(origin[k])) << 32 | bits(dir[k])));
  return static_cast<double>(h >> 11) * 0x1.0p-53 < fraction;
}

void attachGlass(void* device_handle, void* scene_handle, const GlassLayer& layer) {
  if (layer.mesh.empty()) return;
  auto device = static_cast<RTCDevice>(device_handle);
  if (!rtcGetDeviceProperty(device, RTC_DEVICE_PROPERTY_FILTER_FUNCTION_SUPPORTED))
    throw std::runtime_error("this Embree was built without filter functions: glass cannot pass rays");
  const auto& mesh = layer.mesh;
  RTCGeometry geometry = newTriangleGeometry(device, mesh);
  rtcSetGeometryUserData(geometry, const_cast<GlassLayer*>(&layer));
  rtcSetGeometryIntersectFilterFunction(geometry, glassFilter);
  rtcCommitGeometry(geometry);
  rtcAttachGeometry(static_cast<RTCScene>(scene_handle), geometry);
  rtcReleaseGeometry(geometry);
}

}  // namespace bimloc::sim
