// Model file readers (adapters/src/formats/): every format read right — counts, solid flags, coordinates —
// and every class of malformed file rejected with an InputError that names the file and the line
// ("<path>:<line>: ...") or byte offset ("<path>: byte <n>: ...") of the problem (docs/query-contract.md,
// "Model files" and "Bad input"). Fixture files are written by the tests into a scratch directory; the shared
// acceptance models and FCL's env/rob meshes are loaded when ../shared is present.
#include "error_of.h"
#include "scratch_files.h"
#include "unidist/adapters/load.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <unistd.h>
#include <vector>

namespace unidist {
namespace {

namespace fs = std::filesystem;

// ------------------------------------------------------------------------------------------------ helpers

using unidist::testing::errorOf;

/// Little- or big-endian binary data, built value by value (the test machine is little endian).
struct Bytes {
  std::string data;
  bool big = false;
  template <class T>
  Bytes& put(T v) {
    char b[sizeof(T)];
    std::memcpy(b, &v, sizeof(T));
    if (big) std::reverse(b, b + sizeof(T));
    data.append(b, sizeof(T));
    return *this;
  }
};

// The unit cube [-0.5, 0.5]^3: 8 corners, 6 outward counter-clockwise quads (0-based).
const std::array<std::array<double, 3>, 8> kCube = {{{-0.5, -0.5, -0.5},
                                                     {0.5, -0.5, -0.5},
                                                     {0.5, 0.5, -0.5},
                                                     {-0.5, 0.5, -0.5},
                                                     {-0.5, -0.5, 0.5},
                                                     {0.5, -0.5, 0.5},
                                                     {0.5, 0.5, 0.5},
                                                     {-0.5, 0.5, 0.5}}};
const std::array<std::array<int, 4>, 6> kCubeQuads = {
    {{0, 3, 2, 1}, {4, 5, 6, 7}, {0, 1, 5, 4}, {3, 7, 6, 2}, {0, 4, 7, 3}, {1, 2, 6, 5}}};

/// The cube's 12 triangles (each quad split from its first corner).
std::vector<std::array<int, 3>> cubeTriangles() {
  std::vector<std::array<int, 3>> t;
  for (const auto& q : kCubeQuads) {
    t.push_back({q[0], q[1], q[2]});
    t.push_back({q[0], q[2], q[3]});
  }
  return t;
}

const TriangleMesh& asMesh(const std::shared_ptr<const Model>& m) {
  EXPECT_EQ(m->type(), ModelType::Mesh);
  return dynamic_cast<const TriangleMesh&>(*m);
}

const PointCloud& asCloud(const std::shared_ptr<const Model>& m) {
  EXPECT_EQ(m->type(), ModelType::PointCloud);
  return dynamic_cast<const PointCloud&>(*m);
}

double area(const TriangleMesh& m) {
  double a = 0;
  for (const auto& t : m.triangles())
    a += 0.5 * (m.vertices()[t[1]] - m.vertices()[t[0]]).cross(m.vertices()[t[2]] - m.vertices()[t[0]]).norm();
  return a;
}

/// The welded cube read from any format: 8 corners, 12 triangles, a solid of volume 1 with the right bounds.
void expectUnitCube(const std::shared_ptr<const Model>& model) {
  const TriangleMesh& m = asMesh(model);
  EXPECT_EQ(m.vertices().size(), 8u);
  EXPECT_EQ(m.triangles().size(), 12u);
  EXPECT_TRUE(m.isSolid());
  EXPECT_FALSE(m.stats().flipped);
  EXPECT_DOUBLE_EQ(m.stats().signedVolume, 1.0);
  EXPECT_DOUBLE_EQ(area(m), 6.0);
  EXPECT_EQ(m.localBounds().min, Eigen::Vector3d::Constant(-0.5));
  EXPECT_EQ(m.localBounds().max, Eigen::Vector3d::Constant(0.5));
  for (const Eigen::Vector3d& v : m.vertices()) EXPECT_EQ(v.cwiseAbs(), Eigen::Vector3d::Constant(0.5));
}

class Readers : public unidist::testing::ScratchFiles {
 protected:
  /// Loading `contents` as `name` fails with "<path>:<line>: ..." containing `fragment`.
  void expectLineError(const std::string& name, const std::string& contents, int line, const std::string& fragment) {
    expectLoadError(name, contents, ":" + std::to_string(line) + ": ", fragment);
  }

