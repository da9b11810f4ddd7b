#include "sim/render/draw.hpp"

#include "sim/render/font.hpp"
#include "sim/render/triangulate.hpp"

#include <GL/gl.h>

#include <algorithm>
#include <cmath>

namespace bimloc::sim::render {

namespace {

void setColour(const Colour& c) { glColor4f(c.r, c.g, c.b, c.a); }
void vertex(const Eigen::Vector2d& p) { glVertex2d(p.x(), p.y()); }

// Enough segments for a smooth circle at its size in supersampled pixels.
int circleSegments(double radius) { return std::clamp(static_cast<int>(radius * 2.5), 12, 64); }

}  // namespace

Colour hex(std::uint32_t rrggbb, float alpha) {
  return {((rrggbb >> 16) & 0xFF) / 255.0f, ((rrggbb >> 8) & 0xFF) / 255.0f, (rrggbb & 0xFF) / 255.0f, alpha};
}

Colour fromBytes(const std::array<std::uint8_t, 3>& rgb, float alpha) {
  return {rgb[0] / 255.0f, rgb[1] / 255.0f, rgb[2] / 255.0f, alpha};
}

void fillPolygon(const Points& polygon, const Colour& colour) {
  setColour(colour);
  glBegin(GL_TRIANGLES);
  for (const auto& t : triangulate(polygon))
    for (const int i : t) vertex(polygon[i]);
  glEnd();
}

void fillConvex(const Points& polygon, const Colour& colour) {
  setColour(colour);
  glBegin(GL_TRIANGLE_FAN);
  for (const auto& p : polygon) vertex(p);
  glEnd();
}

void fillRect(const Rect& r, const Colour& colour) {
  fillConvex({{r.x0, r.y0}, {r.x1, r.y0}, {r.x1, r.y1}, {r.x0, r.y1}}, colour);
}

void strokeRect(const Rect& r, double w, const Colour& colour) {
  fillRect({r.x0, r.y0, r.x1, r.y0 + w}, colour);
  fillRect({r.x0, r.y1 - w, r.x1, r.y1}, colour);
  fillRect({r.x0, r.y0 + w, r.x0 + w, r.y1 - w}, colour);
  fillRect({r.x1 - w, r.y0 + w, r.x1, r.y1 - w}, colour);
}

void fillDisc(const Eigen::Vector2d& centre, double radius, const Colour& colour) {
  const int n = circleSegments(radius * 3);
  setColour(colour);
  glBegin(GL_TRIANGLE_FAN);
  vertex(centre);
  for (int i = 0; i <= n; ++i) {
    const double a = 2 * M_PI * i / n;
    glVertex2d(centre.x() + radius * std::cos(a), centre.y() + radius * std::sin(a));
  }
  glEnd();
}

void segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, const Colour& colour) {
  const Eigen::Vector2d d = b - a;
  if (d.norm() < 1e-9) return;
  const Eigen::Vector2d n = Eigen::Vector2d(-d.y(), d.x()).normalized() * (0.5 * width);
  fillConvex({a + n, b + n, b - n, a - n}, colour);
}

void strokePolyline(const Points& points, double width, const Colour& colour, bool closed) {
  const std::size_t n = points.size();
  for (std::size_t i = 0; i + 1 < n + (closed ? 1 : 0); ++i) segment(points[i], points[(i + 1) % n], width, colour);
  if (width > 1.5)
    for (const auto& p : points) fillDisc(p, 0.5 * width, colour);
}

void ShapeBatch::triangle(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const Eigen::Vector2d& c,
                          const Colour& colour) {
  for (const Eigen::Vector2d* p : {&a, &b, &c}) {
    xy_.insert(xy_.end(), {static_cast<float>(p->x()), static_cast<float>(p->y())});
    rgba_.insert(rgba_.end(), {colour.r, colour.g, colour.b, colour.a});
  }
}

void ShapeBatch::disc(const Eigen::Vector2d& centre, double radius, const Colour& colour, int segments) {
  Eigen::Vector2d prev = centre + Eigen::Vector2d(radius, 0);
  for (int i = 1; i <= segments; ++i) {
    const double a = 2 * M_PI * i / segments;
    const Eigen::Vector2d next = centre + radius * Eigen::Vector2d(std::cos(a), std::sin(a));
    triangle(centre, prev, next, colour);
    prev = next;
  }
}

void ShapeBatch::segment(const Eigen::Vector2d& a, const Eigen::Vector2d& b, double width, const Colour& colour) {
  const Eigen::Vector2d d = b - a;
  if (d.norm() < 1e-9) return;
  const Eigen::Vector2d n = Eigen::Vector2d(-d.y(), d.x()).normalized() * (0.5 * width);
  triangle(a + n, b + n, b - n, colour);
  triangle(a + n, b - n, a - n, colour);
}

void ShapeBatch::draw() const {
  if (xy_.empty()) return;
  glEnableClientState(GL_VERTEX_ARRAY);
  glEnableClientState(GL_COLOR_ARRAY);
  glVertexPointer(2, GL_FLOAT, 0, xy_.data());
  glColorPointer(4, GL_FLOAT, 0, rgba_.data());
  glDrawArrays(GL_TRIANGLES, 0, static_cast<GLsizei>(xy_.size() / 2));
  glDisableClientState(GL_COLOR_ARRAY);
  glDisableClientState(GL_VERTEX_ARRAY);
}

void drawText(double x, double y, const std::string& text, int scale, const Colour& colour) {
  const double x0 = std::round(x), y0 = std::round(y);
  setColour(colour);
  glBegin(GL_QUADS);
  int column = 0;
  for (const char32_t c : decodeUtf8(text)) {
    const Glyph& g = glyph(c);
    for (int row = 0; row < kGlyphRows; ++row)
      for (int col = 0; col < kGlyphWidth; ++col) {
        if (!(g[row] & (1u << (kGlyphWidth - 1 - col)))) continue;
        const double px = x0 + (column * kAdvance + col) * scale, py = y0 + row * scale;
        glVertex2d(px, py);
        glVertex2d(px + scale, py);
        glVertex2d(px + scale, py + scale);
        glVertex2d(px, py + scale);
      }
    ++column;
  }
  glEnd();
}

void drawArrow(const Eigen::Vector2d& tail, const Eigen::Vector2d& dir, double length, double width,
               const Colour& fill, const Colour& outline, double outline_width) {
  const Eigen::Vector2d side(-dir.y(), dir.x());
  const double head = std::min(length * 0.45, width * 2.6);
  const Eigen::Vector2d tip = tail + dir * length, neck = tip - dir * head;
  const Points shaft{tail + side * (0.5 * width), neck + side * (0.5 * width), neck - side * (0.5 * width),
                     tail - side * (0.5 * width)};
  const Points tip_triangle{neck + side * (1.1 * width), tip, neck - side * (1.1 * width)};
  const Points outer{shaft[0], shaft[1], tip_triangle[0], tip, tip_triangle[2], shaft[2], shaft[3]};
  if (outline_width > 0) strokePolyline(outer, 2 * outline_width, outline, true);
  fillPolygon(outer, fill);
}

}  // namespace bimloc::sim::render
