#include "sim/render/png_write.hpp"

#include "sim/common/atomic_file.hpp"

#include <png.h>

#include <cstring>
#include <stdexcept>

namespace bimloc::sim::render {

std::string encodePng(const Image& image) {
  if (image.width <= 0 || image.height <= 0 ||
      image.rgb.size() != static_cast<std::size_t>(image.width) * image.height * 3)
    throw std::runtime_error("PNG encoding: the image buffer does not match its size");
  // libpng's simplified API: no setjmp/longjmp to cross our C++ frames; errors come back in
  // the struct. The first call measures, the second writes.
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(image.width);
  png.height = static_cast<png_uint_32>(image.height);
  png.format = PNG_FORMAT_RGB;
  const png_int_32 stride = image.width * 3;
  png_alloc_size_t size = 0;
  if (!png_image_write_to_memory(&png, nullptr, &size, 0, image.rgb.data(), stride, nullptr))
    throw std::runtime_error(std::string("PNG encoding failed: ") + png.message);
  std::string bytes(size, '\0');
  if (!png_image_write_to_memory(&png, bytes.data(), &size, 0, image.rgb.data(), stride, nullptr))
    throw std::runtime_error(std::string("PNG encoding failed: ") + png.message);
  bytes.resize(size);
  png_image_free(&png);
  return bytes;
}

void writePng(const std::string& png_path, const std::function<Image()>& render) {
  std::string png;
  try {
    png = encodePng(render());
  } catch (const std::exception& e) {
    throw std::runtime_error(png_path + ": " + e.what());
  }
  writeFileAtomically(png_path, png);  // names the path itself, and leaves no file on failure
}

}  // namespace bimloc::sim::render
