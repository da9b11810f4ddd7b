// PNG encoding of a snapshot (libpng).
#pragma once

#include "sim/render/snapshot.hpp"

#include <functional>
#include <string>

namespace bimloc::sim::render {

// The PNG file's bytes (8-bit RGB); throws std::runtime_error if libpng fails.
std::string encodePng(const Image& image);

// The image `render` draws, as a PNG at `png_path`, written atomically (temporary name, then
// rename). Throws std::runtime_error naming the path when drawing, encoding or writing fails;
// no file is left behind then.
void writePng(const std::string& png_path, const std::function<Image()>& render);

}  // namespace bimloc::sim::render
