#pragma once
// Reads a PNG back for the tests through cairo (cairo_image_surface_create_from_png): its size and its
// pixels as RGB8. Throws std::runtime_error when the file is missing or not a PNG.
#include <cairo.h>

#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

namespace png_test {

struct Png {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  // row-major, 3 bytes a pixel
  std::uint8_t at(int x, int y, int channel) const {
    return rgb.at((std::size_t(y) * std::size_t(width) + std::size_t(x)) * 3 + std::size_t(channel));
  }
};

inline Png decode_file(const std::string& path) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
    const std::string why = cairo_status_to_string(cairo_surface_status(s));
    cairo_surface_destroy(s);
    throw std::runtime_error("cannot read PNG " + path + ": " + why);
  }
  cairo_surface_flush(s);
  const cairo_format_t f = cairo_image_surface_get_format(s);
  if (f != CAIRO_FORMAT_RGB24 && f != CAIRO_FORMAT_ARGB32) {
    cairo_surface_destroy(s);
    throw std::runtime_error("unexpected pixel format in " + path);
  }
  Png p;
  p.width = cairo_image_surface_get_width(s), p.height = cairo_image_surface_get_height(s);
  p.rgb.resize(std::size_t(p.width) * std::size_t(p.height) * 3);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  for (int y = 0; y < p.height; ++y)
    for (int x = 0; x < p.width; ++x) {
      std::uint32_t v;  // native-endian 0xAARRGGBB (premultiplied; the figures are opaque)
      std::memcpy(&v, data + std::size_t(y) * std::size_t(stride) + 4 * std::size_t(x), 4);
      const std::size_t i = (std::size_t(y) * std::size_t(p.width) + std::size_t(x)) * 3;
      p.rgb[i] = std::uint8_t(v >> 16), p.rgb[i + 1] = std::uint8_t(v >> 8), p.rgb[i + 2] = std::uint8_t(v);
    }
  cairo_surface_destroy(s);
  return p;
}

}  // namespace png_test
