#include "sim/world/mesh_io.hpp"

#include "sim/common/atomic_file.hpp"
#include "sim/world/ply_check.hpp"

#include <assimp/Exporter.hpp>
#include <assimp/Importer.hpp>
#include <assimp/postprocess.h>
#include <assimp/scene.h>

#include <Eigen/Geometry>
#include <filesystem>
#include <memory>
#include <stdexcept>

namespace bimloc::sim {
namespace fs = std::filesystem;

void writeMesh(const bim::TriangleMesh& mesh, const std::string& path) {
  if (mesh.empty()) throw std::runtime_error(path + ": refusing to write an empty mesh");
  // A one-mesh scene; aiScene's destructor frees what we allocate with new[] here.
  aiScene scene;
  scene.mRootNode = new aiNode();
  scene.mRootNode->mNumMeshes = 1;
  scene.mRootNode->mMeshes = new unsigned int[1]{0};
  scene.mNumMaterials = 1;
  scene.mMaterials = new aiMaterial*[1]{new aiMaterial()};
  scene.mNumMeshes = 1;
  scene.mMeshes = new aiMesh*[1]{new aiMesh()};
  aiMesh& m = *scene.mMeshes[0];
  m.mPrimitiveTypes = aiPrimitiveType_TRIANGLE;
  m.mMaterialIndex = 0;
  m.mNumVertices = static_cast<unsigned>(mesh.vertices.size());
  m.mVertices = new aiVector3D[m.mNumVertices];
  for (unsigned i = 0; i < m.mNumVertices; ++i) {
    const auto& v = mesh.vertices[i];
    m.mVertices[i] = aiVector3D(v.x(), v.y(), v.z());
  }
  m.mNumFaces = static_cast<unsigned>(mesh.triangles.size());
  m.mFaces = new aiFace[m.mNumFaces];
  for (unsigned i = 0; i < m.mNumFaces; ++i) {
    m.mFaces[i].mNumIndices = 3;
    m.mFaces[i].mIndices = new unsigned int[3]{mesh.triangles[i][0], mesh.triangles[i][1], mesh.triangles[i][2]};
  }
  Assimp::Exporter exporter;
  const aiExportDataBlob* blob = exporter.ExportToBlob(&scene, "plyb");
  if (!blob) throw std::runtime_error(path + ": mesh export failed: " + exporter.GetErrorString());
  writeFileAtomically(path, std::string(static_cast<const char*>(blob->data), blob->size));
}

bim::TriangleMesh loadMesh(const std::string& path) {
  if (fs::path(path).extension() == kMeshExtension && fs::exists(path)) checkPly(path);
  Assimp::Importer importer;
  // ValidateDataStructure runs first: a truncated or damaged PLY gives faces whose indices point
  // past the vertices, on which the other steps crash (a segfault in assimp) instead of failing.
  const aiScene* scene = importer.ReadFile(path, aiProcess_ValidateDataStructure | aiProcess_Triangulate |
                                                     aiProcess_PreTransformVertices | aiProcess_SortByPType);
  if (!scene || !scene->mRootNode)
    throw std::runtime_error(path + ": not a readable mesh, damaged or truncated (" + importer.GetErrorString() + ")");
  bim::TriangleMesh out;
  std::size_t degenerate = 0;
  for (unsigned k = 0; k < scene->mNumMeshes; ++k) {
    const aiMesh& m = *scene->mMeshes[k];
    const auto base = static_cast<std::uint32_t>(out.vertices.size());
    for (unsigned i = 0; i < m.mNumVertices; ++i) {
      const aiVector3D& v = m.mVertices[i];
      const Eigen::Vector3f p(v.x, v.y, v.z);
      if (!p.allFinite())
        throw std::runtime_error(path + ": mesh " + std::to_string(k) + " vertex " + std::to_string(i) + " is not finite");
      out.vertices.push_back(p);
    }
    for (unsigned f = 0; f < m.mNumFaces; ++f) {
      if (m.mFaces[f].mNumIndices != 3) continue;  // points and lines are not surfaces
      const std::array<std::uint32_t, 3> t{base + m.mFaces[f].mIndices[0], base + m.mFaces[f].mIndices[1],
                                           base + m.mFaces[f].mIndices[2]};
      const Eigen::Vector3f& a = out.vertices[t[0]];
      if ((out.vertices[t[1]] - a).cross(out.vertices[t[2]] - a).norm() < 1e-12f) {
        ++degenerate;
        continue;
      }
      out.triangles.push_back(t);
    }
  }
  if (out.triangles.empty())
    throw std::runtime_error(path + (degenerate ? ": every triangle of the mesh is degenerate" : ": the mesh has no triangles"));
  return out;
}

}  // namespace bimloc::sim
