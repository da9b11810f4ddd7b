// assimp's PLY reader trusts the header: a header line missing (end_header) or a body cut
// short makes it read past its buffers (a segfault, not an error). So before assimp sees a
// binary PLY, its header is parsed here and its whole body walked: every element present,
// every face index within the vertices, nothing after the end.
#pragma once

#include <string>

namespace bimloc::sim {

// Throws std::runtime_error "PATH: problem" unless the PLY file is complete and consistent.
// ASCII PLY files get the header checks only.
void checkPly(const std::string& path);

}  // namespace bimloc::sim