  /// Loading `contents` as `name` fails with "<path>: byte <offset>: ..." containing `fragment`.
  void expectByteError(const std::string& name, const std::string& contents, std::size_t offset,
                       const std::string& fragment) {
    expectLoadError(name, contents, ": byte " + std::to_string(offset) + ": ", fragment);
  }
};

// ---------------------------------------------------------------------------------------------------- OBJ

std::string cubeObjQuads() {
  std::string s = "# unit cube as quads\nmtllib cube.mtl\no cube\n";
  for (const auto& v : kCube)
    s += "v " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  s += "g sides\nusemtl grey\ns off\n";
  for (const auto& q : kCubeQuads)
    s += "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + " " + std::to_string(q[2] + 1) + " " +
         std::to_string(q[3] + 1) + "\n";
  return s;
}

TEST_F(Readers, ObjCubeOfQuadsIsASolid) {
  const auto model = loadModel(write("cube.obj", cubeObjQuads()));
  expectUnitCube(model);
  EXPECT_EQ(asMesh(model).stats().inputTriangles, 12u);
}

TEST_F(Readers, ObjTetrahedronWithRelativeIndicesAndCornerForms) {
  // Every corner form, negative indices, w and colour components, comments, CRLF and blank lines.
  const std::string text =
      "# tetrahedron\r\n"
      "v 0 0 0 1.0\r\n"
      "v 1e0 0 0 1 0.5 0.5\r\n"  // x y z r g b
      "v 0 +1 0 1 1 0 0\r\n"     // x y z w r g b
      "v 0 0 1.0 # trailing comment\r\n"
      "\r\n"
      "vt 0 0\r\nvt 1 0\r\nvt 0 1 0\r\n"
      "vn 0 0 -1\r\nvn 1 1 1\r\n"
      "vp 0.5\r\n"
      "f -4 -2 -3\r\n"                    // 1 3 2 (z = 0 face)
      "f 1/1 2/2 4/3\r\n"                 // v/vt
      "f 1//1 4//1 3//1\r\n"              // v//vn
      "f -3/-1/-1 -2/-2/-1 -1/-3/-2\r\n"  // 2 3 4 with v/vt/vn, relative
      "l 1 2\r\np 3\r\n";
  const auto model = loadModel(write("tet.obj", text));
  const TriangleMesh& m = asMesh(model);
  EXPECT_EQ(m.vertices().size(), 4u);
  EXPECT_EQ(m.triangles().size(), 4u);
  EXPECT_TRUE(m.isSolid());
  EXPECT_FALSE(m.stats().flipped);
  EXPECT_DOUBLE_EQ(m.stats().signedVolume, 1.0 / 6.0);
  const Eigen::Vector3d expected[] = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}};
  for (const Eigen::Vector3d& e : expected)
    EXPECT_NE(std::find(m.vertices().begin(), m.vertices().end(), e), m.vertices().end()) << e.transpose();
}

TEST_F(Readers, ObjPolygonIsAFanFromItsFirstCorner) {
  // A regular hexagon (convex): 4 triangles covering exactly its area; an open surface.
  std::string text;
  const double pi = std::acos(-1.0);
  for (int k = 0; k < 6; ++k)
    text += "v " + std::to_string(std::cos(k * pi / 3)) + " " + std::to_string(std::sin(k * pi / 3)) + " 0\n";
  text += "f 1 2 3 4 5 6\n";
  const auto model = loadModel(write("hexagon.obj", text));
  const TriangleMesh& m = asMesh(model);
  EXPECT_EQ(m.stats().inputTriangles, 4u);
  EXPECT_EQ(m.triangles().size(), 4u);
  EXPECT_FALSE(m.isSolid());
  for (std::size_t t = 0; t < 4; ++t) EXPECT_EQ(m.sourceTriangle(static_cast<int>(t)), t);
  double expectedArea = 0;  // the same 4 triangles from the printed (rounded) coordinates
  std::vector<Eigen::Vector3d> p;
  for (int k = 0; k < 6; ++k)
    p.emplace_back(std::stod(std::to_string(std::cos(k * pi / 3))), std::stod(std::to_string(std::sin(k * pi / 3))), 0);
  for (int k = 1; k < 5; ++k) expectedArea += 0.5 * (p[k] - p[0]).cross(p[k + 1] - p[0]).norm();
  EXPECT_NEAR(area(m), expectedArea, 1e-15);
  EXPECT_NEAR(area(m), 1.5 * std::sqrt(3.0), 1e-5);
}

TEST_F(Readers, ObjFacesMayComeBeforeTheirVertices) {
  std::string text;
  for (const auto& q : kCubeQuads)
    text += "f " + std::to_string(q[0] + 1) + " " + std::to_string(q[1] + 1) + " " + std::to_string(q[2] + 1) + " " +
            std::to_string(q[3] + 1) + "\n";
  for (const auto& v : kCube)
    text += "v " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  expectUnitCube(loadModel(write("forward.obj", text)));
}

TEST_F(Readers, ObjCountLineAsInFclMeshes) {
  std::string text = "8 6\n" + cubeObjQuads();
  expectUnitCube(loadModel(write("counted.obj", text)));
  expectLineError("miscounted.obj", "8 7\n" + cubeObjQuads(), 1, "count line says 8 vertices and 7 faces");
}

TEST_F(Readers, ObjOpenSurfaceIsNotASolid) {
  // The cube without its top: five quads, boundary edges.
  std::string text;
  for (const auto& v : kCube)
    text += "v " + std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + "\n";
  for (int f = 0; f < 6; ++f)
    if (f != 1)
      text += "f " + std::to_string(kCubeQuads[f][0] + 1) + " " + std::to_string(kCubeQuads[f][1] + 1) + " " +
              std::to_string(kCubeQuads[f][2] + 1) + " " + std::to_string(kCubeQuads[f][3] + 1) + "\n";
  const auto mModel = loadModel(write("box.obj", text));
  const TriangleMesh& m = asMesh(mModel);
  EXPECT_FALSE(m.isSolid());
  EXPECT_EQ(m.triangles().size(), 10u);
  EXPECT_EQ(m.stats().boundaryEdges, 4u);
}

