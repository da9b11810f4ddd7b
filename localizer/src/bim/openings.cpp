#include "openings.hpp"

#include "extraction.hpp"

#include <bimloc/bim/geometry2d.hpp>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <optional>

namespace bimloc::bim::detail {
namespace {

// A corner this close to a corner of the bounding box counts as on it: box-shaped.
constexpr double kBoxTolerance_m = 1e-3;
// Planes of the body and of the openings closer than this are one plane (no sliver cells).
constexpr double kSamePlane_m = 1e-4;

// The body's own frame: a along its length, b across (left of a), z up; the box is
// [0, length] x [0, width] x [z0, z1].
struct BoxFrame {
  Eigen::Vector2d origin = Eigen::Vector2d::Zero();
  Eigen::Vector2d a = Eigen::Vector2d::UnitX(), b = Eigen::Vector2d::UnitY();
  std::array<double, 3> lo{}, hi{};

  Eigen::Vector3d local(const Eigen::Vector3d& p) const {
    const Eigen::Vector2d q = p.head<2>() - origin;
    return {q.dot(a), q.dot(b), p.z()};
  }
  Eigen::Vector3f world(double x, double y, double z) const {
    const Eigen::Vector2d q = origin + x * a + y * b;
    return Eigen::Vector3d(q.x(), q.y(), z).cast<float>();
  }
};

std::optional<BoxFrame> boxFrame(const Extrusion& body, std::string& why) {
  if (!body.vertical || body.corners.size() != 2 * body.footprint.size()) {
    why = "the element's body is not a vertical extrusion";
    return std::nullopt;
  }
  const Rectangle2 r = minAreaRectangle(convexHull(body.footprint));
  BoxFrame f;
  f.a = r.axis;
  f.b = Eigen::Vector2d(-r.axis.y(), r.axis.x());
  f.origin = r.centre - 0.5 * r.length * f.a - 0.5 * r.width * f.b;
  f.lo = {0.0, 0.0, body.z_min};
  f.hi = {r.length, r.width, body.z_max};
  // A box: every corner of the footprint on a corner of its rectangle, and no corner missing.
  std::array<bool, 4> seen{};
  for (const auto& p : body.footprint) {
    const Eigen::Vector3d q = f.local({p.x(), p.y(), 0.0});
    const bool x0 = std::abs(q.x()) < kBoxTolerance_m, x1 = std::abs(q.x() - r.length) < kBoxTolerance_m;
    const bool y0 = std::abs(q.y()) < kBoxTolerance_m, y1 = std::abs(q.y() - r.width) < kBoxTolerance_m;
    if (!(x0 || x1) || !(y0 || y1)) {
      why = "the element's body is not a box";
      return std::nullopt;
    }
    seen[(x1 ? 1 : 0) + (y1 ? 2 : 0)] = true;
  }
  if (!std::all_of(seen.begin(), seen.end(), [](bool s) { return s; }) || r.length < kBoxTolerance_m ||
      r.width < kBoxTolerance_m || body.z_max - body.z_min < kBoxTolerance_m) {
    why = "the element's body is not a box";
    return std::nullopt;
  }
  return f;
}

// The opening as a box [lo, hi] in the body's frame, clipped to the body; nothing (and why)
// when it is not a box along the body's axes or does not meet the body.
std::optional<std::array<std::array<double, 3>, 2>> openingBox(const BoxFrame& f, const Extrusion& opening,
                                                               std::string& why) {
  std::vector<Eigen::Vector3d> q;
  for (const auto& c : opening.corners) q.push_back(f.local(c));
  if (q.size() != 8) {
    why = "its body is not a box (a profile of " + std::to_string(q.size() / 2) + " points)";
    return std::nullopt;
  }
  std::array<double, 3> lo{}, hi{};
  for (int k = 0; k < 3; ++k) {
    lo[k] = hi[k] = q[0][k];
    for (const auto& p : q) lo[k] = std::min(lo[k], p[k]), hi[k] = std::max(hi[k], p[k]);
  }
  std::array<bool, 8> seen{};
  for (const auto& p : q) {
    int code = 0;
    for (int k = 0; k < 3; ++k) {
      const bool at_lo = std::abs(p[k] - lo[k]) < kBoxTolerance_m, at_hi = std::abs(p[k] - hi[k]) < kBoxTolerance_m;
      if (!at_lo && !at_hi) {
        why = "its body is not a box along the element's length, thickness and height";
        return std::nullopt;
      }
      code |= (at_hi && !at_lo ? 1 : 0) << k;
    }
    seen[static_cast<std::size_t>(code)] = true;
  }
  if (!std::all_of(seen.begin(), seen.end(), [](bool s) { return s; })) {
    why = "its body is not a box along the element's length, thickness and height";
    return std::nullopt;
  }
  for (int k = 0; k < 3; ++k) {
    lo[k] = std::max(lo[k], f.lo[k]), hi[k] = std::min(hi[k], f.hi[k]);
    if (hi[k] - lo[k] < kBoxTolerance_m) {
      why = "it does not meet the element's body";
      return std::nullopt;
    }
  }
  return std::array<std::array<double, 3>, 2>{lo, hi};
}

// Sorted coordinates, those within kSamePlane_m of a smaller one dropped.
std::vector<double> gridLines(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  std::vector<double> lines;
  for (double v : values)
    if (lines.empty() || v - lines.back() > kSamePlane_m) lines.push_back(v);
  return lines;
}

int lineIndex(const std::vector<double>& lines, double v) {
  const auto it = std::lower_bound(lines.begin(), lines.end(), v - kSamePlane_m);
  return static_cast<int>(it - lines.begin());
}

std::string describe(const std::string& ifc_class, const std::string& id, const std::string& name) {
  return ifc_class + " " + id + (name.empty() ? "" : " '" + name + "'");
}

}  // namespace

OpeningCut cutOpenings(const Extrusion& body, const std::vector<Extrusion>& openings) {
  OpeningCut out;
  std::string why;
  const auto frame = boxFrame(body, why);
  std::vector<std::array<std::array<double, 3>, 2>> boxes;
  for (std::size_t i = 0; i < openings.size(); ++i) {
    std::string problem = why;
    std::optional<std::array<std::array<double, 3>, 2>> box;
    if (frame) box = openingBox(*frame, openings[i], problem);
    if (box) boxes.push_back(*box);
    else out.not_cut.emplace_back(i, problem);
  }
  out.cut = boxes.size();
  if (boxes.empty()) {
    out.mesh = prismMesh(body);
    return out;
  }

  // The grid of every plane of the body and of the openings; a cell is solid unless inside
  // an opening. Boxes are unions of whole cells, so the test is exact, by index.
  std::array<std::vector<double>, 3> lines;
  for (int k = 0; k < 3; ++k) {
    std::vector<double> values{frame->lo[k], frame->hi[k]};
    for (const auto& box : boxes) values.push_back(box[0][k]), values.push_back(box[1][k]);
    lines[k] = gridLines(values);
  }
  const int n[3] = {static_cast<int>(lines[0].size()) - 1, static_cast<int>(lines[1].size()) - 1,
                    static_cast<int>(lines[2].size()) - 1};
  const auto cell = [&](int i, int j, int k) { return (static_cast<std::size_t>(k) * n[1] + j) * n[0] + i; };
  std::vector<char> solid(static_cast<std::size_t>(n[0]) * n[1] * n[2], 1);
  for (const auto& box : boxes) {
    int from[3], to[3];
    for (int k = 0; k < 3; ++k) from[k] = lineIndex(lines[k], box[0][k]), to[k] = lineIndex(lines[k], box[1][k]);
    for (int k = from[2]; k < to[2]; ++k)
      for (int j = from[1]; j < to[1]; ++j)
        for (int i = from[0]; i < to[0]; ++i) solid[cell(i, j, k)] = 0;
  }
  const auto solidAt = [&](int i, int j, int k) {
    return i >= 0 && j >= 0 && k >= 0 && i < n[0] && j < n[1] && k < n[2] && solid[cell(i, j, k)];
  };

  // One vertex per grid point used: neighbouring faces share their corners (no cracks).
  std::vector<std::int64_t> vertex_of(static_cast<std::size_t>(n[0] + 1) * (n[1] + 1) * (n[2] + 1), -1);
  const auto vertex = [&](const std::array<int, 3>& g) {
    auto& v = vertex_of[(static_cast<std::size_t>(g[2]) * (n[1] + 1) + g[1]) * (n[0] + 1) + g[0]];
    if (v < 0) {
      v = static_cast<std::int64_t>(out.mesh.vertices.size());
      out.mesh.vertices.push_back(frame->world(lines[0][g[0]], lines[1][g[1]], lines[2][g[2]]));
    }
    return static_cast<std::uint32_t>(v);
  };
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        if (!solid[cell(i, j, k)]) continue;
        const std::array<int, 3> c{i, j, k};
        for (int axis = 0; axis < 3; ++axis)
          for (int side = 0; side < 2; ++side) {
            std::array<int, 3> next = c;
            next[axis] += side ? 1 : -1;
            if (solidAt(next[0], next[1], next[2])) continue;
            // The face's corners counter-clockwise about the outward normal (the frame is
            // right-handed: e_p x e_q = e_axis for the cyclic successors p, q of axis).
            const int p = (axis + 1) % 3, q = (axis + 2) % 3;
            std::array<std::array<int, 3>, 4> g;
            g.fill(c);
            for (auto& corner : g) corner[axis] += side;
            g[1][p] += 1, g[2][p] += 1, g[2][q] += 1, g[3][q] += 1;
            if (!side) std::swap(g[1], g[3]);
            const std::uint32_t v0 = vertex(g[0]), v1 = vertex(g[1]), v2 = vertex(g[2]), v3 = vertex(g[3]);
            out.mesh.triangles.push_back({v0, v1, v2});
            out.mesh.triangles.push_back({v0, v2, v3});
          }
      }
  return out;
}

