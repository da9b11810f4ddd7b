#include "sim/world/site_mesh.hpp"

namespace bimloc::sim {

bool isDoorPart(const bim::MeshPart& part) {
  return part.ifc_class == "IfcDoor" || part.ifc_class == "IfcDoorStandardCase";
}

std::string glassClass(const bim::MeshPart& part) {
  for (const char* type : {"IfcWindow", "IfcCurtainWall", "IfcPlate"})
    if (part.ifc_class.rfind(type, 0) == 0) return type;
  return "";
}

namespace {

void appendPart(bim::TriangleMesh& to, const bim::TriangleMesh& from, const bim::MeshPart& part, const PartEdit& edit) {
  const auto base = static_cast<std::uint32_t>(to.vertices.size());
  for (std::uint32_t v = part.first_vertex; v < part.first_vertex + part.vertex_count; ++v)
    to.vertices.push_back(edit.moved ? (edit.transform * from.vertices[v].cast<double>()).cast<float>() : from.vertices[v]);
  for (std::uint32_t t = part.first_triangle; t < part.first_triangle + part.triangle_count; ++t) {
    std::array<std::uint32_t, 3> tri = from.triangles[t];
    for (auto& i : tri) i = i - part.first_vertex + base;
    to.triangles.push_back(tri);
  }
}

}  // namespace

ComposedStorey composeStorey(const PlanStorey& plan, const std::vector<PartEdit>& edits) {
  ComposedStorey out;
  for (std::size_t i = 0; i < plan.parts.size(); ++i) {
    const bim::MeshPart& part = plan.parts[i];
    const PartEdit& edit = edits[i];
    if (edit.drop) continue;
    if (edit.pass_fraction > 0.0f) {
      const auto element = static_cast<std::uint32_t>(out.glass.pass_fraction.size());
      out.glass.pass_fraction.push_back(edit.pass_fraction);
      appendPart(out.glass.mesh, plan.mesh, part, edit);
      out.glass.element_of_triangle.resize(out.glass.mesh.triangles.size(), element);
      continue;
    }
    bim::MeshPart placed = part;
    placed.first_vertex = static_cast<std::uint32_t>(out.mesh.vertices.size());
    placed.first_triangle = static_cast<std::uint32_t>(out.mesh.triangles.size());
    appendPart(out.mesh, plan.mesh, part, edit);
    out.parts.push_back(std::move(placed));
  }
  return out;
}

void appendBox(ComposedStorey& storey, const std::string& id, const std::string& ifc_class, const Eigen::Vector2d& a,
               const Eigen::Vector2d& b, double thickness_m, double z0, double z1) {
  bim::TriangleMesh& mesh = storey.mesh;
  const Eigen::Vector2d u = (b - a).normalized();
  const Eigen::Vector2d n(-u.y(), u.x());
  const Eigen::Vector2d h = 0.5 * thickness_m * n;
  const Eigen::Vector2d corners[4] = {a - h, b - h, b + h, a + h};  // counter-clockwise seen from above
  bim::MeshPart part{id, id, ifc_class, static_cast<std::uint32_t>(mesh.vertices.size()), 8,
                     static_cast<std::uint32_t>(mesh.triangles.size()), 12};
  const std::uint32_t base = part.first_vertex;
  for (const auto& c : corners) {
    mesh.vertices.emplace_back(float(c.x()), float(c.y()), float(z0));
    mesh.vertices.emplace_back(float(c.x()), float(c.y()), float(z1));
  }
  for (std::uint32_t i = 0; i < 4; ++i) {  // sides: bottom 2i, top 2i+1
    const std::uint32_t j = (i + 1) % 4;
    mesh.triangles.push_back({base + 2 * i, base + 2 * j, base + 2 * j + 1});
    mesh.triangles.push_back({base + 2 * i, base + 2 * j + 1, base + 2 * i + 1});
  }
  mesh.triangles.push_back({base + 0, base + 4, base + 2});  // bottom
  mesh.triangles.push_back({base + 0, base + 6, base + 4});
  mesh.triangles.push_back({base + 1, base + 3, base + 5});  // top
  mesh.triangles.push_back({base + 1, base + 5, base + 7});
  storey.parts.push_back(std::move(part));
}

}  // namespace bimloc::sim
