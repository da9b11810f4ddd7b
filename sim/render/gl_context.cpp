#include "sim/render/gl_context.hpp"

#include <GL/osmesa.h>
#include <GL/gl.h>

#include <algorithm>
#include <cmath>
#include <mutex>
#include <stdexcept>
#include <string>

namespace bimloc::sim::render {

namespace {

constexpr int kSupersample = 3;  // samples per pixel along each axis
// Fewer samples for very large images: the RGBA buffer stays under about 100 MB.
constexpr double kMaxSamples = 24e6;

// OSMesa keeps one current context per thread and Mesa's state trackers are not meant to be
// entered concurrently: one snapshot at a time.
std::mutex& renderMutex() {
  static std::mutex mutex;
  return mutex;
}

// Owns the context and unbinds it on the way out, also when `draw` throws.
class ContextGuard {
 public:
  ContextGuard() : ctx_(OSMesaCreateContextExt(OSMESA_RGBA, 0, 0, 0, nullptr)) {
    // No depth buffer: layers are painted back to front in drawing order.
    if (!ctx_) throw std::runtime_error("OSMesa: cannot create an off-screen context");
  }
  ~ContextGuard() {
    OSMesaMakeCurrent(nullptr, nullptr, 0, 0, 0);
    OSMesaDestroyContext(ctx_);
  }
  ContextGuard(const ContextGuard&) = delete;
  ContextGuard& operator=(const ContextGuard&) = delete;
  OSMesaContext get() const { return ctx_; }

 private:
  OSMesaContext ctx_;
};

// Box filter of the supersampled RGBA buffer (rows bottom first when y_up) into RGB, top first.
Image downsample(const std::vector<std::uint8_t>& rgba, int width, int height, int s, bool y_up) {
  Image out;
  out.width = width;
  out.height = height;
  out.rgb.resize(static_cast<std::size_t>(width) * height * 3);
  const std::size_t big_w = static_cast<std::size_t>(width) * s;
  const int big_h = height * s;
  const int n = s * s;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      int sum[3] = {0, 0, 0};
      for (int dy = 0; dy < s; ++dy) {
        const int row = y * s + dy;
        const std::size_t src_row = static_cast<std::size_t>(y_up ? big_h - 1 - row : row);
        const std::uint8_t* p = &rgba[(src_row * big_w + static_cast<std::size_t>(x) * s) * 4];
        for (int dx = 0; dx < s; ++dx, p += 4)
          for (int c = 0; c < 3; ++c) sum[c] += p[c];
      }
      std::uint8_t* q = &out.rgb[(static_cast<std::size_t>(y) * width + x) * 3];
      for (int c = 0; c < 3; ++c) q[c] = static_cast<std::uint8_t>((sum[c] + n / 2) / n);
    }
  return out;
}

}  // namespace

Image renderOffscreen(int width, int height, const std::function<void()>& draw) {
  const std::lock_guard<std::mutex> lock(renderMutex());
  ContextGuard ctx;
  GLint max_side = 0;
  OSMesaGetIntegerv(OSMESA_MAX_WIDTH, &max_side);
  const int by_memory = static_cast<int>(std::sqrt(kMaxSamples / (static_cast<double>(width) * height)));
  const int s = std::clamp(std::min({max_side / std::max(width, height), by_memory, kSupersample}), 1, kSupersample);
  const int big_w = width * s, big_h = height * s;
  std::vector<std::uint8_t> buffer(static_cast<std::size_t>(big_w) * big_h * 4);
  if (!OSMesaMakeCurrent(ctx.get(), buffer.data(), GL_UNSIGNED_BYTE, big_w, big_h))
    throw std::runtime_error("OSMesa: cannot bind a " + std::to_string(big_w) + "x" + std::to_string(big_h) +
                             " buffer");
  glViewport(0, 0, big_w, big_h);
  glMatrixMode(GL_PROJECTION);
  glLoadIdentity();
  glOrtho(0, width, height, 0, -1, 1);
  glMatrixMode(GL_MODELVIEW);
  glLoadIdentity();
  glDisable(GL_DEPTH_TEST);
  glDisable(GL_CULL_FACE);  // polygons come in either winding
  glEnable(GL_BLEND);
  glBlendFunc(GL_SRC_ALPHA, GL_ONE_MINUS_SRC_ALPHA);
  glClearColor(1, 1, 1, 1);
  glClear(GL_COLOR_BUFFER_BIT);
  draw();
  glFinish();
  if (const GLenum err = glGetError(); err != GL_NO_ERROR)
    throw std::runtime_error("OpenGL error " + std::to_string(err) + " while drawing the snapshot");
  GLint y_up = 1;
  OSMesaGetIntegerv(OSMESA_Y_UP, &y_up);
  return downsample(buffer, width, height, s, y_up != 0);
}

}  // namespace bimloc::sim::render