TEST_F(Readers, MalformedObj) {
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  expectLineError("empty.obj", "", 1, "empty file");
  expectLineError("junk.obj", "v 0 0 0\nv 1.0abc 0 0\nv 0 1 0\nf 1 2 3\n", 2, "'1.0abc' is not a number");
  expectLineError("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n", 3, "'nan' is not a number");
  expectLineError("nan2.obj", tri + "v NaN 0 0\nf 1 2 4\n", 4, "'NaN' is not a number");
  expectLineError("inf.obj", "v inf 0 0\n" + tri + "f 2 3 4\n", 1, "'inf' is not a number");
  expectLineError("huge.obj", "v 1e999 0 0\n" + tri + "f 2 3 4\n", 1, "out of range");
  expectLineError("hex.obj", "v 0x10 0 0\n" + tri + "f 2 3 4\n", 1, "'0x10' is not a number");
  expectLineError("comma.obj", "v 1,5 0 0\n" + tri + "f 2 3 4\n", 1, "'1,5' is not a number");
  expectLineError("short.obj", "v 0 0\n" + tri, 1, "z coordinate is missing");
  expectLineError("long.obj", "v 0 0 0 1 2 3 4 5\n" + tri, 1, "at most 7 values");
  expectLineError("five.obj", "v 0 0 0 1 2\n" + tri, 1, "not 5");
  expectLineError("range.obj", tri + "f 1 2 3\nf 1 2 4\n", 5, "vertex index 4 is out of range: the file defines 3");
  expectLineError("range_fwd.obj", "f 1 2 3\n" + tri + "f 1 2 9\nf 1 3 2\n", 5, "vertex index 9 is out of range");
  expectLineError("negative.obj", tri + "f -1 -2 -4\n", 4, "is -4, but only 3 vertex(s)");
  expectLineError("zero.obj", tri + "f 0 1 2\n", 4, "is 0 (OBJ indices start at 1");
  expectLineError("two.obj", tri + "f 1 2\n", 4, "at least 3 corners, this one has 2");
  expectLineError("float_index.obj", tri + "f 1 2 3.0\n", 4, "'3.0' is not an integer");
  expectLineError("big_index.obj", tri + "f 1 2 99999999999999999999\n", 4, "out of range");
  expectLineError("vt_range.obj", tri + "vt 0 0\nf 1/1 2/2 3/1\n", 5, "texture coordinate index 2 is out of range");
  expectLineError("vn_range.obj", tri + "f 1//1 2//1 3//1\n", 4, "normal index 1 is out of range");
  expectLineError("slashes.obj", tri + "f 1/1/1/1 2 3\n", 4, "more than three '/'-separated parts");
  expectLineError("trailing_slash.obj", tri + "vt 0 0\nf 1/ 2 3\n", 5, "ends with '/'");
  expectLineError("no_vertex.obj", tri + "f /1 2 3\n", 4, "has no vertex index");
  expectLineError("vt_junk.obj", tri + "vt 0 zero\nf 1 2 3\n", 4, "'zero' is not a number");
  expectLineError("vn_short.obj", tri + "vn 0 1\nf 1 2 3\n", 4, "at least 3 value");
  expectLineError("statement.obj", tri + "f 1 2 3\nthis is not obj\n", 5, "unknown OBJ statement 'this'");
  expectLineError("freeform.obj", tri + "curv 0 1 1 2\n", 4, "free-form geometry ('curv')");
  expectLineError("continuation.obj", "v 0 0 \\\n0\n" + tri, 1, "line continuation");
  expectLineError("no_faces.obj", "# points only\n" + tri, 4, "no faces");
  expectLineError("comments_only.obj", "# nothing\n\n# here\n", 3, "no faces");
  expectLineError("binary.obj", std::string("v 0 0 0\n\x01\x02\x00\xff", 12) + "\n", 2,
                  "unknown OBJ statement '\\x01\\x02\\x00\\xFF'");
  // Valid syntax, but nothing with an area is left: the model's message, prefixed with the file.
  const std::string path = write("flat.obj", "v 0 0 0\nv 1 0 0\nv 2 0 0\nf 1 2 3\n");
  const std::string msg = errorOf([&] { loadModel(path); });
  EXPECT_EQ(msg.rfind(path + ": ", 0), 0u) << msg;
  EXPECT_NE(msg.find("non-zero area"), std::string::npos) << msg;
}

// ---------------------------------------------------------------------------------------------------- STL

std::string cubeStlAscii(bool upper = false) {
  std::string s = upper ? "SOLID cube\n" : "solid cube\n";
  for (const auto& t : cubeTriangles()) {
    s += upper ? "FACET NORMAL 0 0 0\n  OUTER LOOP\n" : "  facet normal 0 0 0\n    outer loop\n";
    for (int i : t)
      s += std::string(upper ? "VERTEX " : "      vertex ") + std::to_string(kCube[i][0]) + " " +
           std::to_string(kCube[i][1]) + " " + std::to_string(kCube[i][2]) + "\n";
    s += upper ? "ENDLOOP\nENDFACET\n" : "    endloop\n  endfacet\n";
  }
  return s + (upper ? "ENDSOLID cube\n" : "endsolid cube\n");
}

std::string cubeStlBinary(const std::string& header) {
  Bytes b;
  std::string h = header;
  h.resize(80, ' ');
  b.data = h;
  const auto tris = cubeTriangles();
  b.put<std::uint32_t>(static_cast<std::uint32_t>(tris.size()));
  for (const auto& t : tris) {
    for (int k = 0; k < 3; ++k) b.put<float>(0.0f);
    for (int i : t)
      for (int k = 0; k < 3; ++k) b.put<float>(static_cast<float>(kCube[i][k]));
    b.put<std::uint16_t>(0);
  }
  return b.data;
}

TEST_F(Readers, StlAsciiCube) {
  expectUnitCube(loadModel(write("cube.stl", cubeStlAscii())));
  expectUnitCube(loadModel(write("cube_upper.stl", cubeStlAscii(true))));
  // Keywords split over lines differently, and two solids in one file.
  std::string text =
      "solid\nfacet normal 0 0 -1 outer loop vertex 0 0 0 vertex 0 1 0 vertex 1 0 0 endloop endfacet\nendsolid\n"
      "solid second\nfacet normal 0 0 0\nouter loop\nvertex 0 0 0\nvertex 1 0 0\nvertex 0 0 "
      "1\nendloop\nendfacet\nendsolid second";
  const auto mModel = loadModel(write("two.stl", text));
  const TriangleMesh& m = asMesh(mModel);
  EXPECT_EQ(m.triangles().size(), 2u);
  EXPECT_EQ(m.vertices().size(), 4u);  // welded
  EXPECT_FALSE(m.isSolid());
}

