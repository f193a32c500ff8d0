// An 8-bit RGB image and PNG output (libpng), for headless pictures of the face.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace facectl::face {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes per pixel
  Image() = default;
  Image(int w, int h, std::uint8_t grey) : width(w), height(h), rgb(3u * w * h, grey) {}
};

// Throws InputError when the file cannot be written.
void write_png(const std::string& path, const Image& img);
// Any PNG, converted to 8-bit RGB. Throws InputError when it cannot be read.
Image read_png(const std::string& path);
// Averages factor × factor blocks (anti-aliasing after supersampled rendering).
Image downsample(const Image& img, int factor);
// Copies src into dst with its top-left corner at (x, y), clipped to dst.
void blit(Image& dst, const Image& src, int x, int y);
// `top` above `bottom`, each centred horizontally on a white background.
Image stack_vertically(const Image& top, const Image& bottom, int gap);
// Tiles images of equal size into a grid with `cols` columns and a `gap`-pixel border.
Image contact_sheet(const std::vector<Image>& tiles, int cols, int gap);

}  // namespace facectl::face
