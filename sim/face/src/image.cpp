#include "facectl/face/image.hpp"

#include <png.h>

#include <algorithm>
#include <cstring>

#include "facectl/face/input_error.hpp"

namespace facectl::face {

void write_png(const std::string& path, const Image& img) {
  png_image pi;
  std::memset(&pi, 0, sizeof pi);
  pi.version = PNG_IMAGE_VERSION;
  pi.width = static_cast<png_uint_32>(img.width);
  pi.height = static_cast<png_uint_32>(img.height);
  pi.format = PNG_FORMAT_RGB;
  if (!png_image_write_to_file(&pi, path.c_str(), 0, img.rgb.data(), 0, nullptr))
    throw InputError(path + ": cannot write PNG (" + pi.message + ")");
}

Image read_png(const std::string& path) {
  png_image pi;
  std::memset(&pi, 0, sizeof pi);
  pi.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&pi, path.c_str()))
    throw InputError(path + ": cannot read PNG (" + pi.message + ")");
  pi.format = PNG_FORMAT_RGB;
  Image img(static_cast<int>(pi.width), static_cast<int>(pi.height), 0);
  if (!png_image_finish_read(&pi, nullptr, img.rgb.data(), 0, nullptr)) {
    const std::string message = pi.message;
    png_image_free(&pi);
    throw InputError(path + ": cannot read PNG (" + message + ")");
  }
  return img;
}

Image downsample(const Image& img, int f) {
  Image out(img.width / f, img.height / f, 0);
  for (int y = 0; y < out.height; ++y)
    for (int x = 0; x < out.width; ++x)
      for (int c = 0; c < 3; ++c) {
        int sum = 0;
        for (int dy = 0; dy < f; ++dy)
          for (int dx = 0; dx < f; ++dx)
            sum += img.rgb[3 * ((y * f + dy) * img.width + x * f + dx) + c];
        out.rgb[3 * (y * out.width + x) + c] = static_cast<std::uint8_t>(sum / (f * f));
      }
  return out;
}

void blit(Image& dst, const Image& src, int x, int y) {
  const int x0 = std::max(0, x), x1 = std::min(dst.width, x + src.width);
  if (x0 >= x1) return;
  for (int sy = std::max(0, -y); sy < src.height && y + sy < dst.height; ++sy)
    std::memcpy(&dst.rgb[3 * ((y + sy) * dst.width + x0)], &src.rgb[3 * (sy * src.width + x0 - x)],
                3u * (x1 - x0));
}

Image stack_vertically(const Image& top, const Image& bottom, int gap) {
  Image out(std::max(top.width, bottom.width), top.height + gap + bottom.height, 255);
  blit(out, top, (out.width - top.width) / 2, 0);
  blit(out, bottom, (out.width - bottom.width) / 2, top.height + gap);
  return out;
}

Image contact_sheet(const std::vector<Image>& tiles, int cols, int gap) {
  if (tiles.empty()) return {};
  const int tw = tiles[0].width, th = tiles[0].height;
  const int n = static_cast<int>(tiles.size()), rows = (n + cols - 1) / cols;
  Image out(cols * tw + (cols + 1) * gap, rows * th + (rows + 1) * gap, 255);
  for (int k = 0; k < n; ++k)
    blit(out, tiles[k], gap + (k % cols) * (tw + gap), gap + (k / cols) * (th + gap));
  return out;
}

}  // namespace facectl::face
