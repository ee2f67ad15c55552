// Reading 8-bit RGB PNGs (what `fccvdb render` and the viewer's screenshots write) in tests.
#pragma once

#include <png.h>

#include <cstdio>
#include <memory>
#include <string>
#include <vector>

namespace fcc::test {

struct Rgb8 {
  int width = 0, height = 0;
  std::vector<unsigned char> pixels;  // 3 per pixel
};

// False for a missing file or anything but 8-bit RGB.
inline bool readPng(const std::string& path, Rgb8& out) {
  FILE* f = std::fopen(path.c_str(), "rb");
  if (!f) return false;
  std::unique_ptr<FILE, int (*)(FILE*)> closer(f, std::fclose);
  png_structp png = png_create_read_struct(PNG_LIBPNG_VER_STRING, nullptr, nullptr, nullptr);
  png_infop info = png_create_info_struct(png);
  if (setjmp(png_jmpbuf(png))) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  png_init_io(png, f);
  png_read_info(png, info);
  if (png_get_color_type(png, info) != PNG_COLOR_TYPE_RGB || png_get_bit_depth(png, info) != 8) {
    png_destroy_read_struct(&png, &info, nullptr);
    return false;
  }
  out.width = int(png_get_image_width(png, info));
  out.height = int(png_get_image_height(png, info));
  out.pixels.resize(std::size_t(out.width) * out.height * 3);
  for (int y = 0; y < out.height; ++y) png_read_row(png, out.pixels.data() + std::size_t(y) * out.width * 3, nullptr);
  png_destroy_read_struct(&png, &info, nullptr);
  return true;
}

}  // namespace fcc::test
