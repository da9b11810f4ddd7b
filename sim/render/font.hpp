// A small bitmap font (5 pixels wide, 7 above the baseline, 2 below), because OSMesa has no
// text: glyphs are drawn as one quad per set pixel.
#pragma once

#include <array>
#include <cstdint>
#include <string>

namespace bimloc::sim::render {

constexpr int kGlyphWidth = 5;
constexpr int kGlyphRows = 9;   // 7 cap-height rows, then 2 descender rows
constexpr int kAdvance = 6;     // glyph width plus one column of spacing
constexpr int kLineHeight = 11;  // rows plus two of spacing

// Bit 4 of a row is the leftmost pixel.
using Glyph = std::array<std::uint8_t, kGlyphRows>;

// The glyph of a Unicode code point: ASCII, the degree sign, German letters drawn as their
// base letter (a plan's room names are often German); '?' for anything else.
const Glyph& glyph(char32_t code_point);

// UTF-8 to code points; an invalid byte becomes U+FFFD (drawn as '?').
std::u32string decodeUtf8(const std::string& text);

// Width in pixels of the text at the given scale, without the trailing spacing column.
int textWidth(const std::string& text, int scale);

}  // namespace bimloc::sim::render
