// Wavefront OBJ → TriangleMesh, strictly (every problem names the file and line).
//
// Read:    v x y z [w] | v x y z r g b | v x y z w r g b   (extra components are checked as numbers and ignored)
//          f a b c ...   each corner v, v/vt, v//vn or v/vt/vn; indices from 1, negative = relative to the
//                        elements defined so far (-1 = the last one); vt and vn references are checked too.
//          A polygon with k > 3 corners becomes k − 2 triangles as a fan from its first corner: exact for
//          convex polygons (and polygons star-shaped around that corner), which is what exporters write;
//          a non-convex polygon is not ear-clipped and may give overlapping triangles.
// Checked and ignored: vt (1–3 numbers), vn (3 numbers), vp. Ignored: s, l, p, usemtl, mtllib and the other
//          display/render attributes, comments (# to the end of the line), blank lines. 'o' and 'g' name the
//          group the following faces belong to: a mesh ignores them; readObjGroups keeps them (convex pieces).
// Also:    a first statement of exactly two non-negative integers "V F" is a count line (FCL's benchmark
//          meshes env.obj and rob.obj start with one); the file must then hold exactly V vertices and F faces.
// Errors:  unknown statements, free-form geometry (curv, surf, ...), line continuations ('\'), non-numbers,
//          NaN/Inf, index 0, indices out of range, faces with fewer than 3 corners, a file without faces.
// Positive indices may refer to vertices defined later in the file (checked at the end, the error names the
// face's line); a negative index refers back from the line it is on, as the format defines.
#include "formats/readers.h"
#include "formats/text_scanner.h"

#include <algorithm>
#include <limits>

namespace unidist::formats {
namespace {

using Triangle = TriangleMesh::Triangle;

constexpr long long kMaxIndex = std::numeric_limits<std::uint32_t>::max() - 1;

/// A positive reference past the elements defined so far (resolved when the file has been read).
struct ForwardReference {
  std::size_t line;
  long long index;  // 1-based, as written
  int kind;         // 0 = v, 1 = vt, 2 = vn
};

const char* const kKindName[] = {"vertex", "texture coordinate", "normal"};
const char* const kKindKey[] = {"v", "vt", "vn"};

bool oneOf(std::string_view key, std::initializer_list<std::string_view> keys) {
  return std::find(keys.begin(), keys.end(), key) != keys.end();
}

class ObjReader {
 public:
  ObjReader(const std::string& path, std::string_view text) : s_(path, text) {}

  std::shared_ptr<const Model> read() {
    scan();
    return makeMesh(s_.path(), std::move(vertices_), std::move(triangles_));
  }

  ObjGroups readGroups() {
    scan();
    ObjGroups out;
    out.vertices = std::move(vertices_);
    out.triangles = std::move(triangles_);
    out.groupOfTriangle = std::move(groupOfTriangle_);
    out.groupNames = std::move(groupNames_);
    return out;
  }

 private:
  void scan() {
    bool first = true;
    while (s_.nextLine()) {
      s_.stripComment('#');
      const std::size_t last = s_.line().find_last_not_of(" \t\v\f");
      if (last != std::string_view::npos && s_.line()[last] == '\\')
        s_.fail("line continuation ('\\' at the end of a line) is not supported");
      const std::string_view key = s_.token();
      if (key.empty()) continue;
      const bool firstStatement = first;
      first = false;
      if (key == "v") {
        vertex();
      } else if (key == "f") {
        face();
      } else if (key == "vt") {
        checkNumbers(key, 1, 3);
        ++counts_[1];
      } else if (key == "vn") {
        checkNumbers(key, 3, 3);
        ++counts_[2];
      } else if (key == "vp") {
        checkNumbers(key, 1, 3);
      } else if (key == "o" || key == "g") {
        group();
      } else if (oneOf(key, {"s", "l", "p", "usemtl", "mtllib", "lod", "bevel", "c_interp", "d_interp",
                             "shadow_obj", "trace_obj", "maplib", "usemap", "ctech", "stech"})) {
        // materials, smoothing, lines and points: nothing the geometry needs
      } else if (oneOf(key, {"cstype", "deg", "bmat", "step", "curv", "curv2", "surf", "parm", "trim", "hole", "scrv",
                             "sp", "end", "con"})) {
        s_.fail("free-form geometry ('" + std::string(key) + "') is not supported; only polygonal faces are");
      } else if (!(firstStatement && countLine(key))) {
        s_.fail("unknown OBJ statement " + quoted(key) + " (expected v, f, vt, vn, o, g, s, usemtl, ...)");
      }
    }
    finish();
  }

