// An off-screen OpenGL 1.x canvas (OSMesa, software rendering: no display, no GPU).
#pragma once

#include "sim/render/snapshot.hpp"

#include <functional>

namespace bimloc::sim::render {

// Runs `draw` with a fresh OSMesa context current on a white canvas of width x height pixels
// (projection: pixels, origin top-left, y down; blending on) and returns what it drew.
// Rendered at several samples a pixel and box-filtered down, because OSMesa gives no
// multisampling and thin walls and particle dots would otherwise be jagged.
// Calls are serialised by a mutex: any thread, one at a time. Throws std::runtime_error
// when OSMesa cannot give a context.
Image renderOffscreen(int width, int height, const std::function<void()>& draw);

}  // namespace bimloc::sim::render
