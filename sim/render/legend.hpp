// The legend panel's text cursor, shared by the sections that the layers draw into it.
#pragma once

#include "sim/render/draw.hpp"
#include "sim/render/font.hpp"

#include <string>

namespace bimloc::sim::render {

inline Colour legendInk() { return hex(0x222222); }
inline Colour legendMuted() { return hex(0x6b6b6b); }

// The text cut to max_px, with "..." where it was cut.
std::string fitText(const std::string& text, int scale, double max_px);

// Lays out a legend column's lines from top to bottom.
struct Cursor {
  double x, y, width;
  int s;
  double line() const { return kLineHeight * s; }
  void heading(const std::string& text);
  void text(const std::string& text, const Colour& colour = legendMuted(), double indent = 0);
  void gap() { y += 0.9 * line(); }
};

}  // namespace bimloc::sim::render
