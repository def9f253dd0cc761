// NURBS readers: .unurbs.json and IGES (entity 128, with entity 124 transformations) read right, and every class
// of malformed file rejected with an InputError naming the file and the JSON path, byte or line of the problem.
#include "../core/nurbs_fixtures.h"
#include "error_of.h"
#include "scratch_files.h"
#include "unidist/adapters/load.h"
#include "unidist/nurbs.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <functional>
#include <vector>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace unidist {
namespace {

namespace fs = std::filesystem;
using testing::errorOf;

const fs::path kFixtures = fs::path(UNIDIST_NURBS_DATA_DIR);
const fs::path kModels = fs::path(UNIDIST_SHARED_DIR) / "acceptance" / "models";

std::string readText(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

const NurbsModel& asNurbs(const std::shared_ptr<const Model>& m) {
  const auto* n = dynamic_cast<const NurbsModel*>(m.get());
  if (!n) throw std::runtime_error("not a NURBS model");
  return *n;
}

/// JSON text of a model made of one surface.
std::string toJson(const NurbsSurface& s, bool solid) {
  std::ostringstream o;
  o.precision(17);
  auto list = [&](const std::vector<double>& v) {
    o << "[";
    for (std::size_t k = 0; k < v.size(); ++k) o << (k ? "," : "") << v[k];
    o << "]";
  };
  o << "{\"type\":\"nurbs\",\"solid\":" << (solid ? "true" : "false") << ",\"surfaces\":[{\"degree_u\":" << s.degreeU()
    << ",\"degree_v\":" << s.degreeV() << ",\"knots_u\":";
  list(s.knotsU());
  o << ",\"knots_v\":";
  list(s.knotsV());
  o << ",\"control_points\":[";
  for (int i = 0; i < s.countU(); ++i) {
    o << (i ? "," : "") << "[";
    for (int j = 0; j < s.countV(); ++j) {
      const Eigen::Vector4d c = s.controlPoint(i, j);
      o << (j ? "," : "") << "[" << c[0] << "," << c[1] << "," << c[2] << "," << c[3] << "]";
    }
    o << "]";
  }
  o << "]}]}";
  return o.str();
}

std::string replaceOnce(std::string text, const std::string& from, const std::string& to) {
  const std::size_t at = text.find(from);
  EXPECT_NE(at, std::string::npos) << "fixture edit: '" << from << "' not found";
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

class NurbsReaders : public unidist::testing::ScratchFiles {
 protected:
  void expectError(const std::string& name, const std::string& contents, const std::string& where,
                   const std::string& fragment) {
    expectLoadError(name, contents, where, fragment);
  }
};

// ------------------------------------------------------------------------------------------- .unurbs.json

TEST_F(NurbsReaders, UnurbsSphereRoundTrip) {
  const std::string path = write("sphere.unurbs.json", toJson(nurbs_fixtures::sphereSurface(2.0), true));
  const auto model = loadModel(path);
  const NurbsModel& m = asNurbs(model);
  EXPECT_TRUE(m.isSolid());
  EXPECT_EQ(m.surfaces().size(), 1u);
  EXPECT_NEAR(m.closestPoint(Eigen::Vector3d(0, 3, 0)).signedDistance, 1.0, 1e-12);
  EXPECT_NEAR(m.closestPoint(Eigen::Vector3d(0.5, 0, 0)).signedDistance, -1.5, 1e-12);
  const auto open = loadModel(write("wavy.UNURBS.JSON", toJson(nurbs_fixtures::wavySurface(), false)));
  EXPECT_FALSE(open->isSolid());
}

TEST_F(NurbsReaders, SharedAcceptanceModels) {
  if (!fs::exists(kModels / "sphere_nurbs.unurbs.json")) GTEST_SKIP() << "shared models not found at " << kModels;
  for (const char* name : {"sphere_nurbs.unurbs.json", "torus_nurbs.unurbs.json", "sphere_nurbs_1e4.unurbs.json"}) {
    SCOPED_TRACE(name);
    EXPECT_TRUE(loadModel((kModels / name).string())->isSolid());
  }
  EXPECT_FALSE(loadModel((kModels / "wavy_patch.unurbs.json").string())->isSolid());
  const std::string bad = (kModels / "bad_net.unurbs.json").string();
  const std::string msg = errorOf([&] { loadModel(bad); });
  EXPECT_EQ(msg.rfind(bad + ": surfaces[0]: knots_u: wrong length", 0), 0u) << msg;
}

TEST_F(NurbsReaders, MalformedUnurbs) {
  const std::string good = toJson(nurbs_fixtures::sphereSurface(), true);
  const std::string n = "m.unurbs.json";
  expectError(n, "{\"type\": \"nurbs\", ", ": byte ", "not valid JSON");
  expectError(n, "", ": byte 0: ", "not valid JSON");
  expectError(n, "[1, 2]", ": top level: ", "must be a JSON object");
  expectError(n, replaceOnce(good, "\"solid\":true,", ""), ": top level: ", "missing key \"solid\"");
  expectError(n, replaceOnce(good, "\"solid\":true,", "\"solid\":true,\"colour\":1,"), ": top level: ", "unknown key \"colour\"");
  expectError(n, replaceOnce(good, "\"nurbs\"", "\"mesh\""), ": type: ", "\"nurbs\"");
  expectError(n, replaceOnce(good, "\"solid\":true", "\"solid\":1"), ": solid: ", "true or false");
  expectError(n, "{\"type\":\"nurbs\",\"solid\":false,\"surfaces\":[]}", ": surfaces: ", "non-empty array");
  expectError(n, replaceOnce(good, "\"degree_u\":2", "\"degree_u\":2.5"), ": surfaces[0].degree_u: ", "integer");
  expectError(n, replaceOnce(good, "\"degree_v\":2", "\"degree_v\":0"), ": surfaces[0].degree_v: ", "out of range");
  expectError(n, replaceOnce(good, "\"knots_u\":[0,0,0,", "\"knots_u\":[0,0,\"a\","), ": surfaces[0].knots_u[2]: ", "must be a number");
  expectError(n, replaceOnce(good, "\"knots_u\":[0,0,0,0.25,0.25,", "\"knots_u\":[0,0,0,0.25,0.2,"), ": surfaces[0]: ",
              "knots_u is decreasing at index 4");
  expectError(n, replaceOnce(good, "\"knots_v\":[0,0,0,", "\"knots_v\":[0,0,"), ": surfaces[0]: ", "knots_v: wrong length 7 (expected 8");
  expectError(n, replaceOnce(good, "\"knots_u\":[0,0,0,0.25,0.25,0.5,0.5,0.75,0.75,1,1,1]", "\"knots_u\":[1,1,1,1,1,1,1,1,1,1,1,1]"),
              ": surfaces[0]: ", "zero-length parameter domain");
  expectError(n, replaceOnce(good, "[0,0,-1,1],", "[0,0,-1],"), ": surfaces[0].control_points[0][0]: ", "[x, y, z, w]");
  expectError(n, replaceOnce(good, "[0,0,-1,1],", "[0,0,-1,0],"), ": surfaces[0].control_points[0][0]: ", "weight must be positive");
  expectError(n, replaceOnce(good, "[0,0,-1,1],", "[0,0,-1,-2],"), ": surfaces[0].control_points[0][0]: ", "weight must be positive");
  expectError(n, replaceOnce(good, "[0,0,-1,1],", "[0,0,\"NaN\",1],"), ": surfaces[0].control_points[0][0][2]: ", "must be a number");
  expectError(n, replaceOnce(good, "[0,0,-1,1],", "[0,0,1e999,1],"), "", "");  // NaN/Inf cannot enter: either message is fine
  expectError(n, replaceOnce(good, "[0,0,-1,1],", ""), ": surfaces[0]: ", "control net row 1 has 5 points, row 0 has 4");
  // A solid that does not close.
  const nurbs_fixtures::Net half = [] {
    const NurbsSurface s = nurbs_fixtures::sphereSurface();
    nurbs_fixtures::Net h;
    for (int i = 0; i <= 4; ++i) {
      h.emplace_back();
      for (int j = 0; j < s.countV(); ++j) h.back().push_back(s.controlPoint(i, j));
    }
    return h;
  }();
  const NurbsSurface hemi(2, 2, {0, 0, 0, .5, .5, 1, 1, 1}, {0, 0, 0, .5, .5, 1, 1, 1}, half);
  expectError(n, toJson(hemi, true), ": ", "not closed");
  EXPECT_NO_THROW(loadModel(write("half.unurbs.json", toJson(hemi, false))));
}

// --------------------------------------------------------------------------------------------------- IGES

TEST_F(NurbsReaders, IgesSphereWithTransformation) {
  const auto model = loadModel((kFixtures / "sphere_moved.igs").string());
  const NurbsModel& m = asNurbs(model);
  EXPECT_TRUE(m.isSolid());  // the surfaces close up
  // The unit sphere rotated about z and moved to (1, 2, 3) by entity 124.
  const Eigen::Vector3d c(1, 2, 3);
  for (const Eigen::Vector3d& q : {Eigen::Vector3d(4, 2, 3), Eigen::Vector3d(1, 2, 3.5), Eigen::Vector3d(-1, -1, 0)})
    EXPECT_NEAR(m.closestPoint(q).signedDistance, (q - c).norm() - 1, 1e-12);
  // The rotation: the surface's (u, v) = (0, 0.5) point was (1, 0, 0) and is now (0, 1, 0) + c.
  EXPECT_LT((m.surfaces()[0].evaluate(0, 0.5) - (c + Eigen::Vector3d(0, 1, 0))).norm(), 1e-14);
}

TEST_F(NurbsReaders, IgesTorusWithOtherDelimiters) {
  const auto model = loadModel((kFixtures / "torus_delims.igs").string());
  const NurbsModel& m = asNurbs(model);
  EXPECT_TRUE(m.isSolid());
  EXPECT_NEAR(m.closestPoint(Eigen::Vector3d(0, 0, 0)).signedDistance, 0.75, 1e-12);
  EXPECT_NEAR(m.closestPoint(Eigen::Vector3d(1, 0, 0)).signedDistance, -0.25, 1e-12);
}

// Files OpenCASCADE's IGES writer wrote (tests/data/nurbs/occt_export.cpp): the surfaces as 120° arcs on
// unclamped knot vectors, trimmed faces (144/142) or a B-rep (186 ...) around them, the trimming ignored (the
// faces are whole). Exact against the analytic distances, and the model's box tight although the arcs' control
// points reach twice the radius out.
TEST_F(NurbsReaders, IgesWrittenByOpenCascade) {
  const auto torusDistance = [](const Eigen::Vector3d& q) { return std::hypot(std::hypot(q.x(), q.y()) - 1, q.z()) - 0.25; };
  const Eigen::Vector3d centre(1, 2, 3);
  const auto sphereDistance = [&](const Eigen::Vector3d& q) { return (q - centre).norm() - 0.5; };
  struct File {
    const char* name;
    std::function<double(const Eigen::Vector3d&)> truth;
    Eigen::Vector3d lo, hi;
  };
  const std::vector<File> files = {
      {"torus_occt_faces.igs", torusDistance, {-1.25, -1.25, -0.25}, {1.25, 1.25, 0.25}},
      {"torus_occt_brep.igs", torusDistance, {-1.25, -1.25, -0.25}, {1.25, 1.25, 0.25}},
      {"sphere_occt_faces.igs", sphereDistance, centre.array() - 0.5, centre.array() + 0.5}};
  std::srand(7);
  for (const File& f : files) {
    SCOPED_TRACE(f.name);
    const auto model = loadModel((kFixtures / f.name).string());
    const NurbsModel& m = asNurbs(model);
    EXPECT_TRUE(m.isSolid());
    EXPECT_EQ(m.surfaces().size(), 1u);
    // The box holds the surface and is within 2 % of its size of the true one (the control points' box was
    // 3.75 x 4.33 x 0.87 for the torus).
    const Aabb box = m.localBounds();
    EXPECT_TRUE((box.min.array() <= f.lo.array() + 1e-9).all() && (box.max.array() >= f.hi.array() - 1e-9).all());
    EXPECT_LT((box.min - f.lo).norm() + (box.max - f.hi).norm(), 0.02 * (f.hi - f.lo).norm());
    for (int k = 0; k < 200; ++k) {
      const Eigen::Vector3d q = 0.5 * (f.lo + f.hi) + 0.8 * (f.hi - f.lo).cwiseProduct(Eigen::Vector3d::Random());
      EXPECT_NEAR(m.closestPoint(q).signedDistance, f.truth(q), 1e-9) << q.transpose();
    }
  }
}

// A trim that keeps less than the whole surface is refused, naming the entity (read untrimmed, the model would
// be wrong): holes, a boundary inside the parameter rectangle, a boundary in model space only, a face with two
// loops. Edits of the OpenCASCADE files, each keeping the line's 64 data columns.
TEST_F(NurbsReaders, IgesTrimmedFacesAreRefused) {
  const std::string faces = readText(kFixtures / "torus_occt_faces.igs");
  const std::string brep = readText(kFixtures / "torus_occt_brep.igs");
  expectError("holes.igs", replaceOnce(faces, "144,3,1,0,5;  ", "144,3,1,1,5,7;"), ":", "entity 144 (directory entry 1) cuts 1 hole");
  // The outer boundary's parameter-space curve swapped for its model-space one: points off the rectangle.
  expectError("inside.igs", replaceOnce(faces, "142,0,3,7,17,3;", "142,0,3,17,7,3;"), ":", "keeps part of its surface");
  expectError("model.igs", replaceOnce(faces, "142,0,3,7,17,3;", "142,0,3,0,17,3;"), ":", "in model space only");
  expectError("loops.igs", replaceOnce(brep, "510,7,1,1,9;  ", "510,7,2,1,9,9;"), ":", "entity 510 (directory entry 5) has 2 loops");
}

// A parameter range narrower than the knot domain restricts the surface to it (here a band of the moved sphere:
// half its longitudes, its middle latitudes), an open model; one reaching outside the domain is an error.
TEST_F(NurbsReaders, IgesParameterRangeRestrictsTheSurface) {
  const std::string good = readText(kFixtures / "sphere_moved.igs");
  const std::string bandPath = write("band.igs", replaceOnce(good, "1,0,0,1,0,1,0,1;   ", "1,0,0,1,0,.5,.3,.7;"));
  const auto wholeModel = loadModel((kFixtures / "sphere_moved.igs").string());
  const NurbsModel& whole = asNurbs(wholeModel);
  const auto model = loadModel(bandPath);
  const NurbsModel& m = asNurbs(model);
  EXPECT_FALSE(m.isSolid());
  const NurbsSurface& s = m.surfaces()[0];
  EXPECT_EQ(s.uMin(), 0);
  EXPECT_EQ(s.uMax(), 0.5);
  EXPECT_EQ(s.vMin(), 0.3);
  EXPECT_EQ(s.vMax(), 0.7);
  for (double u : {0.0, 0.1, 0.37, 0.5})
    for (double v : {0.3, 0.45, 0.7})
      EXPECT_LT((s.evaluate(u, v) - whole.surfaces()[0].evaluate(u, v)).norm(), 1e-13) << u << " " << v;
  EXPECT_NEAR(m.closestPoint(Eigen::Vector3d(1, 2, 3)).signedDistance, 1, 1e-12);  // the centre
  expectError("wide.igs", replaceOnce(good, "1,0,0,1,0,1,0,1;   ", "1,0,0,1,0,1,0,2;   "), ":", "knot domain");
  expectError("empty.igs", replaceOnce(good, "1,0,0,1,0,1,0,1;   ", "1,0,0,1,.5,.5,0,1; "), ":", "u range");
}

/// Replaces columns [from, from + text.size()) of physical line `line` (from 1) of an IGES text.
std::string patchColumns(std::string text, int line, std::size_t from, const std::string& replacement) {
  std::size_t at = 0;
  for (int k = 1; k < line; ++k) at = text.find('\n', at) + 1;
  text.replace(at + from, replacement.size(), replacement);
  return text;
}

std::string dropLine(std::string text, int line) {
  std::size_t at = 0;
  for (int k = 1; k < line; ++k) at = text.find('\n', at) + 1;
  text.erase(at, text.find('\n', at) + 1 - at);
  return text;
}

std::string keepLines(const std::string& text, std::initializer_list<int> lines) {
  std::istringstream in(text);
  std::string line, out;
  for (int k = 1; std::getline(in, line); ++k)
    for (int keep : lines)
      if (keep == k) out += line + "\n";
  return out;
}

TEST_F(NurbsReaders, MalformedIges) {
  // sphere_moved.igs: line 1 S, lines 2-3 G, lines 4-5 D (entity 124), 6-7 D (entity 128), P from line 8 (124)
  // and line 9 on (128).
  const std::string good = readText(kFixtures / "sphere_moved.igs");
  ASSERT_FALSE(good.empty());
  const std::string n = "m.igs";
  expectError(n, "", ":1: ", "no directory section");
  expectError(n, good.substr(0, good.find('\n') + 1) + good.substr(good.find('\n') + 1, 40) + "\n", ":2: ",
              "shorter than 73 columns");
  expectError(n, patchColumns(good, 5, 72, "X"), ":5: ", "unknown section letter 'X'");
  expectError(n, patchColumns(good, 6, 8, "      99"), ":6: ", "parameter data pointer 99 is outside the P section");
  expectError(n, patchColumns(good, 6, 48, "       7"), ":6: ", "does not name an entity 124");
  expectError(n, patchColumns(good, 7, 0, "     126"), ":7: ", "different entity types");
  expectError(n, dropLine(good, 7), ":", "odd number of directory lines");
  expectError(n, patchColumns(good, 9, 22, "0.2x"), ":9: ", "is not a number");
  expectError(n, patchColumns(good, 9, 0, "127"), ":9: ", "does not start with the entity type 128");
  expectError(n, patchColumns(good, 2, 0, "2H"), ":2: ", "delimiter");
  expectError(n, patchColumns(good, 7, 24, "       1"), ":", "missing record delimiter");
  // A weight of zero: the surface's own check, with the line of the entity.
  expectError(n, replaceOnce(good, ",1,0.7071067811865476,1,0.7071067811865476,1,", ",1,0.7071067811865476,0,0.7071067811865476,1,"),
              ":9: ", "weight");
  // Only the transformation (S, G, its D entry and P line, T): no surface.
  expectError(n, keepLines(good, {1, 2, 3, 4, 5, 8, 16}), ":", "no rational B-spline surface (entity 128)");
}

}  // namespace
}  // namespace unidist