TEST_F(Readers, StlBinaryCube) {
  const std::string data = cubeStlBinary("binary cube");
  ASSERT_EQ(data.size(), 84u + 50u * 12u);
  expectUnitCube(loadModel(write("cube_bin.stl", data)));
}

TEST_F(Readers, StlBinaryWhoseHeaderSaysSolid) {
  // Seen in the wild: a binary file whose header starts with "solid"; the exact size decides.
  expectUnitCube(loadModel(write("solid_header.stl", cubeStlBinary("solid cube exported as binary"))));
}

TEST_F(Readers, MalformedBinaryStl) {
  const std::string good = cubeStlBinary("binary");
  expectByteError("empty.stl", "", 0, "empty file");
  expectByteError("short.stl", "abc", 3, "truncated binary STL");
  expectByteError("header_only.stl", good.substr(0, 60), 60, "truncated binary STL");
  // Cut in the middle of triangle 5: the offset is where that triangle starts.
  expectByteError("truncated.stl", good.substr(0, 84 + 50 * 5 + 17), 84 + 50 * 5, "inside triangle 5");
  expectByteError("truncated_solid.stl", cubeStlBinary("solid but binary").substr(0, 84 + 50 * 3 + 1), 84 + 50 * 3,
                  "truncated binary STL");
  expectByteError("extra.stl", good + "xyz", 84 + 50 * 12, "3 unexpected bytes after the 12 triangles");
  std::string zero = good.substr(0, 84);
  zero[80] = zero[81] = zero[82] = zero[83] = 0;
  expectByteError("zero.stl", zero, 80, "declares 0 triangles");
  // NaN in triangle 1, vertex 2, y: offset 84 + 50 + 12 (normal) + 2·12 + 4.
  std::string nan = good;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan[84 + 50 + 12 + 24 + 4], &q, 4);
  expectByteError("nan.stl", nan, 84 + 50 + 12 + 24 + 4, "triangle 1, vertex 2: coordinate is NaN");
  std::string inf = good;
  const float i = std::numeric_limits<float>::infinity();
  std::memcpy(&inf[84 + 12], &i, 4);
  expectByteError("inf.stl", inf, 84 + 12, "triangle 0, vertex 0: coordinate is infinite");
}

TEST_F(Readers, MalformedAsciiStl) {
  const std::string head = "solid t\nfacet normal 0 0 1\nouter loop\n";
  const std::string tail = "endloop\nendfacet\nendsolid t\n";
  const std::string v3 = "vertex 0 0 0\nvertex 1 0 0\nvertex 0 1 0\n";
  expectLineError("junk.stl", head + "vertex 0 0 0\nvertex 1 0 zero\nvertex 0 1 0\n" + tail, 5,
                  "'zero' is not a number");
  expectLineError("nan.stl", head + "vertex 0 0 0\nvertex nan 0 0\nvertex 0 1 0\n" + tail, 5, "'nan' is not a number");
  expectLineError("suffix.stl", head + "vertex 0 0 0\nvertex 1.0abc 0 0\nvertex 0 1 0\n" + tail, 5, "'1.0abc'");
  expectLineError("normal.stl", "solid t\nfacet normal 0 x 1\nouter loop\n" + v3 + tail, 2, "'x' is not a number");
  expectLineError("four.stl", head + v3 + "vertex 1 1 0\n" + tail, 7, "more than 3 vertices");
  expectLineError("two.stl", head + "vertex 0 0 0\nvertex 1 0 0\n" + tail, 6,
                  "expected 'vertex' (a facet has exactly 3)");
  expectLineError("no_loop.stl", "solid t\nfacet normal 0 0 1\n" + v3 + tail, 3, "expected 'outer'");
  expectLineError("no_endsolid.stl", head + v3 + "endloop\nendfacet\n", 8, "'endsolid' is missing");
  expectLineError("cut.stl", head + "vertex 0 0 0\nvertex 1 0", 5, "end of file where vertex z was expected");
  expectLineError("keyword.stl",
                  "solid t\nfacet normal 0 0 1\nouter loop\n" + v3 + "endloop\nendfacet\nfacets\nendsolid\n", 9,
                  "expected 'facet' or 'endsolid', found 'facets'");
  expectLineError("empty_solid.stl", "solid nothing\nendsolid nothing\n", 2, "no facets");
  expectLineError("after.stl", head + v3 + tail + "garbage\n", 10, "expected 'solid' or the end of the file");
}

// ---------------------------------------------------------------------------------------------------- PLY

enum class PlyEncoding { Ascii, Little, Big };

