// Drawing primitives on the off-screen canvas, in pixels (origin top-left, y down). Thick
// lines are quads, not GL lines, so they keep their width through the supersampling.
#pragma once

#include "sim/render/layout.hpp"

#include <Eigen/Core>
#include <array>
#include <cstdint>
#include <string>
#include <vector>

namespace bimloc::sim::render {

struct Colour {
  float r = 0, g = 0, b = 0, a = 1;
};
Colour hex(std::uint32_t rrggbb, float alpha = 1.0f);
Colour fromBytes(const std::array<std::uint8_t, 3>& rgb, float alpha = 1.0f);

using Points = std::vector<Eigen::Vector2d>;

void fillPolygon(const Points& polygon, const Colour& colour);  // any simple polygon
void fillConvex(const Points& polygon, const Colour& colour);
void fillRect(const Rect& rect, const Colour& colour);
void strokeRect(const Rect& rect, double width, const Colour& colour);  // inside the rect
void fillDisc(const Eigen::Vector2d& centre, double radius, const Colour& colour);
void segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, const Colour& colour);
// Round-joined, so outlines of arrows have no notches at their corners.
void strokePolyline(const Points& points, double width, const Colour& colour, bool closed);

// Many small shapes (particles) as one vertex array: one draw call instead of a few GL calls
// per shape, which is what makes a hundred thousand particles affordable.
class ShapeBatch {
 public:
  void disc(const Eigen::Vector2d& centre, double radius, const Colour& colour, int segments);
  void segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, const Colour& colour);
  void draw() const;  // in the order added

 private:
  void triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c, const Colour& colour);
  std::vector<float> xy_;
  std::vector<float> rgba_;
};

// Text with its top-left corner at (x, y), snapped to whole pixels so glyphs stay crisp.
void drawText(double x, double y, const std::string& text, int scale, const Colour& colour);

// An arrow from `tail` along the pixel direction `dir` (unit), filled, with an outline.
void drawArrow(const Eigen::Vector2d& tail, const Eigen::Vector2d& dir, double length, double width,
               const Colour& fill, const Colour& outline, double outline_width);

}  // namespace bimloc::sim::render
