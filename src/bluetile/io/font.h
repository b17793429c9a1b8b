// A small built-in bitmap font (printable ASCII, 5x7 pixels plus a descender row), so plots get
// their labels on any machine, headless, without a font file, and render identically everywhere.
#pragma once

#include <array>
#include <cstdint>

namespace bluetile {

constexpr int glyph_width = 5;   // pixels drawn
constexpr int glyph_height = 8;  // rows 0-6 above the baseline, row 7 the descender
constexpr int glyph_advance = 6; // pixels from one character to the next
constexpr int line_advance = 10;

// Rows of the glyph for `c`, top first; bit 4 is the leftmost pixel. Characters outside
// printable ASCII get '?'.
const std::array<std::uint8_t, glyph_height>& glyph(char c);

}  // namespace bluetile
