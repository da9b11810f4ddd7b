// PNG encoding of a snapshot (libpng).
#pragma once

#include "sim/render/snapshot.hpp"

#include <string>

namespace bimloc::sim::render {

// The PNG file's bytes (8-bit RGB); throws std::runtime_error if libpng fails.
std::string encodePng(const Image& image);

}  // namespace bimloc::sim::render
