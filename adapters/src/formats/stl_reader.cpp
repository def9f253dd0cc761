// STL → TriangleMesh, ASCII or binary, strictly (errors name the file and the line or byte offset).
//
// Which encoding: binary when the file is at least 84 bytes and its size is exactly 84 + 50·n for the n in
// bytes 80–83 — decided first, because binary files whose 80-byte header starts with "solid" exist in the
// wild. Otherwise ASCII when it starts with "solid" and holds only text bytes (no control characters but
// blanks and line ends); otherwise binary, which then reports the size that does not match its count.
// (Text bytes at 80–83 read as a count of at least 0x20202020, so only an ASCII file of over 26 GB could
// pass for binary by its size.)
//
// Binary: 80-byte header (ignored), uint32 n (little endian), n × {normal 3×float32 (ignored: the mesh
//         computes its own), 3 vertices × 3 float32, uint16 attribute (ignored)}. n = 0, a size other than
//         84 + 50·n and a NaN/Inf vertex coordinate are errors (the byte offset of the culprit).
// ASCII:  solid [name] { facet normal ni nj nk / outer loop / vertex x y z (×3) / endloop / endfacet }
//         endsolid [name]; several solids in one file are read as one mesh. Keywords are case-insensitive
//         and separated by any white space (line breaks included). Exactly three vertices per facet.
// STL has no shared vertices: the three corners of each facet are separate, and the mesh welds equal ones.
#include "formats/readers.h"
#include "formats/text_scanner.h"

#include <cctype>
#include <cmath>
#include <limits>

namespace unidist::formats {
namespace {

using Triangle = TriangleMesh::Triangle;

bool equalsIgnoreCase(std::string_view a, std::string_view b) {
  if (a.size() != b.size()) return false;
  for (std::size_t i = 0; i < a.size(); ++i)
    if (std::tolower(static_cast<unsigned char>(a[i])) != std::tolower(static_cast<unsigned char>(b[i]))) return false;
  return true;
}

/// "solid" after optional white space, followed by white space or the end, and no control bytes anywhere.
bool looksAscii(std::string_view data) {
  std::size_t i = 0;
  while (i < data.size() && std::isspace(static_cast<unsigned char>(data[i]))) ++i;
  if (!equalsIgnoreCase(data.substr(i, 5), "solid")) return false;
  if (i + 5 < data.size() && !std::isspace(static_cast<unsigned char>(data[i + 5]))) return false;
  for (char c : data) {
    const unsigned char u = static_cast<unsigned char>(c);
    if ((u < 0x20 && u != '\t' && u != '\n' && u != '\r' && u != '\v' && u != '\f') || u == 0x7f) return false;
  }
  return true;
}

std::uint32_t littleEndian32(std::string_view data, std::size_t at) {
  const auto b = [&](std::size_t k) { return static_cast<std::uint32_t>(static_cast<unsigned char>(data[at + k])); };
  return b(0) | b(1) << 8 | b(2) << 16 | b(3) << 24;
}

std::shared_ptr<const Model> readBinary(const std::string& path, std::string_view data) {
  if (data.size() < 84)
    failAtByte(path, data.size(),
               "truncated binary STL: the file ends after " + std::to_string(data.size()) +
                   " bytes, before the 84-byte header and triangle count (and it is not ASCII STL: that starts "
                   "with 'solid')");
  const std::uint64_t n = littleEndian32(data, 80);
  if (n == 0) failAtByte(path, 80, "the binary STL header declares 0 triangles");
  if (n > std::numeric_limits<std::uint32_t>::max() / 3)
    failAtByte(path, 80, "the binary STL header declares " + std::to_string(n) + " triangles: too many");
  const std::uint64_t expected = 84 + 50 * n;
  if (data.size() < expected) {
    const std::uint64_t complete = (data.size() - 84) / 50;
    failAtByte(path, 84 + 50 * complete,
               "truncated binary STL: the header declares " + std::to_string(n) + " triangles (" +
                   std::to_string(expected) + " bytes) but the file ends at byte " + std::to_string(data.size()) +
                   ", inside triangle " + std::to_string(complete));
  }
  if (data.size() > expected)
    failAtByte(path, expected,
               std::to_string(data.size() - expected) + " unexpected bytes after the " + std::to_string(n) +
                   " triangles the binary STL header declares");

  std::vector<Eigen::Vector3d> vertices;
  std::vector<Triangle> triangles;
  vertices.reserve(3 * n);
  triangles.reserve(n);
  ByteReader r(path, data, 84, /*bigEndian=*/false);
  for (std::uint32_t t = 0; t < n; ++t) {
    r.skip(12, "a facet normal");
    for (int v = 0; v < 3; ++v) {
      double c[3];
      for (double& x : c) {
        const std::size_t at = r.offset();
        x = r.read<float>("a vertex coordinate");
        if (!std::isfinite(x))
          r.fail(at, "triangle " + std::to_string(t) + ", vertex " + std::to_string(v) + ": coordinate is " +
                         (std::isnan(x) ? "NaN" : "infinite"));
      }
      vertices.emplace_back(c[0], c[1], c[2]);
    }
    r.skip(2, "an attribute byte count");
    triangles.push_back({3 * t, 3 * t + 1, 3 * t + 2});
  }
  return makeMesh(path, std::move(vertices), std::move(triangles));
}

/// Tokens across lines, with the scanner's line number for messages.
class AsciiStl {
 public:
  AsciiStl(const std::string& path, std::string_view text) : s_(path, text) {}

