// The built-in 5×7 font: pixel counts of known glyphs, scaling, clipping, fallback.
#include "facectl/face/bitmap_font.hpp"

#include <gtest/gtest.h>

namespace facectl::face {
namespace {

constexpr std::array<std::uint8_t, 3> kInk{10, 20, 30};

int ink_pixels(const Image& img) {
  int n = 0;
  for (int i = 0; i < img.width * img.height; ++i)
    n +=
        img.rgb[3 * i] == kInk[0] && img.rgb[3 * i + 1] == kInk[1] && img.rgb[3 * i + 2] == kInk[2];
  return n;
}

int drawn(std::string_view text, int scale, int x = 1, int y = 1) {
  Image img(80, 40, 255);
  draw_text(img, x, y, text, scale, kInk);
  return ink_pixels(img);
}

TEST(BitmapFont, GlyphsSetTheirDotCounts) {
  // Dots counted by hand from the 5×7 shapes: A = 3+2+2+2+5+2+2, 0 = 3+2+3+3+3+2+3,
  // m = 3+3+3+2+2, '_' = 5, space = 0.
  EXPECT_EQ(drawn("A", 1), 18);
  EXPECT_EQ(drawn("0", 1), 19);
  EXPECT_EQ(drawn("m", 1), 13);
  EXPECT_EQ(drawn("_", 1), 5);
  EXPECT_EQ(drawn(" ", 1), 0);
  EXPECT_EQ(drawn("Am_", 1), 18 + 13 + 5);
  EXPECT_EQ(drawn("A", 2), 4 * 18);  // each dot a 2×2 block
}

TEST(BitmapFont, DotsAreWhereTheTableSays) {
  Image img(8, 9, 255);
  draw_text(img, 1, 1, "L", 1, kInk);  // a column on the left, a full bottom row
  auto ink = [&](int x, int y) { return img.rgb[3 * (y * img.width + x)] == kInk[0]; };
  for (int y = 1; y <= 7; ++y) EXPECT_TRUE(ink(1, y)) << y;
  for (int x = 1; x <= 5; ++x) EXPECT_TRUE(ink(x, 7)) << x;
  EXPECT_FALSE(ink(2, 3));
  EXPECT_FALSE(ink(0, 7));
  EXPECT_FALSE(ink(6, 7));
}

TEST(BitmapFont, WidthAndAdvance) {
  EXPECT_EQ(text_width("", 1), 0);
  EXPECT_EQ(text_width("A", 1), 5);
  EXPECT_EQ(text_width("ABC", 1), 17);
  EXPECT_EQ(text_width("ABC", 3), 51);
  Image img(40, 10, 255);
  draw_text(img, 0, 0, "II", 1, kInk);  // I spans columns 1..3; the second starts at 6
  auto ink = [&](int x) { return img.rgb[3 * x] == kInk[0]; };
  EXPECT_TRUE(ink(1) && ink(3) && ink(7) && ink(9));
  EXPECT_FALSE(ink(0) || ink(4) || ink(5) || ink(6));
}

TEST(BitmapFont, UnknownCharactersDrawAsQuestionMarksAndEdgesClip) {
  EXPECT_EQ(drawn("~", 1), drawn("?", 1));
  EXPECT_EQ(drawn("\x01", 1), drawn("?", 1));
  EXPECT_GT(drawn("?", 1), 0);
  // Half of an 'H' hangs off the left edge: its left column (7 dots) and bar dots go.
  EXPECT_EQ(drawn("H", 1, -2, 0), 7 + 2);
  EXPECT_EQ(drawn("H", 1, 100, 100), 0);
}

}  // namespace
}  // namespace facectl::face