/// The cube as PLY with quads, colours (ignored) and an extra element, in any encoding.
std::string cubePly(PlyEncoding enc, const char* coordType = "float", const char* indexType = "int") {
  const char* format = enc == PlyEncoding::Ascii    ? "ascii"
                       : enc == PlyEncoding::Little ? "binary_little_endian"
                                                    : "binary_big_endian";
  std::string s = std::string("ply\nformat ") + format + " 1.0\ncomment unit cube\nobj_info test\n" +
                  "element vertex 8\nproperty " + coordType + " x\nproperty " + coordType + " y\nproperty " +
                  coordType + " z\nproperty uchar red\nproperty uchar green\nproperty uchar blue\n" +
                  "element face 6\nproperty list uchar " + indexType + " vertex_indices\nproperty uchar flags\n" +
                  "element edge 1\nproperty int vertex1\nproperty int vertex2\nend_header\n";
  const bool dbl = std::string(coordType) == "double" || std::string(coordType) == "float64";
  const bool uintIdx = std::string(indexType) == "uint";
  if (enc == PlyEncoding::Ascii) {
    for (const auto& v : kCube)
      s += std::to_string(v[0]) + " " + std::to_string(v[1]) + " " + std::to_string(v[2]) + " 255 128 0\n";
    for (const auto& q : kCubeQuads)
      s += "4 " + std::to_string(q[0]) + " " + std::to_string(q[1]) + " " + std::to_string(q[2]) + " " +
           std::to_string(q[3]) + " 7\n";
    return s + "0 1\n";
  }
  Bytes b;
  b.big = enc == PlyEncoding::Big;
  for (const auto& v : kCube) {
    for (double c : v) dbl ? (void)b.put<double>(c) : (void)b.put<float>(static_cast<float>(c));
    b.put<std::uint8_t>(255).put<std::uint8_t>(128).put<std::uint8_t>(0);
  }
  for (const auto& q : kCubeQuads) {
    b.put<std::uint8_t>(4);
    for (int i : q) uintIdx ? (void)b.put<std::uint32_t>(static_cast<std::uint32_t>(i)) : (void)b.put<std::int32_t>(i);
    b.put<std::uint8_t>(7);
  }
  b.put<std::int32_t>(0).put<std::int32_t>(1);
  return s + b.data;
}

TEST_F(Readers, PlyCubeInEveryEncoding) {
  expectUnitCube(loadModel(write("cube_ascii.ply", cubePly(PlyEncoding::Ascii))));
  expectUnitCube(loadModel(write("cube_le.ply", cubePly(PlyEncoding::Little))));
  expectUnitCube(loadModel(write("cube_be.ply", cubePly(PlyEncoding::Big))));
  expectUnitCube(loadModel(write("cube_be_double.ply", cubePly(PlyEncoding::Big, "double", "uint"))));
  expectUnitCube(loadModel(write("cube_le_double.ply", cubePly(PlyEncoding::Little, "float64", "uint"))));
  expectUnitCube(loadModel(write("cube_ascii_int.ply", cubePly(PlyEncoding::Ascii, "double", "uint"))));
}

