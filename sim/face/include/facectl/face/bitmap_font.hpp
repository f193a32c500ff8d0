// A tiny built-in 5×7 bitmap font for labels on rendered pictures (no font files, no
// extra dependency): printable ASCII, with descenders in an eighth row; each glyph in a
// 6×8 cell.
#pragma once

#include <array>
#include <cstdint>
#include <string_view>

#include "facectl/face/image.hpp"

namespace facectl::face {

inline constexpr int kGlyphWidth = 5, kGlyphHeight = 8, kGlyphAdvance = 6;

// Rows top to bottom, bit 4 = leftmost column. Characters outside the table draw as '?'.
const std::array<std::uint8_t, kGlyphHeight>& glyph(char c);

// Pixel width of `text` at `scale` (each font pixel a scale × scale block), no trailing gap.
int text_width(std::string_view text, int scale);
// Draws `text` with its top-left corner at (x, y); pixels outside the image are clipped.
void draw_text(Image& img, int x, int y, std::string_view text, int scale,
               std::array<std::uint8_t, 3> colour);

}  // namespace facectl::face
