// Pictures after rendering: grids of tiles, PNG files through libpng's simplified API
// (png_image_write_to_file: no setjmp error handling to wrap), and JPEG files through
// libjpeg-turbo (whose error handler must jump back: WriteJpeg).
#include <png.h>
// jpeglib.h needs FILE and size_t declared first.
#include <cstdio>
#include <jpeglib.h>

#include <csetjmp>
#include <fstream>

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

namespace {

// libjpeg reports errors by calling error_exit, which by default ends the process: ours jumps
// back to the caller with the message instead.
struct JpegError {
  jpeg_error_mgr manager;
  std::jmp_buf back;
  char message[JMSG_LENGTH_MAX];
};

void JumpBack(j_common_ptr info) {
  JpegError* error = reinterpret_cast<JpegError*>(info->err);
  (*info->err->format_message)(info, error->message);
  std::longjmp(error->back, 1);
}

}  // namespace

void WriteJpeg(const Image& image, const std::string& path, int quality) {
  jpeg_compress_struct info{};
  JpegError error{};
  info.err = jpeg_std_error(&error.manager);
  error.manager.error_exit = JumpBack;
  unsigned char* bytes = nullptr;
  unsigned long size = 0;
  if (setjmp(error.back)) {
    jpeg_destroy_compress(&info);
    std::free(bytes);
    throw std::runtime_error("cannot write " + path + ": " + error.message);
  }
  jpeg_create_compress(&info);
  jpeg_mem_dest(&info, &bytes, &size);
  info.image_width = JDIMENSION(image.width);
  info.image_height = JDIMENSION(image.height);
  info.input_components = 3;
  info.in_color_space = JCS_RGB;
  jpeg_set_defaults(&info);
  info.dct_method = JDCT_ISLOW;  // exact integer DCT: the same bytes on every CPU
  jpeg_set_quality(&info, quality, TRUE);
  jpeg_start_compress(&info, TRUE);
  while (info.next_scanline < info.image_height) {
    JSAMPROW row = const_cast<JSAMPROW>(&image.rgb[size_t(info.next_scanline) * image.width * 3]);
    jpeg_write_scanlines(&info, &row, 1);
  }
  jpeg_finish_compress(&info);
  jpeg_destroy_compress(&info);
  std::ofstream out(path, std::ios::binary);
  out.write(reinterpret_cast<const char*>(bytes), std::streamsize(size));
  std::free(bytes);
  if (!out) throw std::runtime_error("cannot write " + path);
}

}  // namespace prs::render
