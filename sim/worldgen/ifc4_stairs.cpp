#include "sim/worldgen/ifc4_stairs.hpp"

#include <algorithm>
#include <vector>

namespace bimloc::worldgen::ifc {
namespace {

// The steps' underside runs parallel to the pitch line, this far (vertically) below the inner
// corners of the steps: a cast-in-place flight's waist.
constexpr double kWaist_m = 0.15;
// The opening box reaches this far above and below the slab, so that the boolean subtraction
// never cuts coplanar faces.
constexpr double kSlabOpeningOverlap_m = 0.05;
// Parts of one stair get GlobalId indices index * kPartsPerStair + part.
constexpr std::size_t kPartsPerStair = 16;

// The flight's side view in its own frame (u along the run, v up), counter-clockwise: risers
// and treads on top, the waist's underside below, from the first riser's foot (u = 0) to the
// last tread's end (u = treads · going), where the landing's front is the last riser.
std::vector<Vector2d> flightProfile(const StairFlightSpec& f) {
  const double r = f.riser_m, g = f.going_m;
  const int treads = f.treads();
  std::vector<Vector2d> clockwise = {{0.0, 0.0}, {0.0, r}};
  for (int k = 1; k <= treads; ++k) {
    clockwise.emplace_back(k * g, k * r);
    if (k < treads) clockwise.emplace_back(k * g, (k + 1) * r);
  }
  clockwise.emplace_back(treads * g, treads * r - kWaist_m);
  clockwise.emplace_back(g * kWaist_m / r, 0.0);  // where the underside meets the floor
  return {clockwise.rbegin(), clockwise.rend()};
}

int writeFlight(ItemWriter& w, const StairFlightSpec& f, int storey_placement, const std::string& quoted_id) {
  const Vector3d x(f.direction.x(), f.direction.y(), 0.0);
  const int placement = localPlacement(
      w, storey_placement, axes(w, Vector3d(f.start.x(), f.start.y(), f.z_m), Vector3d::UnitZ(), x));
  // Walking line: the run line, from the first riser to the last.
  const int walking = polyline(w, {Vector2d::Zero(), Vector2d(f.run_m(), 0.0)}, false);
  const int axis_rep = representation(w, w.axis_context, "Axis", "Curve2D", walking);
  // The side view in the vertical plane through the flight's left edge, swept across its width.
  const int position = axes(w, Vector3d(0.0, f.width_m / 2, 0.0), -Vector3d::UnitY(), Vector3d::UnitX());
  const int solid = extrusion(w, polygonProfile(w, flightProfile(f)), position, f.width_m);
  const int body_rep = representation(w, w.body_context, "Body", "SweptSolid", solid);
  const int shape = w.file.add("IFCPRODUCTDEFINITIONSHAPE", {step::unset(), step::unset(), refs({axis_rep, body_rep})});
  return w.file.add("IFCSTAIRFLIGHT",
                    root(quoted_id, f.name) + std::vector<std::string>{step::unset(), ref(placement), ref(shape), step::unset(),
                                                                       step::integer(f.risers), step::integer(f.treads()),
                                                                       real(f.riser_m), real(f.going_m), ".STRAIGHT."});
}

int writeLanding(ItemWriter& w, const LandingSpec& l, int storey_placement, const std::string& quoted_id) {
  const int solid = extrusion(w, polygonProfile(w, l.outline), translation(w, Vector3d(0.0, 0.0, l.top_z_m - l.thickness_m)),
                              l.thickness_m);
  const int placement = localPlacement(w, storey_placement, w.origin_axes);
  return w.file.add("IFCSLAB", root(quoted_id, l.name) + std::vector<std::string>{step::unset(), ref(placement),
                                                                                  ref(bodyShape(w, solid)), step::unset(),
                                                                                  ".LANDING."});
}

}  // namespace

int writeStair(ItemWriter& w, const StairSpec& stair, std::size_t index, int storey_placement, const IdFor& id) {
  std::vector<int> parts;
  std::size_t part = 0;
  for (const StairFlightSpec& f : stair.flights)
    parts.push_back(writeFlight(w, f, storey_placement, id("stair-part", index * kPartsPerStair + part++)));
  for (const LandingSpec& l : stair.landings)
    parts.push_back(writeLanding(w, l, storey_placement, id("stair-part", index * kPartsPerStair + part++)));
  const int placement = localPlacement(w, storey_placement, w.origin_axes);
  const int stair_id = w.file.add("IFCSTAIR", root(id("stair", index), stair.name) +
                                                  std::vector<std::string>{step::unset(), ref(placement), step::unset(),
                                                                           step::unset(), ".HALF_TURN_STAIR."});
  w.file.add("IFCRELAGGREGATES", root(id("stair-parts", index), {}) + std::vector<std::string>{ref(stair_id), refs(parts)});
  return stair_id;
}

void writeSlabOpening(ItemWriter& w, int slab, int slab_placement, const std::vector<Vector2d>& outline, double z_bottom,
                      double thickness, const std::string& name, std::size_t index, const IdFor& id) {
  const int placement = localPlacement(w, slab_placement, w.origin_axes);
  const int solid = extrusion(w, polygonProfile(w, outline),
                              translation(w, Vector3d(0.0, 0.0, z_bottom - kSlabOpeningOverlap_m)),
                              thickness + 2 * kSlabOpeningOverlap_m);
  const int opening = w.file.add("IFCOPENINGELEMENT",
                                 root(id("slab-opening", index), name) +
                                     std::vector<std::string>{step::unset(), ref(placement), ref(bodyShape(w, solid)),
                                                              step::unset(), ".OPENING."});
  w.file.add("IFCRELVOIDSELEMENT", root(id("slab-voids", index), {}) + std::vector<std::string>{ref(slab), ref(opening)});
}

}  // namespace bimloc::worldgen::ifc
