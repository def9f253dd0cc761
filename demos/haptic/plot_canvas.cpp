#include "plot_canvas.h"

#include "unidist/types.h"

#include <png.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstring>

namespace unidist::haptic {
namespace {

/// One glyph: 5 rows of 3 pixels, top row first, '#' set.
struct Glyph {
  char c;
  const char* rows;
};

// Drawn for this plot: 3×5 is the smallest grid where every digit and letter stays distinct.
constexpr Glyph kFont[] = {
    {'0', "####.##.##.####"}, {'1', ".#.##..#..#.###"}, {'2', "###..#####..###"}, {'3', "###..#.##..####"},
    {'4', "#.##.####..#..#"}, {'5', "####..###..####"}, {'6', "####..####.####"}, {'7', "###..#.#..#..#."},
    {'8', "####.#####.####"}, {'9', "####.####..####"}, {'A', ".#.#.#####.##.#"}, {'B', "##.#.###.#.###."},
    {'C', ".###..#..#...##"}, {'D', "##.#.##.##.###."}, {'E', "####..##.#..###"}, {'F', "####..##.#..#.."},
    {'G', ".###..#.##.#.##"}, {'H', "#.##.#####.##.#"}, {'I', "###.#..#..#.###"}, {'J', "..#..#..##.#.#."},
    {'K', "#.##.###.#.##.#"}, {'L', "#..#..#..#..###"}, {'M', "#.########.##.#"}, {'N', "##.#.##.##.##.#"},
    {'O', ".#.#.##.##.#.#."}, {'P', "##.#.###.#..#.."}, {'Q', ".#.#.##.##.#.##"}, {'R', "##.#.###.#.##.#"},
    {'S', ".###...#...###."}, {'T', "###.#..#..#..#."}, {'U', "#.##.##.##.####"}, {'V', "#.##.##.##.#.#."},
    {'W', "#.##.########.#"}, {'X', "#.##.#.#.#.##.#"}, {'Y', "#.##.#.#..#..#."}, {'Z', "###..#.#.#..###"},
    {'.', ".............#."}, {'-', "......###......"}, {'+', "....#.###.#...."}, {'|', ".#..#..#..#..#."},
    {'(', "..#.#..#..#...#"}, {')', "#...#..#..#.#.."}, {'/', "..#..#.#.#..#.."}, {':', "....#.....#...."},
    {'=', "...###...###..."}, {'_', "............###"}, {',', "..........#.#.."},
};

const char* glyphRows(char c) {
  const char u = static_cast<char>(std::toupper(static_cast<unsigned char>(c)));
  for (const Glyph& g : kFont)
    if (g.c == u && std::strlen(g.rows) == 15) return g.rows;
  return nullptr;  // a space, or a sign the font lacks: left blank
}

}  // namespace

PlotCanvas::PlotCanvas(int width, int height, Rgb background)
    : width_(width), height_(height), rgb_(3 * static_cast<std::size_t>(width) * static_cast<std::size_t>(height)) {
  for (std::size_t i = 0; i < rgb_.size(); i += 3) {
    rgb_[i] = background.r;
    rgb_[i + 1] = background.g;
    rgb_[i + 2] = background.b;
  }
}

void PlotCanvas::set(int x, int y, Rgb c) {
  if (x < 0 || y < 0 || x >= width_ || y >= height_) return;
  std::uint8_t* p = &rgb_[3 * (static_cast<std::size_t>(y) * static_cast<std::size_t>(width_) + static_cast<std::size_t>(x))];
  p[0] = c.r;
  p[1] = c.g;
  p[2] = c.b;
}

void PlotCanvas::line(double x0, double y0, double x1, double y1, Rgb c, int thickness) {
  // Sample at half-pixel spacing: no gaps at any slope, and a square brush gives the thickness.
  const double length = std::max(std::abs(x1 - x0), std::abs(y1 - y0));
  const int samples = std::max(1, static_cast<int>(std::ceil(2 * length)));
  const int lo = -(thickness - 1) / 2, hi = thickness / 2;
  for (int i = 0; i <= samples; ++i) {
    const double s = static_cast<double>(i) / samples;
    const int x = static_cast<int>(std::lround(x0 + s * (x1 - x0))), y = static_cast<int>(std::lround(y0 + s * (y1 - y0)));
    for (int dy = lo; dy <= hi; ++dy)
      for (int dx = lo; dx <= hi; ++dx) set(x + dx, y + dy, c);
  }
}

void PlotCanvas::fillRect(int x0, int y0, int x1, int y1, Rgb c) {
  for (int y = std::min(y0, y1); y <= std::max(y0, y1); ++y)
    for (int x = std::min(x0, x1); x <= std::max(x0, x1); ++x) set(x, y, c);
}

int PlotCanvas::textWidth(const std::string& s, int scale) { return static_cast<int>(s.size()) * 4 * scale; }

int PlotCanvas::text(int x, int y, const std::string& s, Rgb c, int scale) {
  for (std::size_t i = 0; i < s.size(); ++i) {
    const char* rows = glyphRows(s[i]);
    if (!rows) continue;
    const int left = x + static_cast<int>(i) * 4 * scale;
    for (int row = 0; row < 5; ++row)
      for (int col = 0; col < 3; ++col)
        if (rows[row * 3 + col] == '#')
          fillRect(left + col * scale, y + row * scale, left + (col + 1) * scale - 1, y + (row + 1) * scale - 1, c);
  }
  return textWidth(s, scale);
}

void PlotCanvas::writePng(const std::string& path) const {
  png_image png;
  std::memset(&png, 0, sizeof png);
  png.version = PNG_IMAGE_VERSION;
  png.width = static_cast<png_uint_32>(width_);
  png.height = static_cast<png_uint_32>(height_);
  png.format = PNG_FORMAT_RGB;
  errno = 0;
  if (!png_image_write_to_file(&png, path.c_str(), 0, rgb_.data(), 0, nullptr)) {
    const std::string why = errno ? std::strerror(errno) : png.message;
    png_image_free(&png);
    throw InputError(path + ": cannot write the PNG plot (" + why + ")");
  }
}

}  // namespace unidist::haptic
