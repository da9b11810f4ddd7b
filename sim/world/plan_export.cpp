#include "sim/world/plan_export.hpp"

#include "sim/common/atomic_file.hpp"
#include "sim/world/mesh_io.hpp"

#include <bimloc/bim/building_json.hpp>

#include <cctype>
#include <cstdio>
#include <sstream>

namespace bimloc::sim {

std::string storeyMeshName(const bim::Building& building, std::size_t index) {
  std::string safe;
  for (const char c : building.storeys.at(index).name)
    safe += std::isalnum(static_cast<unsigned char>(c)) || c == '-' ? c : '_';
  char prefix[32];
  std::snprintf(prefix, sizeof prefix, "storey_%02zu", index);
  return std::string(prefix) + (safe.empty() ? "" : "_" + safe) + kMeshExtension;
}

std::string wallsCsv(const bim::Building& building) {
  std::ostringstream csv;
  csv.precision(9);
  csv << "storey,wall_id,face,axis,start_x,start_y,start_z,nx,ny,nz,length_m,thickness_m,d\n";
  for (std::size_t s = 0; s < building.storeys.size(); ++s)
    for (const auto& wall : building.storeys[s].walls)
      for (int f = 0; f < 2; ++f) {
        const auto& face = wall.faces[f];
        csv << s << ',' << wall.id << ',' << f << ',' << bim::toString(face.axis) << ',' << face.start.x() << ','
            << face.start.y() << ',' << face.start.z() << ',' << face.plane.n.x() << ',' << face.plane.n.y() << ','
            << face.plane.n.z() << ',' << face.length_m() << ',' << wall.thickness_m << ',' << face.plane.d << '\n';
      }
  return csv.str();
}

std::vector<std::string> exportPlan(const bim::Building& building, const std::string& dir) {
  StagingDirectory staging(dir, {"building.json", "bimloc.building"});
  std::vector<std::string> names{"building.json", "walls.csv"};
  nlohmann::json doc = bim::toJson(building);
  for (std::size_t s = 0; s < building.storeys.size(); ++s) {
    const auto& mesh = building.storeys[s].mesh;
    if (mesh.empty()) {
      doc["storeys"][s]["mesh"] = nullptr;
      continue;
    }
    const std::string name = storeyMeshName(building, s);
    writeMesh(mesh, staging.file(name));
    doc["storeys"][s]["mesh"] = name;
    names.push_back(name);
  }
  writeFileAtomically(staging.file("building.json"), doc.dump(1) + "\n");
  writeFileAtomically(staging.file("walls.csv"), wallsCsv(building));
  staging.commit();
  return names;
}

}  // namespace bimloc::sim