std::unordered_map<int, TriangleMesh> rebuiltBodies(const RawModel& raw, std::vector<std::string>& warnings) {
  std::map<int, std::vector<const RawOpening*>> openings_of;  // by voided entity id
  for (const auto& o : raw.openings) openings_of[o.voided_entity_id].push_back(&o);
  std::unordered_map<int, TriangleMesh> bodies;
  for (const auto* group : {&raw.walls, &raw.elements})
    for (const auto& p : *group) {
      if (!p.mesh.empty()) {
        // IFC++ cut its openings with Carve, whose CSG orders by heap address: on some plans
        // (Office_A_20110811.ifc) it cuts a different subset of a wall's windows from run to
        // run. A body that is one box with box openings is cut here instead, exactly (and
        // IFC++ was not asked to: own_opening_cuts.hpp); any other keeps IFC++'s mesh.
        const auto& own = openings_of[p.entity_id];
        const bool left_to_us = std::binary_search(raw.openings_left_to_us.begin(), raw.openings_left_to_us.end(), p.entity_id);
        bool cut_here = false;
        if (p.sole_body && !own.empty() &&
            std::all_of(own.begin(), own.end(), [](const RawOpening* o) { return o->extrusion && o->sole; })) {
          std::vector<Extrusion> solids;
          for (const RawOpening* o : own) solids.push_back(*o->extrusion);
          OpeningCut cut = cutOpenings(*p.sole_body, solids);
          cut_here = cut.not_cut.empty() && cut.cut == solids.size();
          if (cut_here) bodies.emplace(p.entity_id, std::move(cut.mesh));
        }
        // The reader checked that every one of these cuts before it kept IFC++ from cutting
        // them; should one not, the storey mesh would have the element whole, unsaid.
        if (left_to_us && !cut_here)
          warnings.push_back(describeProduct(p) + ": its openings are not cut from the storey mesh (they could not be " +
                             "cut as read): the element stands whole there");
        continue;
      }
      if (!p.extrusion) continue;
      std::vector<Extrusion> solids;
      std::vector<const RawOpening*> readable;
      const std::string owner = describe(p.ifc_class, p.global_id, p.name);
      for (const RawOpening* o : openings_of[p.entity_id]) {
        if (o->extrusion) {
          solids.push_back(*o->extrusion);
          readable.push_back(o);
        } else {
          warnings.push_back(describe(o->ifc_class, o->global_id, o->name) + " in " + owner +
                             ": not cut from the storey mesh: " + o->geometry_problem);
        }
      }
      OpeningCut cut = cutOpenings(*p.extrusion, solids);
      for (const auto& [index, why] : cut.not_cut) {
        const RawOpening* o = readable[index];
        warnings.push_back(describe(o->ifc_class, o->global_id, o->name) + " in " + owner +
                           ": not cut from the storey mesh: " + why);
      }
      bodies.emplace(p.entity_id, std::move(cut.mesh));
    }
  return bodies;
}

}  // namespace bimloc::bim::detail