  /// 'o name' / 'g name ...': the following faces belong to the group of that whole text (one group per text).
  void group() {
    std::string name;
    for (std::string_view t = s_.token(); !t.empty(); t = s_.token()) name += (name.empty() ? "" : " ") + std::string(t);
    const auto found = std::find(groupNames_.begin(), groupNames_.end(), name);
    currentGroup_ = static_cast<int>(found - groupNames_.begin());
    if (found == groupNames_.end()) groupNames_.push_back(name);
  }

  void vertex() {
    double c[3];
    c[0] = next("x coordinate");
    c[1] = next("y coordinate");
    c[2] = next("z coordinate");
    int extra = 0;
    for (std::string_view t = s_.token(); !t.empty(); t = s_.token()) {
      if (++extra > 4) s_.fail("a vertex has at most 7 values (x y z [w] [r g b])");
      s_.number(t, "vertex component " + std::to_string(3 + extra));
    }
    if (extra == 2) s_.fail("a vertex has 3, 4, 6 or 7 values (x y z [w] [r g b]), not 5");
    if (vertices_.size() >= static_cast<std::size_t>(kMaxIndex)) s_.fail("too many vertices");
    vertices_.emplace_back(c[0], c[1], c[2]);
    counts_[0] = static_cast<long long>(vertices_.size());
  }

  double next(const char* what) {
    const std::string_view t = s_.token();
    if (t.empty()) s_.fail(std::string("vertex needs x y z: the ") + what + " is missing");
    return s_.number(t, what);
  }

  void checkNumbers(std::string_view key, int lo, int hi) {
    int n = 0;
    for (std::string_view t = s_.token(); !t.empty(); t = s_.token()) {
      if (++n > hi) s_.fail("'" + std::string(key) + "' has more than " + std::to_string(hi) + " values");
      s_.number(t, std::string(key) + " value " + std::to_string(n));
    }
    if (n < lo) s_.fail("'" + std::string(key) + "' needs at least " + std::to_string(lo) + " value(s)");
  }

  /// Resolves one index of kind k (as written) to 0-based; forward references are recorded.
  long long resolve(std::string_view text, int k, std::size_t corner) {
    const auto what = [&] { return std::string(kKindName[k]) + " index of corner " + std::to_string(corner); };
    long long i = 0;
    if (!parseInteger(text, i) || i < -kMaxIndex || i > kMaxIndex) s_.integer(text, what(), -kMaxIndex, kMaxIndex);
    if (i == 0) s_.fail(what() + " is 0 (OBJ indices start at 1; negative ones count back from the last)");
    if (i < 0) {
      if (-i > counts_[k])
        s_.fail(what() + " is " + std::to_string(i) + ", but only " + std::to_string(counts_[k]) + " " + kKindName[k] +
                "(s) ('" + kKindKey[k] + "') are defined before this line");
      return counts_[k] + i;
    }
    if (i > counts_[k]) forward_.push_back({s_.lineNumber(), i, k});
    return i - 1;
  }

