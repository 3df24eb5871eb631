// Pictures after rendering: grids of tiles, and PNG files through libpng's simplified API
// (png_image_write_to_file: no setjmp error handling to wrap).
#include <png.h>

#include <cmath>
#include <stdexcept>

#include "render/render.h"

namespace prs::render {
namespace {

void WritePngImage(png_image& image, const std::string& path, const void* pixels) {
  if (!png_image_write_to_file(&image, path.c_str(), 0, pixels, 0, nullptr)) {
    const std::string reason = image.message;
    png_image_free(&image);
    throw std::runtime_error("cannot write " + path + ": " + reason);
  }
}

png_image MakePngImage(int width, int height, png_uint_32 format) {
  png_image image{};
  image.version = PNG_IMAGE_VERSION;
  image.width = static_cast<png_uint_32>(width);
  image.height = static_cast<png_uint_32>(height);
  image.format = format;
  return image;
}

}  // namespace

std::pair<int, int> CalcGridShape(int count) {
  if (count < 1) return {0, 0};
  const int columns = static_cast<int>(std::ceil(std::sqrt(static_cast<double>(count))));
  return {columns, (count + columns - 1) / columns};
}

Image ComposeGrid(const std::vector<Image>& tiles) {
  if (tiles.empty()) throw std::invalid_argument("ComposeGrid: no tiles");
  const int tile_w = tiles[0].width, tile_h = tiles[0].height;
  const auto [columns, rows] = CalcGridShape(static_cast<int>(tiles.size()));
  const int step_x = tile_w + kGridGutter, step_y = tile_h + kGridGutter;
  Image grid{columns * step_x - kGridGutter, rows * step_y - kGridGutter, {}};
  grid.rgb.assign(size_t(grid.width) * grid.height * 3, 255);
  for (size_t t = 0; t < tiles.size(); ++t) {
    if (tiles[t].width != tile_w || tiles[t].height != tile_h)
      throw std::invalid_argument("ComposeGrid: tile " + std::to_string(t) + " is " +
                                  std::to_string(tiles[t].width) + "x" +
                                  std::to_string(tiles[t].height) + ", not " +
                                  std::to_string(tile_w) + "x" + std::to_string(tile_h));
    const int x0 = static_cast<int>(t % columns) * step_x;
    const int y0 = static_cast<int>(t / columns) * step_y;
    for (int y = 0; y < tile_h; ++y) {
      const uint8_t* from = &tiles[t].rgb[size_t(y) * tile_w * 3];
      std::copy(from, from + tile_w * 3, &grid.rgb[(size_t(y0 + y) * grid.width + x0) * 3]);
    }
  }
  return grid;
}

void WritePng(const Image& image, const std::string& path) {
  png_image png = MakePngImage(image.width, image.height, PNG_FORMAT_RGB);
  png.flags |= PNG_IMAGE_FLAG_FAST;
  WritePngImage(png, path, image.rgb.data());
}

void WriteDepthPng(const DepthImage& depth, const std::string& path, double mm_per_unit) {
  std::vector<png_uint_16> millimetres(depth.depth_m.size());
  for (size_t i = 0; i < depth.depth_m.size(); ++i) {
    const double units = std::round(depth.depth_m[i] * 1000.0 / mm_per_unit);
    millimetres[i] = std::isfinite(units) && units > 0 && units <= 65535 ? png_uint_16(units) : 0;
  }
  // PNG_FORMAT_LINEAR_Y: 16-bit grey written as is (with a linear gamma note).
  png_image png = MakePngImage(depth.width, depth.height, PNG_FORMAT_LINEAR_Y);
  png.flags |= PNG_IMAGE_FLAG_FAST;
  WritePngImage(png, path, millimetres.data());
}

void WriteMaskPng(const std::vector<uint8_t>& mask, int width, int height,
                  const std::string& path) {
  if (mask.size() != size_t(width) * size_t(height))
    throw std::invalid_argument("WriteMaskPng: the mask is not width x height");
  std::vector<uint8_t> grey(mask.size());
  for (size_t i = 0; i < mask.size(); ++i) grey[i] = mask[i] ? 255 : 0;
  png_image png = MakePngImage(width, height, PNG_FORMAT_GRAY);
  png.flags |= PNG_IMAGE_FLAG_FAST;  // two values: fast compression loses little
  WritePngImage(png, path, grey.data());
}

}  // namespace prs::render
