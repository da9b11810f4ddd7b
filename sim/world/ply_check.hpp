// assimp's PLY reader trusts the header: a header line missing (end_header) or a body cut
// short makes it read past its buffers (a segfault, not an error). So before assimp sees a
// PLY, its header is parsed here and its whole body walked, binary or ASCII: every element
// present, every face a polygon (3 corners or more: assimp's triangulation aborts the process on
// fewer) of existing vertices, nothing after the end.
#pragma once

#include <string>

namespace bimloc::sim {

// Throws std::runtime_error "PATH: problem" unless the PLY file is complete and consistent.
void checkPly(const std::string& path);

}  // namespace bimloc::sim