  void face() {
    polygon_.clear();
    for (std::string_view t = s_.token(); !t.empty(); t = s_.token()) {
      const std::size_t corner = polygon_.size() + 1;
      // Split "v", "v/vt", "v//vn", "v/vt/vn".
      std::string_view part[3];
      int parts = 0;
      std::size_t start = 0;
      for (;;) {
        const std::size_t slash = t.find('/', start);
        if (parts == 3) s_.fail("corner " + quoted(t) + " has more than three '/'-separated parts");
        part[parts++] = t.substr(start, slash == std::string_view::npos ? std::string_view::npos : slash - start);
        if (slash == std::string_view::npos) break;
        start = slash + 1;
      }
      if (part[0].empty()) s_.fail("corner " + quoted(t) + " has no vertex index");
      if ((parts == 2 && part[1].empty()) || (parts == 3 && part[2].empty()))
        s_.fail("corner " + quoted(t) + " ends with '/' (expected v, v/vt, v//vn or v/vt/vn)");
      polygon_.push_back(static_cast<std::uint32_t>(resolve(part[0], 0, corner)));
      if (parts >= 2 && !part[1].empty()) resolve(part[1], 1, corner);
      if (parts == 3) resolve(part[2], 2, corner);
    }
    if (polygon_.size() < 3)
      s_.fail("a face needs at least 3 corners, this one has " + std::to_string(polygon_.size()));
    if (currentGroup_ < 0) {  // faces before any 'o'/'g' form the unnamed group
      groupNames_.push_back("");
      currentGroup_ = static_cast<int>(groupNames_.size()) - 1;
    }
    for (std::size_t k = 1; k + 1 < polygon_.size(); ++k) {  // fan from the first corner
      triangles_.push_back({polygon_[0], polygon_[k], polygon_[k + 1]});
      groupOfTriangle_.push_back(currentGroup_);
    }
    ++faces_;
  }

  /// "V F" as the first statement (FCL's meshes); false when the line is not two integers.
  bool countLine(std::string_view first) {
    const std::string_view second = s_.token();
    if (second.empty() || !s_.atEndOfLine()) return false;
    for (std::string_view t : {first, second})
      if (t.find_first_not_of("0123456789") != std::string_view::npos) return false;
    countLine_ = s_.lineNumber();
    declaredVertices_ = s_.integer(first, "vertex count", 0, kMaxIndex);
    declaredFaces_ = s_.integer(second, "face count", 0, std::numeric_limits<long long>::max());
    return true;
  }

  void finish() {
    if (s_.lineNumber() == 0) s_.fail("empty file");
    for (const ForwardReference& r : forward_)
      if (r.index > counts_[r.kind])
        failAtLine(s_.path(), r.line,
                   std::string(kKindName[r.kind]) + " index " + std::to_string(r.index) +
                       " is out of range: the file " + "defines " + std::to_string(counts_[r.kind]) + " " +
                       kKindName[r.kind] + "(s) ('" + kKindKey[r.kind] + "')");
    if (countLine_ != 0 && (declaredVertices_ != counts_[0] || declaredFaces_ != static_cast<long long>(faces_)))
      failAtLine(s_.path(), countLine_,
                 "the count line says " + std::to_string(declaredVertices_) + " vertices and " +
                     std::to_string(declaredFaces_) + " faces, but the file has " + std::to_string(counts_[0]) +
                     " and " + std::to_string(faces_));
    if (triangles_.empty())
      s_.fail("end of file: no faces ('f' lines) in " + std::to_string(s_.lineNumber()) +
              " lines (an OBJ model must be a polygon mesh)");
  }

  LineScanner s_;
  std::vector<Eigen::Vector3d> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<int> groupOfTriangle_;
  std::vector<std::string> groupNames_;
  int currentGroup_ = -1;
  std::vector<std::uint32_t> polygon_;
  std::vector<ForwardReference> forward_;
  long long counts_[3] = {0, 0, 0};  // v, vt, vn defined so far
  std::size_t faces_ = 0;
  std::size_t countLine_ = 0;
  long long declaredVertices_ = 0, declaredFaces_ = 0;
};

}  // namespace

std::shared_ptr<const Model> readObj(const std::string& path) {
  const std::string text = readWholeFile(path);
  return ObjReader(path, text).read();
}

ObjGroups readObjGroups(const std::string& path) {
  const std::string text = readWholeFile(path);
  return ObjReader(path, text).readGroups();
}

}  // namespace unidist::formats