  std::shared_ptr<const Model> read() {
    expectKeyword("solid");
    s_.rest();  // the solid's name
    for (;;) {
      const std::string_view t = next();
      if (t.empty()) s_.fail("end of file inside a solid: 'endsolid' is missing (file truncated?)");
      if (equalsIgnoreCase(t, "facet")) {
        facet();
      } else if (equalsIgnoreCase(t, "endsolid")) {
        s_.rest();  // the name again
        const std::string_view after = next();
        if (after.empty()) break;
        if (!equalsIgnoreCase(after, "solid"))
          s_.fail("expected 'solid' or the end of the file, found " + quoted(after));
        s_.rest();
      } else {
        s_.fail("expected 'facet' or 'endsolid', found " + quoted(t));
      }
    }
    if (triangles_.empty()) s_.fail("the ASCII STL file has no facets");
    return makeMesh(s_.path(), std::move(vertices_), std::move(triangles_));
  }

 private:
  /// The next token, moving to following lines as needed; empty at the end of the text.
  std::string_view next() {
    for (;;) {
      const std::string_view t = s_.token();
      if (!t.empty()) return t;
      if (!s_.nextLine()) return {};
    }
  }

  void expectKeyword(const char* keyword) {
    const std::string_view t = next();
    if (t.empty()) {
      if (s_.lineNumber() == 0) s_.fail("empty file");
      s_.fail(std::string("end of file where '") + keyword + "' was expected (file truncated?)");
    }
    if (!equalsIgnoreCase(t, keyword)) s_.fail(std::string("expected '") + keyword + "', found " + quoted(t));
  }

  double number(const char* what) {
    const std::string_view t = next();
    if (t.empty()) s_.fail(std::string("end of file where ") + what + " was expected (file truncated?)");
    return s_.number(t, what);
  }

  void facet() {
    expectKeyword("normal");
    for (const char* what : {"normal x", "normal y", "normal z"}) number(what);  // checked, not used
    expectKeyword("outer");
    expectKeyword("loop");
    const auto first = static_cast<std::uint32_t>(vertices_.size());
    for (int v = 0; v < 3; ++v) {
      const std::string_view t = next();
      if (!equalsIgnoreCase(t, "vertex"))
        s_.fail("expected 'vertex' (a facet has exactly 3), found " +
                (t.empty() ? std::string("the end of file") : quoted(t)));
      const double x = number("vertex x"), y = number("vertex y"), z = number("vertex z");
      vertices_.emplace_back(x, y, z);
    }
    const std::string_view t = next();
    if (equalsIgnoreCase(t, "vertex")) s_.fail("a facet with more than 3 vertices (STL facets are triangles)");
    if (!equalsIgnoreCase(t, "endloop"))
      s_.fail("expected 'endloop', found " + (t.empty() ? std::string("the end of file") : quoted(t)));
    expectKeyword("endfacet");
    if (vertices_.size() >= std::numeric_limits<std::uint32_t>::max() - 3) s_.fail("too many facets");
    triangles_.push_back({first, first + 1, first + 2});
  }

  LineScanner s_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Triangle> triangles_;
};

}  // namespace

std::shared_ptr<const Model> readStl(const std::string& path) {
  const std::string data = readWholeFile(path);
  if (data.empty()) failAtByte(path, 0, "empty file");
  if (data.size() >= 84 && data.size() == 84 + 50 * static_cast<std::uint64_t>(littleEndian32(data, 80)))
    return readBinary(path, data);
  if (looksAscii(data)) return AsciiStl(path, data).read();
  return readBinary(path, data);
}

}  // namespace unidist::formats
