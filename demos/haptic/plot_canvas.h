// A tiny RGB raster for line plots written as PNG (libpng's simplified API): lines, rectangles and text in a
// built-in 3×5 pixel font (digits, upper-case letters — lower case is drawn upper case — and a few signs),
// scaled up by whole pixels. Enough for axes, ticks, a title and a legend; nothing more.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace unidist::haptic {

struct Rgb {
  std::uint8_t r = 0, g = 0, b = 0;
};

class PlotCanvas {
 public:
  PlotCanvas(int width, int height, Rgb background);
  int width() const { return width_; }
  int height() const { return height_; }
  void set(int x, int y, Rgb c);  ///< ignored outside the picture
  /// A line `thickness` pixels wide between two points (pixel coordinates, y down).
  void line(double x0, double y0, double x1, double y1, Rgb c, int thickness = 1);
  void fillRect(int x0, int y0, int x1, int y1, Rgb c);
  /// Text with its top-left corner at (x, y), each font pixel `scale` pixels; returns its width in pixels.
  int text(int x, int y, const std::string& s, Rgb c, int scale = 2);
  static int textWidth(const std::string& s, int scale = 2);
  /// Throws InputError naming the file when it cannot be written.
  void writePng(const std::string& path) const;

 private:
  int width_, height_;
  std::vector<std::uint8_t> rgb_;  ///< top row first
};

}  // namespace unidist::haptic
