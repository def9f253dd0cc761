// An 8-bit RGB picture, top row first, and its PNG file (libpng's simplified API: no setjmp, errors returned).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace unidist::render {

struct Image {
  int width = 0, height = 0;
  std::vector<std::uint8_t> rgb;  ///< width × height × 3 bytes, top row first

  const std::uint8_t* pixel(int x, int y) const { return &rgb[3 * (static_cast<std::size_t>(y) * width + x)]; }
};

/// Writes the picture as an 8-bit RGB PNG. Throws InputError naming the file when it cannot be written.
void writePng(const std::string& path, const Image& image);
/// Reads any PNG as 8-bit RGB (alpha composited on black). Throws InputError naming the file on failure.
Image readPng(const std::string& path);

}  // namespace unidist::render
