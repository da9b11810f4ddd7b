#include "render_fixtures.hpp"

#include "sim/world/world.hpp"

#include <gtest/gtest.h>
#include <png.h>

#include <cmath>
#include <cstring>
#include <map>

namespace bimloc::test {

const bim::Building& renderPlan(const std::string& name) {
  static std::map<std::string, sim::World> worlds;
  auto it = worlds.find(name);
  if (it == worlds.end())
    it = worlds.emplace(name, sim::World::fromPlan(std::string(BIMLOC_WORLDS_DIR) + "/" + name + ".ifc")).first;
  return it->second.building();
}

Rgb pixelAt(const sim::Image& image, const Eigen::Vector2d& px) {
  const int x = static_cast<int>(std::floor(px.x())), y = static_cast<int>(std::floor(px.y()));
  EXPECT_TRUE(x >= 0 && y >= 0 && x < image.width && y < image.height) << "pixel " << x << "," << y << " off the image";
  if (x < 0 || y < 0 || x >= image.width || y >= image.height) return {};
  const std::uint8_t* p = &image.rgb[(static_cast<std::size_t>(y) * image.width + x) * 3];
  return {p[0], p[1], p[2]};
}

void expectColour(const Rgb& got, const std::array<std::uint8_t, 3>& want, const std::string& what, int tolerance) {
  EXPECT_NEAR(got.r, want[0], tolerance) << what;
  EXPECT_NEAR(got.g, want[1], tolerance) << what;
  EXPECT_NEAR(got.b, want[2], tolerance) << what;
}

std::array<std::uint8_t, 3> rgbBytes(std::uint32_t c) {
  return {static_cast<std::uint8_t>(c >> 16), static_cast<std::uint8_t>(c >> 8), static_cast<std::uint8_t>(c)};
}

sim::Image readPng(const std::string& path) {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&png, path.c_str())) {
    ADD_FAILURE() << path << ": " << png.message;
    return {};
  }
  png.format = PNG_FORMAT_RGB;
  sim::Image image;
  image.width = static_cast<int>(png.width);
  image.height = static_cast<int>(png.height);
  image.rgb.resize(PNG_IMAGE_SIZE(png));
  if (!png_image_finish_read(&png, nullptr, image.rgb.data(), 0, nullptr)) ADD_FAILURE() << path << ": " << png.message;
  return image;
}

}  // namespace bimloc::test
