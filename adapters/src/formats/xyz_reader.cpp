// XYZ → PointCloud, strictly (every problem names the file and line).
//
// One point per line: "x y z" or "x y z nx ny nz", values separated by blanks (spaces, tabs) or by commas
// with optional blanks around them. '#' starts a comment (to the end of the line); blank lines are skipped.
// The first point decides whether the file has normals: every point must then have the same number of
// values. Anything else — a header row ("x,y,z"), a 4th or 7th column, an empty field ("1,,2"), NaN/Inf,
// a file without points — is an error naming the line.
#include "formats/readers.h"
#include "formats/text_scanner.h"

namespace unidist::formats {

std::shared_ptr<const Model> readXyz(const std::string& path) {
  const std::string text = readWholeFile(path);
  LineScanner s(path, text);
  std::vector<Eigen::Vector3d> points, normals;
  points.reserve(text.size() / 24);  // a point takes at least 6 bytes; typical files ~25-60 per line
  int columns = 0;                   // 3 or 6, set by the first point
  std::size_t firstLine = 0;
  static const char* const kNames[] = {"x", "y", "z", "nx", "ny", "nz"};
  while (s.nextLine()) {
    s.stripComment('#');
    double v[6];
    int n = 0;
    for (std::string_view f = s.field(); !f.empty(); f = s.field()) {
      if (n == 6) s.fail("more than 6 values (a point is x y z or x y z nx ny nz)");
      v[n] = s.number(f, kNames[n]);
      ++n;
    }
    if (n == 0) continue;
    if (n != 3 && n != 6) s.fail(std::to_string(n) + " values (a point is x y z or x y z nx ny nz)");
    if (columns == 0) {
      columns = n;
      firstLine = s.lineNumber();
      if (columns == 6) normals.reserve(points.capacity());
    } else if (n != columns) {
      s.fail(std::to_string(n) + " values, but the first point (line " + std::to_string(firstLine) + ") has " +
             std::to_string(columns) + (columns == 6 ? " (with normals)" : " (without normals)"));
    }
    points.emplace_back(v[0], v[1], v[2]);
    if (n == 6) normals.emplace_back(v[3], v[4], v[5]);
  }
  if (points.empty()) {
    if (s.emptyText()) failAtLine(path, 1, "empty file (no points)");
    s.fail("no points in the file (only comments and blank lines)");
  }
  return makeCloud(path, std::move(points), std::move(normals));
}

}  // namespace unidist::formats
