// Shared helpers of the picture tests: the plans they draw, reading a pixel, reading a PNG
// back with libpng (an independent decoder of what the renderer encoded).
#pragma once

#include "sim/render/snapshot.hpp"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>

namespace bimloc::test {

// A project world's building, extracted once for all the tests.
const bim::Building& renderPlan(const std::string& name);
inline const bim::Storey& officeStorey() { return renderPlan("site_office").storeys.at(0); }

struct Rgb {
  int r = 0, g = 0, b = 0;
};

// The pixel holding the continuous pixel coordinates `px` (a failure when off the image).
Rgb pixelAt(const sim::Image& image, const Eigen::Vector2d& px);

// Within `tolerance` of each channel (the supersampling's box filter blends edges only).
void expectColour(const Rgb& got, const std::array<std::uint8_t, 3>& want, const std::string& what, int tolerance = 10);
std::array<std::uint8_t, 3> rgbBytes(std::uint32_t rrggbb);

sim::Image readPng(const std::string& path);

}  // namespace bimloc::test