TEST_F(Readers, PlyWithoutFacesIsAPointCloudWithNormals) {
  const std::string header =
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\n"
      "element face 0\nproperty list uchar int vertex_indices\nend_header\n";
  const auto cModel = loadModel(write("cloud.ply", header + "1 2 3 0 0 2\n-1 0.5 1e-3 1 0 0\n0 0 0 0 0 0\n"));
  const PointCloud& c = asCloud(cModel);
  ASSERT_EQ(c.points().size(), 3u);
  EXPECT_EQ(c.points()[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(c.points()[1], Eigen::Vector3d(-1, 0.5, 1e-3));
  ASSERT_EQ(c.normals().size(), 3u);
  EXPECT_EQ(c.normals()[0], Eigen::Vector3d(0, 0, 1));  // normalised
  EXPECT_EQ(c.normals()[2], Eigen::Vector3d::Zero());   // "no normal"

  // Binary big endian, no normals, no face element.
  Bytes b;
  b.big = true;
  b.put<double>(0.25).put<double>(-0.5).put<double>(0.125).put<double>(1).put<double>(2).put<double>(3);
  const auto dModel =
      loadModel(write("cloud_be.ply",
                      "ply\nformat binary_big_endian 1.0\nelement vertex 2\nproperty double x\nproperty double y\n"
                      "property double z\nend_header\n" +
                          b.data));
  const PointCloud& d = asCloud(dModel);
  ASSERT_EQ(d.points().size(), 2u);
  EXPECT_EQ(d.points()[0], Eigen::Vector3d(0.25, -0.5, 0.125));
  EXPECT_EQ(d.points()[1], Eigen::Vector3d(1, 2, 3));
  EXPECT_TRUE(d.normals().empty());

  // Binary little endian with normals.
  Bytes l;
  l.put<float>(1).put<float>(2).put<float>(3).put<float>(0).put<float>(3).put<float>(4);
  const auto eModel =
      loadModel(write("cloud_le.ply",
                      "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                      "property float z\nproperty float nx\nproperty float ny\nproperty float nz\nend_header\n" +
                          l.data));
  const PointCloud& e = asCloud(eModel);
  EXPECT_EQ(e.points()[0], Eigen::Vector3d(1, 2, 3));
  ASSERT_EQ(e.normals().size(), 1u);
  EXPECT_NEAR((e.normals()[0] - Eigen::Vector3d(0, 0.6, 0.8)).norm(), 0, 1e-15);
}

const char* const kTriHeader =
    "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
    "element face 1\nproperty list uchar int vertex_indices\nend_header\n";  // 9 header lines

TEST_F(Readers, MalformedPlyHeader) {
  const std::string tri = "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n";
  expectLineError("empty.ply", "", 1, "empty file");
  expectLineError("magic.ply", "plyx\nformat ascii 1.0\n", 1, "not a PLY file");
  expectLineError("format.ply", "ply\nformat binary 1.0\nend_header\n", 2, "unknown PLY format 'binary'");
  expectLineError("version.ply", "ply\nformat ascii 2.0\nend_header\n", 2, "unsupported PLY version '2.0'");
  expectLineError("no_format.ply", "ply\nelement vertex 1\nproperty float x\nend_header\n0\n", 4, "no 'format' line");
  // No end_header: the first data line is reported, with the likely cause.
  expectLineError(
      "no_end.ply",
      "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n" + tri, 7,
      "is 'end_header' missing?");
  expectLineError("no_end_eof.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\n", 4,
                  "the 'end_header' line is missing");
  expectLineError("type.ply", "ply\nformat ascii 1.0\nelement vertex 3\nproperty float3 x\nend_header\n", 4,
                  "unknown property type 'float3'");
  expectLineError("list_count.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list float int vertex_indices\nend_header\n" +
                      tri,
                  8, "unsupported list count type 'float'");
  expectLineError("list_double.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list double int vertex_indices\nend_header\n" +
                      tri,
                  8, "unsupported list count type 'double'");
  expectLineError("float_indices.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty list uchar float vertex_indices\nend_header\n" +
                      tri,
                  8, "vertex indices must be an integer type");
  expectLineError("scalar_indices.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty int vertex_indices\nend_header\n" +
                      tri,
                  8, "must be a list");
  expectLineError("list_x.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty list uchar float x\nproperty float y\n"
                  "property float z\nend_header\n1 0 0 0\n1 1 0 0\n1 0 1 0\n",
                  4, "vertex property 'x' is a list");
  expectLineError("no_z.ply",
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nend_header\n0 0\n", 3,
                  "no 'z' property");
  expectLineError("no_vertex.ply", "ply\nformat ascii 1.0\nelement point 1\nproperty float x\nend_header\n0\n", 5,
                  "no 'vertex' element");
  expectLineError("partial_normals.ply",
                  "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\n"
                  "property float nx\nend_header\n0 0 0 1\n",
                  3, "only some of nx, ny, nz");
  expectLineError("no_index_list.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element face 1\nproperty uchar flags\nend_header\n0 0 0\n1 0 0\n0 1 0\n1\n",
                  7, "no 'vertex_indices' list");
  expectLineError("dup_prop.ply", "ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float x\n", 5,
                  "a second property named 'x'");
  expectLineError("dup_elem.ply", "ply\nformat ascii 1.0\nelement vertex 1\nelement vertex 1\n", 4,
                  "a second element named 'vertex'");
  expectLineError("count.ply", "ply\nformat ascii 1.0\nelement vertex -1\n", 3, "out of range");
  expectLineError("count_text.ply", "ply\nformat ascii 1.0\nelement vertex many\n", 3, "'many' is not an integer");
  expectLineError("orphan.ply", "ply\nformat ascii 1.0\nproperty float x\n", 3, "'property' before any 'element'");
  expectLineError("no_properties.ply",
                  "ply\nformat binary_little_endian 1.0\nelement vertex 1\nproperty float x\nproperty float y\n"
                  "property float z\nelement nothing 4000000000\nend_header\n" +
                      std::string(12, '\0'),
                  7, "element 'nothing' has entries but no properties");
  expectLineError("strips.ply",
                  "ply\nformat ascii 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\n"
                  "element tristrips 1\nproperty list int int vertex_indices\nend_header\n0 0 0\n1 0 0\n0 1 0\n"
                  "3 0 1 2\n",
                  7, "triangle strips ('tristrips') are not supported");
  expectLineError(
      "zero_vertices.ply",
      "ply\nformat ascii 1.0\nelement vertex 0\nproperty float x\nproperty float y\nproperty float z\nend_header\n", 3,
      "0 entries");
}

TEST_F(Readers, MalformedAsciiPlyData) {
  const std::string h = kTriHeader;  // data starts on line 10
  EXPECT_EQ(asMesh(loadModel(write("good.ply", h + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n"))).triangles().size(), 1u);
  expectLineError("junk.ply", h + "0 0 0\n1 0 zero\n0 1 0\n3 0 1 2\n", 11, "'zero' is not a number");
  expectLineError("nan.ply", h + "0 0 0\n1 0 0\nnan 1 0\n3 0 1 2\n", 12, "'nan' is not a number");
  expectLineError("inf.ply", h + "0 0 0\n1 0 -inf\n0 1 0\n3 0 1 2\n", 11, "'-inf' is not a number");
  expectLineError("index.ply", h + "0 0 0\n1 0 0\n0 1 0\n3 0 1 3\n", 13, "vertex index 3 is out of range");
  expectLineError("neg_index.ply", h + "0 0 0\n1 0 0\n0 1 0\n3 0 -1 2\n", 13, "vertex index -1 is out of range");
  expectLineError("float_index.ply", h + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2.5\n", 13, "'2.5' is not an integer");
  expectLineError("list_range.ply", h + "0 0 0\n1 0 0\n0 1 0\n256 0 1 2\n", 13, "out of range [0, 255]");
  expectLineError("two_corners.ply", h + "0 0 0\n1 0 0\n0 1 0\n2 0 1\n", 13, "face 0 has 2 vertices");
  // The header lies: it declares more vertices than there are (the face line is read as a vertex) ...
  const std::string more =
      "ply\nformat ascii 1.0\nelement vertex 4\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expectLineError("lie_more.ply", more + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 13,
                  "does the header's count match the data?");
  // ... or fewer faces than there are, or fewer vertices, or more faces.
  expectLineError("lie_extra.ply", h + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n", 14, "data after the last entry");
  const std::string fewer =
      "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\nproperty float z\n"
      "element face 1\nproperty list uchar int vertex_indices\nend_header\n";
  expectLineError("lie_fewer.ply", fewer + "0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n", 12, "face 0 has 0 vertices");
  expectLineError("lie_faces.ply", h + "0 0 0\n1 0 0\n0 1 0\n", 12, "end of file after 0 of the 1 'face' entries");
  expectLineError("short_line.ply", h + "0 0 0\n1 0\n0 1 0\n3 0 1 2\n", 11, "the line ends before property 'z'");
  expectLineError("short_list.ply", h + "0 0 0\n1 0 0\n0 1 0\n3 0 1\n", 13,
                  "the line ends before property 'vertex_indices'");
}

TEST_F(Readers, MalformedBinaryPlyData) {
  const std::string header =
      "ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\n"
      "property float z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";
  const std::size_t d = header.size();
  Bytes b;
  for (float v : {0.f, 0.f, 0.f, 1.f, 0.f, 0.f, 0.f, 1.f, 0.f}) b.put<float>(v);
  b.put<std::uint8_t>(3).put<std::int32_t>(0).put<std::int32_t>(1).put<std::int32_t>(2);
  const std::string good = header + b.data;  // 36 bytes of vertices, 13 of the face
  EXPECT_EQ(asMesh(loadModel(write("good_le.ply", good))).triangles().size(), 1u);

  // Cut inside the face's index list: the list's length is where the data stops adding up.
  expectByteError("truncated.ply", good.substr(0, d + 36 + 6), d + 36, "has 3 items, more than the 5 bytes left hold");
  expectByteError("truncated_vertex.ply", good.substr(0, d + 14), d + 12, "vertex 1 (of 3), property 'x'");
  expectByteError("extra.ply", good + "\n", d + 49, "1 bytes after the last entry");
  // The header declares 4 vertices: the face's first 12 bytes become vertex 3, and its last byte (the top
  // byte of index 2, zero) is read as the face's corner count.
  std::string lie = good;
  lie.replace(lie.find("vertex 3"), 8, "vertex 4");
  expectByteError("lie.ply", lie, d + 48, "face 0 has 0 vertices");
  // Index 5 in the face: its offset is d + 36 + 1 + 2·4.
  std::string index = good;
  const std::int32_t five = 5;
  std::memcpy(&index[d + 36 + 9], &five, 4);
  expectByteError("index.ply", index, d + 36 + 9, "vertex index 5 is out of range");
  std::string negative = good;
  const std::int32_t minus = -1;
  std::memcpy(&negative[d + 36 + 1], &minus, 4);
  expectByteError("negative.ply", negative, d + 37, "vertex index -1 is out of range");
  std::string nan = good;
  const float q = std::numeric_limits<float>::quiet_NaN();
  std::memcpy(&nan[d + 12 + 8], &q, 4);
  expectByteError("nan.ply", nan, d + 20, "vertex 1 (of 3): z is NaN");
  std::string count = good;
  count[d + 36] = 2;
  expectByteError("two.ply", count, d + 36, "face 0 has 2 vertices");
  std::string huge = good;
  huge[d + 36] = static_cast<char>(200);
  expectByteError("huge_list.ply", huge, d + 36, "has 200 items, more than the 12 bytes left hold");
  // A big-endian file read right only when swapped: the same bytes declared little endian lie elsewhere.
  std::string bigHeader = header;
  bigHeader.replace(bigHeader.find("little"), 6, "big");
  expectByteError("wrong_endian.ply", bigHeader + b.data, d - 3 + 41, "vertex index 16777216 is out of range");
  // Header promises a million vertices: no huge allocation, an error where the data ends.
  std::string million = good;
  million.replace(million.find("vertex 3"), 8, "vertex 1000000");
  expectByteError("million.ply", million, d + 6 + 48, "unexpected end of file in vertex 4 (of 1000000)");
}

// ---------------------------------------------------------------------------------------------------- XYZ

TEST_F(Readers, XyzSeparatorsCommentsAndNormals) {
  const std::string text =
      "# scanned points\n"
      "1 2 3\n"
      "\n"
      "4.5\t-5\t6e-1   # tab separated\n"
      "7,8,9\n"
      "  -1 , +2 ,3.25  \r\n"
      "\t\n";
  const auto cModel = loadModel(write("plain.xyz", text));
  const PointCloud& c = asCloud(cModel);
  ASSERT_EQ(c.points().size(), 4u);
  EXPECT_EQ(c.points()[0], Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(c.points()[1], Eigen::Vector3d(4.5, -5, 0.6));
  EXPECT_EQ(c.points()[2], Eigen::Vector3d(7, 8, 9));
  EXPECT_EQ(c.points()[3], Eigen::Vector3d(-1, 2, 3.25));
  EXPECT_TRUE(c.normals().empty());
  EXPECT_FALSE(c.isSolid());

  const auto nModel = loadModel(write("normals.xyz", "0 0 1 0 0 2\n1,0,0,3,0,0\n0\t1\t0\t0\t0\t0\n"));
  const PointCloud& n = asCloud(nModel);
  ASSERT_EQ(n.points().size(), 3u);
  ASSERT_EQ(n.normals().size(), 3u);
  EXPECT_EQ(n.normals()[0], Eigen::Vector3d(0, 0, 1));
  EXPECT_EQ(n.normals()[1], Eigen::Vector3d(1, 0, 0));
  EXPECT_EQ(n.normals()[2], Eigen::Vector3d::Zero());
}

TEST_F(Readers, MalformedXyz) {
  expectLineError("empty.xyz", "", 1, "empty file");
  expectLineError("comments.xyz", "# a\n\n# b\n", 3, "no points");
  expectLineError("two.xyz", "1 2 3\n1 2\n", 2, "2 values");
  expectLineError("four.xyz", "1 2 3 4\n", 1, "4 values");
  expectLineError("seven.xyz", "1 2 3 4 5 6 7\n", 1, "more than 6 values");
  expectLineError("mixed.xyz", "1 2 3\n4 5 6\n1 2 3 0 0 1\n", 3, "6 values, but the first point (line 1) has 3");
  expectLineError("header.xyz", "x,y,z\n1,2,3\n", 1, "x: 'x' is not a number");
  expectLineError("empty_field.xyz", "1,,2,3\n", 1, "empty value");
  expectLineError("leading_comma.xyz", "1 2 3\n,1,2,3\n", 2, "empty value");
  expectLineError("trailing_comma.xyz", "1 2 3\n1,2,3,\n", 2, "a ',' ends the line");
  expectLineError("nan.xyz", "1 2 3\n1 nan 3\n", 2, "y: 'nan' is not a number");
  expectLineError("inf.xyz", "1 2 3\n1 2 inf\n", 2, "z: 'inf' is not a number");
  expectLineError("junk.xyz", "1 2 3\n1 2 3.0abc\n", 2, "'3.0abc' is not a number");
  expectLineError("normal_nan.xyz", "1 2 3 0 0 1\n1 2 3 0 NaN 1\n", 2, "ny: 'NaN' is not a number");
}

// --------------------------------------------------------------------------------------- shared models

const fs::path kModels = fs::path(UNIDIST_SHARED_DIR) / "acceptance" / "models";
const fs::path kFcl = fs::path(UNIDIST_SHARED_DIR) / "data" / "fcl";

/// The shared file, or an empty path when the shared directory is not there.
fs::path sharedFile(const fs::path& dir, const char* name) { return fs::exists(dir / name) ? dir / name : fs::path(); }

TEST(SharedModels, AcceptanceMeshesLoad) {
  const struct {
    const char* name;
    std::size_t triangles;
    bool solid;
  } cases[] = {{"cube.obj", 12, true},        {"lshape.obj", 20, true},     {"icosphere_320.obj", 320, true},
               {"icosphere.stl", 1280, true}, {"torus_1k.obj", 1024, true}, {"torus_20k.obj", 0, true}};
  bool any = false;
  for (const auto& c : cases) {
    SCOPED_TRACE(c.name);
    const fs::path p = sharedFile(kModels, c.name);
    if (p.empty()) continue;
    any = true;
    const auto start = std::chrono::steady_clock::now();
    const auto model = loadModel(p.string());
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    const TriangleMesh& m = asMesh(model);
    if (c.triangles) {
      EXPECT_EQ(m.triangles().size(), c.triangles);
    }
    EXPECT_EQ(m.isSolid(), c.solid);
    EXPECT_EQ(m.stats().droppedZeroArea + m.stats().droppedDuplicate, 0u);
    std::printf("  %-20s %7zu triangles %6zu vertices  %s  loaded in %.1f ms\n", c.name, m.triangles().size(),
                m.vertices().size(), m.isSolid() ? "solid" : "open", ms);
  }
  if (!any) GTEST_SKIP() << "shared acceptance models not found at " << kModels;
}

TEST(SharedModels, AcceptanceCloudsLoad) {
  const fs::path single = sharedFile(kModels, "single_point.xyz");
  if (single.empty()) GTEST_SKIP() << "shared acceptance models not found at " << kModels;
  const auto sModel = loadModel(single.string());
  const PointCloud& s = asCloud(sModel);
  ASSERT_EQ(s.points().size(), 1u);
  EXPECT_EQ(s.points()[0], Eigen::Vector3d(0.25, -0.5, 0.125));
  EXPECT_TRUE(s.normals().empty());

  for (const char* name : {"sphere_cloud.xyz", "torus_cloud.xyz"}) {
    SCOPED_TRACE(name);
    const fs::path p = sharedFile(kModels, name);
    ASSERT_FALSE(p.empty());
    std::ifstream in(p);
    std::size_t lines = 0, columns = 0;
    for (std::string line; std::getline(in, line);)
      if (!line.empty() && line[0] != '#') {
        ++lines;
        if (columns == 0) columns = static_cast<std::size_t>(std::count(line.begin(), line.end(), ' ')) + 1;
      }
    const auto cModel = loadModel(p.string());
    const PointCloud& c = asCloud(cModel);
    EXPECT_EQ(c.points().size(), lines);
    EXPECT_EQ(c.normals().size(), columns == 6 ? lines : 0u);
  }
}

TEST(SharedModels, MalformedObjNamesFileAndLine) {
  const fs::path p = sharedFile(kModels, "malformed.obj");
  if (p.empty()) GTEST_SKIP() << "shared acceptance models not found at " << kModels;
  const std::string msg = errorOf([&] { loadModel(p.string()); });
  EXPECT_EQ(msg, p.string() + ":3: z coordinate: 'zero' is not a number");
}

TEST(SharedModels, FclBenchmarkMeshesLoad) {
  const fs::path env = sharedFile(kFcl, "env.obj"), rob = sharedFile(kFcl, "rob.obj");
  if (env.empty() || rob.empty()) GTEST_SKIP() << "FCL meshes not found at " << kFcl;
  const auto eModel = loadModel(env.string());
  const TriangleMesh& e = asMesh(eModel);
  const auto rModel = loadModel(rob.string());
  const TriangleMesh& r = asMesh(rModel);
  EXPECT_EQ(e.stats().inputTriangles, 2180u);
  EXPECT_EQ(e.stats().inputVertices, 6540u);
  EXPECT_EQ(r.stats().inputTriangles, 216u);
  EXPECT_EQ(r.stats().inputVertices, 648u);
  EXPECT_LT(e.vertices().size(), 6540u);  // triangle soup, welded
  EXPECT_GT(e.localBounds().diagonal(), 6000);
  std::printf("  env.obj: %zu triangles kept, %zu vertices, %s; rob.obj: %zu triangles, %zu vertices, %s\n",
              e.triangles().size(), e.vertices().size(), e.isSolid() ? "solid" : "open", r.triangles().size(),
              r.vertices().size(), r.isSolid() ? "solid" : "open");
}

}  // namespace
}  // namespace unidist
