// Storey meshes on disk, through assimp: what `bimloc extract` writes and the simulator loads.
#pragma once

#include <bimloc/bim/building.hpp>

#include <string>

namespace bimloc::sim {

// Binary little-endian PLY: compact, exact float32 vertices, read by assimp, PCL and MeshLab.
constexpr const char* kMeshExtension = ".ply";

// Writes the mesh atomically; throws std::runtime_error naming the path.
void writeMesh(const bim::TriangleMesh& mesh, const std::string& path);

// Loads every mesh of a PLY, OBJ, glTF, STL or DAE file into one triangle mesh (node
// transforms applied). Throws std::runtime_error for an unreadable file, an empty mesh,
// non-finite vertices or only degenerate triangles.
bim::TriangleMesh loadMesh(const std::string& path);

}  // namespace bimloc::sim
