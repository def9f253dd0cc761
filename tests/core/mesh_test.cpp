// Triangle meshes against truth written here (tests/core/mesh_fixtures.h): brute force over all triangles with
// an independent long-double point–triangle routine, brute-force winding numbers, analytic convex solids.
// Every family runs on seeded random points near, inside and outside, at scales 1e-4, 1 and 1e4.
#include "core/mesh_fixtures.h"
#include "mesh/bvh.h"
#include "mesh/point_triangle.h"
#include "unidist/distance.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cstdio>
#include <string>
#include <thread>

namespace {

using meshfix::Soup;
using meshfix::Tri;
using meshfix::Vec;
using unidist::InputError;
using unidist::SurfaceCell;
using unidist::SurfacePoint;
using unidist::TriangleFeature;
using unidist::TriangleMesh;

double sizeOf(const Soup& s) {
  Vec lo = s.vertices[0], hi = s.vertices[0];
  for (const Vec& v : s.vertices) lo = lo.cwiseMin(v), hi = hi.cwiseMax(v);
  return (hi - lo).norm();
}

// ---------------------------------------------------------------------------------------------------------
// Point–triangle

TEST(PointTriangle, EveryVoronoiRegionByName) {
  const Vec a(0, 0, 0), b(3, 0, 0), c(0, 2, 0);
  struct Case {
    const char* name;
    Vec q, p;
    TriangleFeature f;
  };
  const Case cases[] = {
      {"above the face", {0.5, 0.5, 2}, {0.5, 0.5, 0}, TriangleFeature::Face},
      {"below the face", {1, 0.25, -3}, {1, 0.25, 0}, TriangleFeature::Face},
      {"beyond edge 01", {1.5, -1, 1}, {1.5, 0, 0}, TriangleFeature::Edge01},
      {"beyond edge 12", {3, 2, 0.5}, {3 - 12.0 / 13, 8.0 / 13, 0}, TriangleFeature::Edge12},
      {"beyond edge 20", {-1, 1, -1}, {0, 1, 0}, TriangleFeature::Edge20},
      {"beyond vertex 0", {-1, -1, 0.3}, a, TriangleFeature::Vertex0},
      {"beyond vertex 1", {4, -0.5, 0}, b, TriangleFeature::Vertex1},
      {"beyond vertex 2", {-0.1, 3, 2}, c, TriangleFeature::Vertex2},
      {"on vertex 1", b, b, TriangleFeature::Vertex1},
  };
  for (const Case& k : cases) {
    SCOPED_TRACE(k.name);
    const auto r = unidist::mesh::closestOnTriangle(k.q, a, b, c);
    EXPECT_EQ(r.feature, k.f);
    EXPECT_LE((r.point - k.p).norm(), 1e-15);
    EXPECT_NEAR(r.squaredDistance, (k.q - k.p).squaredNorm(), 1e-14);
    const Vec fromBary = (1 - r.b1 - r.b2) * a + r.b1 * b + r.b2 * c;
    EXPECT_LE((fromBary - r.point).norm(), 1e-14);
  }
}

TEST(PointTriangle, DegenerateTrianglesAreTheirSegments) {
  std::mt19937_64 rng(5);
  std::uniform_real_distribution<double> u(-2, 2);
  const Vec a(0.125, 0.25, -0.375), d(1, -2, 0.5);  // dyadic: a + t·d is exact for the t used here
  const Vec collinear[3] = {a, a + d, a + 0.25 * d};
  for (int i = 0; i < 1000; ++i) {
    const Vec q(u(rng), u(rng), u(rng));
    const auto r = unidist::mesh::closestOnTriangle(q, collinear[0], collinear[1], collinear[2]);
    const double truth = std::sqrt(static_cast<double>(meshfix::segmentSq(meshfix::toL(q), meshfix::toL(a), meshfix::toL(a + d))));
    ASSERT_NEAR(std::sqrt(r.squaredDistance), truth, 1e-14) << i;
    ASSERT_TRUE(r.point.allFinite());
    const auto point = unidist::mesh::closestOnTriangle(q, a, a, a);  // all three vertices equal
    ASSERT_NEAR(std::sqrt(point.squaredDistance), (q - a).norm(), 1e-15);
    ASSERT_EQ(point.point, a);
  }
  EXPECT_TRUE(unidist::mesh::zeroArea(collinear[0], collinear[1], collinear[2]));
  EXPECT_TRUE(unidist::mesh::zeroArea(Vec(0, 0, 0), Vec(1, 1, 1), Vec(3, 3, 3)));
  EXPECT_FALSE(unidist::mesh::zeroArea(Vec(0, 0, 0), Vec(1, 1, 1), Vec(3, 3, 3 + 4.440892098500626e-16)));
  EXPECT_EQ(unidist::mesh::accurateUnitNormal(a, a + d, a + 0.5 * d), Vec::Zero());
}

// Distance from q to a triangle whose coordinates are multiples of 2^-40 below 4 in size: the normal is
// computed exactly in 128-bit integers and only then rounded, so its direction is right to ~1e-19 even for
// a sliver, where a long-double cross product of the edges would be off by ~1e-12 rad.
meshfix::VecL preciseNormal(const Vec& a, const Vec& b, const Vec& c) {
  using I = __int128;
  const auto fixed = [](double x) { return static_cast<I>(std::llround(std::ldexp(x, 40))); };
  I A[3], B[3], C[3];
  for (int i = 0; i < 3; ++i) A[i] = fixed(a[i]), B[i] = fixed(b[i]), C[i] = fixed(c[i]);
  meshfix::VecL n;
  for (int i = 0; i < 3; ++i) {
    const int j = (i + 1) % 3, k = (i + 2) % 3;
    const I value = (B[j] - A[j]) * (C[k] - A[k]) - (B[k] - A[k]) * (C[j] - A[j]);
    n[i] = std::ldexp(static_cast<long double>(value), -80);
  }
  return n;
}

double preciseTriangleDistance(const Vec& q, const Vec& a, const Vec& b, const Vec& c) {
  const meshfix::VecL n = preciseNormal(a, b, c);
  const meshfix::VecL ql = meshfix::toL(q), al = meshfix::toL(a), bl = meshfix::toL(b), cl = meshfix::toL(c);
  const long double s0 = n.dot((bl - al).cross(ql - al)), s1 = n.dot((cl - bl).cross(ql - bl)),
                    s2 = n.dot((al - cl).cross(ql - cl));
  if (n.squaredNorm() > 0 && s0 >= 0 && s1 >= 0 && s2 >= 0)
    return static_cast<double>(std::abs(n.dot(ql - al)) / n.norm());
  return static_cast<double>(std::sqrt(std::min(
      {meshfix::segmentSq(ql, al, bl), meshfix::segmentSq(ql, bl, cl), meshfix::segmentSq(ql, cl, al)})));
}

Vec onGrid(const Vec& v) {
  return {std::ldexp(std::round(std::ldexp(v.x(), 40)), -40), std::ldexp(std::round(std::ldexp(v.y(), 40)), -40),
          std::ldexp(std::round(std::ldexp(v.z(), 40)), -40)};
}

// A sliver (height 1e-7 of its length) in a random orientation: the rounded cross product of its edges is off
// by ~1e-9 rad, which would move projected points by 1e-9 of their distance; the accurate normal must not.
TEST(PointTriangle, SliversAreExactToRounding) {
  std::mt19937_64 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  int face = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const Eigen::Quaterniond rot = Eigen::Quaterniond::UnitRandom();
    const double length = 1.7, height = 1e-7 * length;
    const Vec offset(u(rng), u(rng), u(rng));
    const Vec a = onGrid(offset), b = onGrid(offset + rot * Vec(length, 0, 0)),
              c = onGrid(offset + rot * Vec(0.37 * length, height, 0));
    // The rounded triangle's own normal: rot·z is ~1e-9 rad off it (the rounding of the vertices).
    const Vec n = preciseNormal(a, b, c).normalized().cast<double>();
    for (int i = 0; i < 20; ++i) {
      // Mostly above or below the face (random barycentric coordinates), some beyond its edges.
      double s = 0.5 * (1 + u(rng)), t = 0.5 * (1 + u(rng));
      if (i % 5 != 0 && s + t > 1) s = 1 - s, t = 1 - t;
      const Vec q = a + s * (b - a) + t * (c - a) + 0.3 * u(rng) * n;
      const auto r = unidist::mesh::closestOnTriangle(q, a, b, c);
      worst = std::max(worst, std::abs(std::sqrt(r.squaredDistance) - preciseTriangleDistance(q, a, b, c)) / length);
      // The returned point is on the triangle.
      ASSERT_LE(preciseTriangleDistance(r.point, a, b, c), 1e-15 * length);
      face += r.feature == TriangleFeature::Face;
    }
  }
  EXPECT_LE(worst, 1e-15);
  EXPECT_GT(face, 2500);  // most queries project into the face: the hard case was exercised
}

// ---------------------------------------------------------------------------------------------------------
// Point queries against brute force

struct Family {
  std::string name;
  Soup soup;
  bool solid;
};

Soup slicedBox() {
  // A box whose +z face holds a sliver: E sits 1e-9 off the diagonal AC, so triangle (C, A, E) is 1e-9 thin.
  Soup s = meshfix::gridBox(Vec(0.6, 0.45, 0.3), 1);
  // Remove the two +z triangles (the last face written by gridBox: axis 2, side 1).
  s.triangles.resize(s.triangles.size() - 2);
  auto find = [&](const Vec& p) {
    for (std::uint32_t i = 0; i < s.vertices.size(); ++i)
      if (s.vertices[i] == p) return i;
    return std::uint32_t(-1);
  };
  const std::uint32_t A = find(Vec(-0.6, -0.45, 0.3)), B = find(Vec(0.6, -0.45, 0.3)), C = find(Vec(0.6, 0.45, 0.3)),
                      D = find(Vec(-0.6, 0.45, 0.3));
  s.vertices.push_back(Vec(0.0, 0.0, 0.3) + 1e-9 * Vec(0.45, -0.6, 0).normalized());
  const auto E = static_cast<std::uint32_t>(s.vertices.size() - 1);
  s.triangles.push_back({A, B, E});
  s.triangles.push_back({B, C, E});
  s.triangles.push_back({C, A, E});
  s.triangles.push_back({A, C, D});
  return s;
}

std::vector<Family> families() {
  return {{"icosphere", meshfix::icosphere(0.8, 3), true},
          {"box", meshfix::gridBox(Vec(0.5, 0.35, 0.25), 3), true},
          {"torus", meshfix::torus(0.8, 0.25, 40, 20), true},
          {"sheet", meshfix::wavySheet(16), false},
          {"sliver box", slicedBox(), true}};
}

void checkAgainstBruteForce(const Family& fam, double scale, int count, std::uint64_t seed) {
  const Soup soup = meshfix::scaled(fam.soup, scale, Vec(0.3, -0.2, 0.1) * scale);
  const TriangleMesh mesh = meshfix::makeMesh(soup);
  ASSERT_EQ(mesh.isSolid(), fam.solid);
  const double size = sizeOf(soup);
  std::mt19937_64 rng(seed);
  const std::vector<Vec> points = meshfix::queryPoints(soup, count, 0.05, 0.3, rng);
  int inside = 0, signChecked = 0;
  for (std::size_t i = 0; i < points.size(); ++i) {
    const Vec& q = points[i];
    const SurfacePoint s = mesh.closestPoint(q);
    const double truth = meshfix::bruteDistance(soup, q);
    ASSERT_NEAR(std::abs(s.signedDistance), truth, 1e-13 * size) << "i=" << i;
    ASSERT_NEAR((q - s.point).norm(), truth, 1e-13 * size) << "i=" << i;
    ASSERT_NEAR(s.normal.norm(), 1.0, 1e-14) << "i=" << i;
    // The point is on the reported triangle at the reported barycentric coordinates.
    const Tri& t = mesh.triangles()[static_cast<std::size_t>(s.feature)];
    const auto& V = mesh.vertices();
    const Vec fromBary = (1 - s.param.x() - s.param.y()) * V[t[0]] + s.param.x() * V[t[1]] + s.param.y() * V[t[2]];
    ASSERT_LE((fromBary - s.point).norm(), 1e-13 * size) << "i=" << i;
    ASSERT_LE(static_cast<double>(std::sqrt(meshfix::triangleSq(s.point, V[t[0]], V[t[1]], V[t[2]]))), 1e-13 * size);
    if (truth > 0) {
      const Vec u = (q - s.point) / (q - s.point).norm();
      ASSERT_LE((s.normal - (s.signedDistance < 0 ? -u : u)).norm(), 1e-9) << "i=" << i;
    }
    if (!fam.solid) {
      ASSERT_GE(s.signedDistance, 0) << "i=" << i;
      ASSERT_FALSE(mesh.inside(q));
      continue;
    }
    if (truth < 1e-9 * size) continue;  // the side of a point this close is rounding
    const bool in = meshfix::bruteWinding(soup, q) > 0.5;
    ASSERT_EQ(s.signedDistance < 0, in) << "i=" << i << " sd=" << s.signedDistance;
    ASSERT_EQ(mesh.inside(q), in) << "i=" << i;
    inside += in;
    ++signChecked;
  }
  if (fam.solid) {  // both sides were exercised
    EXPECT_GT(inside, signChecked / 20);
    EXPECT_LT(inside, signChecked - signChecked / 20);
  }
}

class MeshFamily : public ::testing::TestWithParam<std::tuple<int, double>> {};

TEST_P(MeshFamily, ClosestPointAndSignMatchBruteForce) {
  const auto [index, scale] = GetParam();
  const Family fam = families()[static_cast<std::size_t>(index)];
  SCOPED_TRACE(fam.name + " at scale " + std::to_string(scale));
  checkAgainstBruteForce(fam, scale, scale == 1.0 ? 3000 : 600, 1000 + static_cast<std::uint64_t>(index));
}

INSTANTIATE_TEST_SUITE_P(AllFamilies, MeshFamily,
                         ::testing::Combine(::testing::Values(0, 1, 2, 3, 4), ::testing::Values(1e-4, 1.0, 1e4)));

// Points on the surface, exactly representable: vertices, edge midpoints and face points of an axis-aligned
// box with dyadic sizes. The distance must be exactly 0 and the normal the feature's outward pseudo-normal.
TEST(MeshPointQuery, PointsExactlyOnTheSurfaceHaveZeroDistance) {
  const Soup soup = meshfix::gridBox(Vec(0.5, 0.75, 1.25), 2);
  const TriangleMesh mesh = meshfix::makeMesh(soup);
  ASSERT_TRUE(mesh.isSolid());
  for (const Vec& v : soup.vertices) {
    const SurfacePoint s = mesh.closestPoint(v);
    EXPECT_EQ(s.signedDistance, 0.0);
    EXPECT_EQ(s.point, v);
    EXPECT_GT(s.normal.dot(v), 0);  // outward at every vertex of a box centred at the origin
  }
  for (const Tri& t : soup.triangles)
    for (int k = 0; k < 3; ++k) {
      const Vec mid = 0.5 * (soup.vertices[t[k]] + soup.vertices[t[(k + 1) % 3]]);  // exact: dyadic
      const SurfacePoint s = mesh.closestPoint(mid);
      EXPECT_EQ(s.signedDistance, 0.0);
      EXPECT_NEAR(s.normal.norm(), 1.0, 1e-15);
      const Vec face = (soup.vertices[t[0]] + soup.vertices[t[1]] + soup.vertices[t[2]]);
      EXPECT_GT(s.normal.dot(face), 0);
    }
  // Corners: the pseudo-normal of a box corner is the diagonal.
  const SurfacePoint corner = mesh.closestPoint(Vec(0.5, 0.75, 1.25));
  EXPECT_LE((corner.normal - Vec(1, 1, 1).normalized()).norm(), 1e-15);
  // Just off the corner along the diagonal, inside and outside.
  EXPECT_GT(mesh.closestPoint(Vec(0.5, 0.75, 1.25) * (1 + 1e-12)).signedDistance, 0);
  EXPECT_LT(mesh.closestPoint(Vec(0.5, 0.75, 1.25) * (1 - 1e-12)).signedDistance, 0);
}

// Around sharp edges and vertices of a non-convex solid the face normal alone gives the wrong side; the
// pseudo-normals must not. Points sampled densely near every vertex and edge of the torus.
TEST(MeshPointQuery, SignIsRightNearEveryEdgeAndVertex) {
  const Soup soup = meshfix::torus(0.8, 0.25, 12, 6);  // coarse: sharp dihedral angles
  const TriangleMesh mesh = meshfix::makeMesh(soup);
  std::mt19937_64 rng(3);
  std::normal_distribution<double> n01;
  int checked = 0;
  for (const Tri& t : soup.triangles)
    for (int k = 0; k < 3; ++k)
      for (double along : {0.0, 0.3}) {
        const Vec p = (1 - along) * soup.vertices[t[k]] + along * soup.vertices[t[(k + 1) % 3]];
        for (int j = 0; j < 4; ++j) {
          const Vec q = p + 1e-3 * Vec(n01(rng), n01(rng), n01(rng));
          const double w = meshfix::bruteWinding(soup, q);
          if (meshfix::bruteDistance(soup, q) < 1e-9) continue;
          ASSERT_EQ(mesh.closestPoint(q).signedDistance < 0, w > 0.5);
          ++checked;
        }
      }
  EXPECT_GT(checked, 1500);
}

// ---------------------------------------------------------------------------------------------------------
// Inside test

TEST(MeshInside, WindingNumberMatchesConvexSolidsExactly) {
  for (const Soup& soup : {meshfix::icosphere(1.3, 3), meshfix::gridBox(Vec(0.4, 0.9, 0.3), 4)}) {
    const TriangleMesh mesh = meshfix::makeMesh(soup);
    ASSERT_TRUE(mesh.isConvex());
    std::mt19937_64 rng(8);
    const std::vector<Vec> points = meshfix::queryPoints(soup, 4000, 0.02, 0.2, rng);
    for (std::size_t i = 0; i < points.size(); ++i) {
      const Vec& q = points[i];
      double planeDistance = -1e300;  // max over faces of the signed plane distance: > 0 outside
      for (std::size_t t = 0; t < mesh.triangles().size(); ++t)
        planeDistance = std::max(planeDistance, mesh.faceNormal(static_cast<int>(t)).dot(q - mesh.vertices()[mesh.triangles()[t][0]]));
      if (std::abs(planeDistance) < 1e-9) continue;
      const bool in = planeDistance < 0;
      ASSERT_EQ(mesh.inside(q), in) << i;
      ASSERT_NEAR(mesh.windingNumber(q), in ? 1.0 : 0.0, 1e-9) << i;
    }
  }
}

TEST(MeshInside, HierarchicalWindingEqualsBruteForceOnOpenAndClosedMeshes) {
  for (const Soup& soup : {meshfix::torus(0.8, 0.25, 40, 20), meshfix::wavySheet(20)}) {
    const TriangleMesh mesh = meshfix::makeMesh(soup);
    std::mt19937_64 rng(21);
    for (const Vec& q : meshfix::queryPoints(soup, 1000, 0.05, 0.3, rng)) {
      if (meshfix::bruteDistance(soup, q) < 1e-6) continue;
      ASSERT_NEAR(mesh.windingNumber(q), meshfix::bruteWinding(soup, q), 1e-10);
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// Construction: solid detection, cleaning, validation

Soup unitCube() { return meshfix::gridBox(Vec(1, 1, 1), 1); }

TEST(MeshTopology, ClosedCubeIsSolid) {
  const TriangleMesh m = meshfix::makeMesh(unitCube());
  EXPECT_TRUE(m.stats().closed);
  EXPECT_TRUE(m.stats().consistentlyOriented);
  EXPECT_TRUE(m.isSolid());
  EXPECT_TRUE(m.isConvex());
  EXPECT_FALSE(m.stats().flipped);
  EXPECT_NEAR(m.stats().signedVolume, 8.0, 1e-14);
  EXPECT_EQ(m.type(), unidist::ModelType::Mesh);
}

TEST(MeshTopology, CubeWithAFaceRemovedIsOpen) {
  Soup s = unitCube();
  s.triangles.resize(10);
  const TriangleMesh m = meshfix::makeMesh(s);
  EXPECT_FALSE(m.isSolid());
  EXPECT_FALSE(m.stats().closed);
  EXPECT_TRUE(m.stats().consistentlyOriented);
  EXPECT_EQ(m.stats().boundaryEdges, 4u);
  EXPECT_FALSE(m.isConvex());
  // No inside: the centre is 1 from the surface, unsigned.
  EXPECT_NEAR(m.closestPoint(Vec::Zero()).signedDistance, 1.0, 1e-15);
  EXPECT_FALSE(m.inside(Vec::Zero()));
  EXPECT_NE(m.describe().find("open (4 boundary edges"), std::string::npos) << m.describe();
}

TEST(MeshTopology, CubeWithAFaceFlippedIsNotConsistentlyOriented) {
  Soup s = unitCube();
  std::swap(s.triangles[0][1], s.triangles[0][2]);
  std::swap(s.triangles[1][1], s.triangles[1][2]);
  const TriangleMesh m = meshfix::makeMesh(s);
  EXPECT_TRUE(m.stats().closed);
  EXPECT_FALSE(m.stats().consistentlyOriented);
  EXPECT_FALSE(m.isSolid());
  EXPECT_EQ(m.stats().misorientedEdges, 4u);
  EXPECT_GE(m.closestPoint(Vec::Zero()).signedDistance, 0);
}

TEST(MeshTopology, InwardSolidIsTurnedOutward) {
  for (const Soup& outward : {unitCube(), meshfix::torus(0.8, 0.25, 24, 12)}) {
    const TriangleMesh m = meshfix::makeMesh(meshfix::reversed(outward));
    EXPECT_TRUE(m.isSolid());
    EXPECT_TRUE(m.stats().flipped);
    EXPECT_GT(m.stats().signedVolume, 0);
    const SurfacePoint far = m.closestPoint(Vec(3, 0.1, 0.2));
    EXPECT_GT(far.signedDistance, 0);
    EXPECT_GT(far.normal.x(), 0.9);
    // Every face normal points away from the inside.
    for (std::size_t t = 0; t < m.triangles().size(); ++t) {
      const auto& tri = m.triangles()[t];
      const Vec c = (m.vertices()[tri[0]] + m.vertices()[tri[1]] + m.vertices()[tri[2]]) / 3;
      EXPECT_FALSE(m.inside(c + 1e-6 * m.faceNormal(static_cast<int>(t))));
      EXPECT_TRUE(m.inside(c - 1e-6 * m.faceNormal(static_cast<int>(t))));
    }
  }
}

// A cube given as 12 separate triangles with their own vertex copies (36 vertices), plus repeats (one of them
// reversed), zero-area triangles (a repeated index; three collinear vertices, one of them the exact midpoint
// of an edge that then serves nothing else) and a vertex equal to another with -0.0 for +0.0.
TEST(MeshTopology, WeldingAndDroppingAreCounted) {
  const Soup cube = meshfix::scaled(unitCube(), 1.0, Vec(0, 0, 1));  // z from 0 to 2: a zero coordinate
  Soup s;
  for (const Tri& t : cube.triangles) {
    Tri copy;
    for (int k = 0; k < 3; ++k) {
      s.vertices.push_back(cube.vertices[t[k]]);
      copy[k] = static_cast<std::uint32_t>(s.vertices.size() - 1);
    }
    s.triangles.push_back(copy);
  }
  // -0.0 in place of +0.0: the same position.
  for (Vec& v : s.vertices)
    if (v.z() == 0.0) {
      v.z() = -0.0;
      break;
    }
  s.triangles.push_back(s.triangles[3]);                                         // repeat
  s.triangles.push_back({s.triangles[5][0], s.triangles[5][2], s.triangles[5][1]});  // reversed repeat
  s.triangles.push_back({s.triangles[7][1], s.triangles[7][2], s.triangles[7][0]});  // rotated repeat
  s.triangles.push_back({0, 0, 1});                                              // repeated index
  const Vec a = s.vertices[s.triangles[0][0]], b = s.vertices[s.triangles[0][1]];
  s.vertices.push_back(0.5 * (a + b));  // exact midpoint of an edge
  s.triangles.push_back({s.triangles[0][0], static_cast<std::uint32_t>(s.vertices.size() - 1), s.triangles[0][1]});
  s.vertices.push_back(Vec(7, 7, 7));  // used by nothing

  const TriangleMesh m = meshfix::makeMesh(s);
  const auto& st = m.stats();
  EXPECT_EQ(st.inputVertices, 38u);
  EXPECT_EQ(st.inputTriangles, 17u);
  EXPECT_EQ(st.weldedVertices, 10u);  // 8 corners + the midpoint + the unused one
  EXPECT_EQ(st.unusedVertices, 2u);
  EXPECT_EQ(st.droppedZeroArea, 2u);
  EXPECT_EQ(st.droppedDuplicate, 3u);
  EXPECT_EQ(m.vertices().size(), 8u);
  EXPECT_EQ(m.triangles().size(), 12u);
  EXPECT_TRUE(m.isSolid());
  EXPECT_TRUE(m.isConvex());
  for (int t = 0; t < 12; ++t) EXPECT_EQ(m.sourceTriangle(t), static_cast<std::uint32_t>(t));
  const std::string d = m.describe();
  EXPECT_NE(d.find("12 triangles, 8 vertices, solid (convex)"), std::string::npos) << d;
  EXPECT_NE(d.find("welded 28 duplicate vertices, dropped 2 zero-area and 3 duplicate triangles"), std::string::npos) << d;
  // And it answers like the clean cube.
  const TriangleMesh clean = meshfix::makeMesh(cube);
  std::mt19937_64 rng(4);
  for (const Vec& q : meshfix::queryPoints(cube, 500, 0.1, 0.3, rng))
    ASSERT_EQ(m.closestPoint(q).signedDistance, clean.closestPoint(q).signedDistance);
}

TEST(MeshTopology, BadInputIsRejectedWithTheReason) {
  const auto message = [](std::vector<Vec> v, std::vector<Tri> t) {
    try {
      TriangleMesh m(std::move(v), std::move(t));
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::vector<Vec> v = {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}};
  EXPECT_EQ(message(v, {}), "mesh: no triangles");
  EXPECT_EQ(message(v, {{0, 1, 2}, {0, 1, 40}}), "mesh: triangle 1 has vertex index 40 out of range (3 vertices)");
  EXPECT_EQ(message({{0, 0, 0}, {1, NAN, 0}, {0, 1, 0}}, {{0, 1, 2}}),
            "mesh: vertex 1 has a non-finite coordinate (1, nan, 0)");
  EXPECT_EQ(message({{0, 0, 0}, {1, 0, INFINITY}, {0, 1, 0}}, {{0, 1, 2}}),
            "mesh: vertex 1 has a non-finite coordinate (1, 0, inf)");
  EXPECT_EQ(message({{0, 0, 0}, {1, 1, 1}, {2, 2, 2}, {0, 0, 0}}, {{0, 1, 2}, {0, 3, 1}}),
            "mesh: no triangle with non-zero area (2 triangles: 2 zero-area, 0 duplicate)");
}

// The smallest mesh: one triangle, open, a hierarchy of one leaf whose cell still splits down to points.
TEST(MeshTopology, OneTriangle) {
  const TriangleMesh m({{0, 0, 0}, {2, 0, 0}, {0, 1, 0}}, {{0, 1, 2}});
  EXPECT_FALSE(m.isSolid());
  EXPECT_EQ(m.stats().boundaryEdges, 3u);
  EXPECT_EQ(m.closestPoint(Vec(0.5, 0.25, -3)).signedDistance, 3.0);
  EXPECT_EQ(m.closestPoint(Vec(0.5, 0.25, -3)).normal, Vec(0, 0, -1));
  EXPECT_EQ(m.closestPoint(Vec(0.5, 0.25, 0)).normal, Vec(0, 0, 1));  // on it: the face normal
  EXPECT_EQ(m.support(Vec(1, 0.1, 0)), Vec(2, 0, 0));
  std::vector<SurfaceCell> cells = m.surfaceCells();
  ASSERT_EQ(cells.size(), 1u);
  for (int i = 0; i < 30; ++i) {
    std::vector<SurfaceCell> four;
    m.splitCell(cells.front(), four);
    ASSERT_EQ(four.size(), 4u);
    cells = {four[static_cast<std::size_t>(i % 4)]};
  }
  EXPECT_LT(cells.front().radius, 1e-8);
}

// Queries are defined for finite points; a NaN or infinite one must still not crash or read out of bounds.
TEST(MeshTopology, NonFiniteQueriesDoNotCrash) {
  const TriangleMesh m = meshfix::makeMesh(unitCube());
  for (const Vec& q : {Vec(NAN, 0, 0), Vec(INFINITY, 0, 0), Vec(0, -INFINITY, 1)}) {
    const SurfacePoint s = m.closestPoint(q);
    EXPECT_GE(s.feature, 0);
    EXPECT_LT(s.feature, 12);
    (void)m.inside(q);
  }
}

// ---------------------------------------------------------------------------------------------------------
// Convexity and the support map

TEST(MeshConvexity, DecidedExactlyOnTheUsualSuspects) {
  EXPECT_TRUE(meshfix::makeMesh(meshfix::icosphere(1, 2)).isConvex());
  EXPECT_TRUE(meshfix::makeMesh(meshfix::gridBox(Vec(1, 2, 3), 3)).isConvex());  // flat edges inside faces
  EXPECT_TRUE(meshfix::makeMesh(slicedBox()).isConvex());
  EXPECT_FALSE(meshfix::makeMesh(meshfix::torus(0.8, 0.25, 16, 8)).isConvex());
  EXPECT_FALSE(meshfix::makeMesh(meshfix::wavySheet(4)).isConvex());
  // A box with one face-interior vertex pushed in by 1e-6: a dent.
  Soup dented = meshfix::gridBox(Vec(1, 1, 1), 2);
  for (Vec& v : dented.vertices)
    if (v == Vec(1, 0, 0)) v.x() -= 1e-6;
  EXPECT_FALSE(meshfix::makeMesh(dented).isConvex());
  // ... and pushed out: with this triangulation the flat triangles beside it make valleys, not convex either.
  Soup bulged = meshfix::gridBox(Vec(1, 1, 1), 2);
  for (Vec& v : bulged.vertices)
    if (v == Vec(1, 0, 0)) v.x() += 1e-6;
  EXPECT_FALSE(meshfix::makeMesh(bulged).isConvex());
  Soup raised = meshfix::icosphere(1.0, 2);
  raised.vertices[0] *= 1.001;  // a vertex of the icosahedron (valence 5) moved out: still convex
  EXPECT_TRUE(meshfix::makeMesh(raised).isConvex());
  raised.vertices[0] *= 0.9;  // sunk below its neighbours' plane (their sagitta is ~4 %)
  EXPECT_FALSE(meshfix::makeMesh(raised).isConvex());
  // Two disjoint boxes: every edge convex, not convex together.
  Soup two = meshfix::gridBox(Vec(1, 1, 1), 1);
  const Soup other = meshfix::scaled(two, 1, Vec(5, 0, 0));
  const auto offset = static_cast<std::uint32_t>(two.vertices.size());
  two.vertices.insert(two.vertices.end(), other.vertices.begin(), other.vertices.end());
  for (Tri t : other.triangles) two.triangles.push_back({t[0] + offset, t[1] + offset, t[2] + offset});
  const TriangleMesh twoBoxes = meshfix::makeMesh(two);
  EXPECT_TRUE(twoBoxes.isSolid());
  EXPECT_FALSE(twoBoxes.isConvex());
}

TEST(MeshSupport, MatchesTheBestVertex) {
  std::mt19937_64 rng(9);
  std::normal_distribution<double> n01;
  for (const Soup& soup : {meshfix::icosphere(0.7, 4), meshfix::gridBox(Vec(1, 2, 3), 3), meshfix::torus(0.8, 0.2, 30, 12)}) {
    const TriangleMesh m = meshfix::makeMesh(soup);
    for (int i = 0; i < 2000; ++i) {
      Vec d(n01(rng), n01(rng), n01(rng));
      if (i % 10 == 0) d = Vec::Unit(i % 3) * (i % 20 == 0 ? 1 : -1);  // axis directions: ties
      double best = -1e300;
      for (const Vec& v : soup.vertices) best = std::max(best, d.dot(v));
      ASSERT_NEAR(d.dot(m.support(d)), best, 1e-14 * d.norm() * 4) << i;
    }
  }
}

// ---------------------------------------------------------------------------------------------------------
// Surface cells

TEST(MeshCells, CoverTheSurfaceAndShrinkToPoints) {
  const Soup soup = meshfix::torus(0.8, 0.25, 16, 8);
  const TriangleMesh m = meshfix::makeMesh(soup);
  std::mt19937_64 rng(13);
  std::uniform_real_distribution<double> u01(0, 1);
  // Surface points: every vertex and random points on every triangle.
  std::vector<Vec> samples(soup.vertices);
  for (const Tri& t : soup.triangles)
    for (int k = 0; k < 2; ++k) {
      double a = u01(rng), b = u01(rng);
      if (a + b > 1) a = 1 - a, b = 1 - b;
      samples.push_back(soup.vertices[t[0]] + a * (soup.vertices[t[1]] - soup.vertices[t[0]]) +
                        b * (soup.vertices[t[2]] - soup.vertices[t[0]]));
    }
  std::vector<SurfaceCell> cells = m.surfaceCells();
  ASSERT_FALSE(cells.empty());
  EXPECT_LE(cells.size(), 4u);
  double firstLargest = 0, largest = 0;
  for (int level = 0; cells.size() < 20000; ++level) {
    // Every sample lies in some cell, every cell's sample lies on the mesh and in the cell.
    for (const Vec& p : samples) {
      bool covered = false;
      for (const SurfaceCell& c : cells) covered = covered || (p - c.center).norm() <= c.radius;
      ASSERT_TRUE(covered) << "level " << level;
    }
    largest = 0;
    for (std::size_t i = 0; i < cells.size(); ++i) {
      const SurfaceCell& c = cells[i];
      ASSERT_LE((c.sample - c.center).norm(), c.radius * (1 + 1e-12) + 1e-15);
      if (i % 37 == 0) {
        ASSERT_LE(meshfix::bruteDistance(soup, c.sample), 1e-15);
      }
      largest = std::max(largest, c.radius);
    }
    if (level == 0) firstLargest = largest;
    std::vector<SurfaceCell> next;
    for (const SurfaceCell& c : cells) m.splitCell(c, next);
    ASSERT_GE(next.size(), cells.size());
    cells = std::move(next);
  }
  EXPECT_LT(largest, 0.2 * firstLargest);
  // One triangle cell, split again and again, converges to a point.
  SurfaceCell c = cells.front();
  ASSERT_LT(c.face, 0);
  for (int i = 0; i < 40; ++i) {
    std::vector<SurfaceCell> four;
    m.splitCell(c, four);
    ASSERT_EQ(four.size(), 4u);
    c = four[static_cast<std::size_t>(i % 4)];
  }
  EXPECT_LT(c.radius, 1e-12);
}

// Every triangle is inside the ball of the cells at the leaf level (vertices and points on each triangle).
TEST(MeshCells, LeafBallsHoldTheirTriangles) {
  const Soup soup = meshfix::scaled(meshfix::icosphere(1.0, 3), 1e4, Vec(2e4, -1e4, 3e3));
  const TriangleMesh m = meshfix::makeMesh(soup);
  std::vector<SurfaceCell> cells = m.surfaceCells(), triangleCells;
  while (!cells.empty()) {
    std::vector<SurfaceCell> next;
    for (const SurfaceCell& c : cells) {
      if (c.face < 0) {
        triangleCells.push_back(c);
        continue;
      }
      m.splitCell(c, next);
    }
    cells = std::move(next);
  }
  std::vector<int> seen(m.triangles().size(), 0);
  for (const SurfaceCell& c : triangleCells) {
    const int t = -1 - c.face;
    ++seen[static_cast<std::size_t>(t)];
    const auto& tri = m.triangles()[static_cast<std::size_t>(t)];
    // The triangle cell (or its four quarters, for one-triangle leaves) holds the part it encodes: check the
    // part's corners, which span it.
    const Vec a = m.vertices()[tri[0]], e1 = m.vertices()[tri[1]] - a, e2 = m.vertices()[tri[2]] - a;
    for (auto [u, v] : {std::pair{c.u0, c.v0}, std::pair{c.u1, c.v0}, std::pair{c.u0, c.v1}})
      ASSERT_LE((a + u * e1 + v * e2 - c.center).norm(), c.radius);
  }
  for (int s : seen) ASSERT_GE(s, 1);
}

// ---------------------------------------------------------------------------------------------------------
// Laziness, thread safety, cost

TEST(MeshBvh, BuiltOnceLazilyAndSharedByConcurrentQueries) {
  const Soup soup = meshfix::torus(0.8, 0.25, 100, 50);  // 10k triangles
  std::mt19937_64 rng(17);
  const std::vector<Vec> points = meshfix::queryPoints(soup, 4000, 0.05, 0.3, rng);

  const TriangleMesh reference = meshfix::makeMesh(soup);
  const std::size_t before = reference.memoryBytes();
  EXPECT_FALSE(reference.bvhBuilt());
  std::vector<SurfacePoint> expected;
  std::vector<bool> expectedInside;
  for (const Vec& q : points) {
    expected.push_back(reference.closestPoint(q));
    expectedInside.push_back(reference.inside(q));
  }
  EXPECT_TRUE(reference.bvhBuilt());
  EXPECT_GT(reference.memoryBytes(), before);

  const TriangleMesh fresh = meshfix::makeMesh(soup);
  std::vector<std::thread> threads;
  std::vector<int> mismatches(8, 0);
  for (int k = 0; k < 8; ++k)
    threads.emplace_back([&, k] {
      for (std::size_t i = 0; i < points.size(); ++i) {
        const std::size_t j = (i + static_cast<std::size_t>(k) * 500) % points.size();  // different orders
        const SurfacePoint s = fresh.closestPoint(points[j]);
        const bool inside = fresh.inside(points[j]);
        mismatches[static_cast<std::size_t>(k)] +=
            s.point != expected[j].point || s.signedDistance != expected[j].signedDistance ||
            s.normal != expected[j].normal || s.feature != expected[j].feature ||
            inside != expectedInside[j];
      }
    });
  for (std::thread& t : threads) t.join();
  for (int m : mismatches) EXPECT_EQ(m, 0);
  EXPECT_EQ(fresh.bvhBuildCount(), 1);
  EXPECT_EQ(reference.bvhBuildCount(), 1);
  EXPECT_EQ(fresh.memoryBytes(), reference.memoryBytes());  // the same structures, built once each
}

// The build decides splits in single precision; a 1e-4 model 3e4 from its origin must still get a balanced
// tree (floats of raw coordinates would merge its features), and cells with proved balls.
TEST(MeshBvh, SmallModelFarFromItsOriginGetsABalancedTree) {
  const Soup soup = meshfix::scaled(meshfix::icosphere(1.0, 4), 1e-4, Vec(1e4, -2e4, 3e4));  // 5120 triangles
  const TriangleMesh m = meshfix::makeMesh(soup);
  EXPECT_LE(m.bvh().tree.depth, 16);
  std::mt19937_64 rng(23);
  for (const Vec& q : meshfix::queryPoints(soup, 300, 0.05, 0.3, rng))
    ASSERT_NEAR(std::abs(m.closestPoint(q).signedDistance), meshfix::bruteDistance(soup, q), 1e-13 * 2e-4);
  // Every vertex is inside the ball of the node cells along the way down to it.
  std::vector<SurfaceCell> cells = m.surfaceCells();
  for (int level = 0; level < 6; ++level) {
    for (const Vec& v : soup.vertices) {
      bool inside = false;
      for (const SurfaceCell& c : cells) inside = inside || (v - c.center).norm() <= c.radius;
      ASSERT_TRUE(inside) << level;
    }
    std::vector<SurfaceCell> next;
    for (const SurfaceCell& c : cells) m.splitCell(c, next);
    cells = std::move(next);
  }
}

TEST(MeshBvh, BuildTimeAndMemoryAreReported) {
  for (int n : {71, 224}) {  // 2·n·n/2 triangles: ~10k and ~100k
    const Soup soup = meshfix::torus(0.8, 0.25, 2 * n, n / 2);
    const TriangleMesh m = meshfix::makeMesh(soup);
    const std::size_t base = m.memoryBytes();
    (void)m.closestPoint(Vec(0.1, 0.2, 0.3));
    const double tris = static_cast<double>(m.triangles().size());
    std::printf("[ info     ] %zu triangles: hierarchy built in %.2f ms, %.1f bytes/triangle (model %.1f, total %.1f)\n",
                m.triangles().size(), m.bvhBuildMicroseconds() / 1000, (m.memoryBytes() - base) / tris, base / tris,
                m.memoryBytes() / tris);
    EXPECT_EQ(m.bvhBuildCount(), 1);
    EXPECT_LT(m.bvh().tree.depth, unidist::mesh::kMaxBvhDepth);
  }
}

// ---------------------------------------------------------------------------------------------------------
// The existing generic path answers mesh pairs.

// Distance between segment [p0, p1] and segment [a, b] by ternary search on the first parameter (the
// distance to a convex set along a segment is convex).
double segmentSegment(const Vec& p0, const Vec& p1, const Vec& a, const Vec& b) {
  auto f = [&](double s) {
    return std::sqrt(static_cast<double>(meshfix::segmentSq(meshfix::toL(p0 + s * (p1 - p0)), meshfix::toL(a), meshfix::toL(b))));
  };
  double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) < f(m2)) hi = m2; else lo = m1;
  }
  return std::min({f(0.5 * (lo + hi)), f(0), f(1)});
}

TEST(MeshGeneric, CapsuleToMeshDistanceMatchesBruteForce) {
  const Soup soup = meshfix::torus(0.8, 0.25, 24, 12);
  const TriangleMesh mesh = meshfix::makeMesh(soup);
  const unidist::Capsule capsule(0.1, 0.3);
  Eigen::Isometry3d X_WM = Eigen::Isometry3d::Identity();
  X_WM.linear() = Eigen::AngleAxisd(0.3, Vec(1, 2, 3).normalized()).toRotationMatrix();
  X_WM.translation() = Vec(0.1, -0.2, 0.05);
  Eigen::Isometry3d X_WC = Eigen::Isometry3d::Identity();
  X_WC.linear() = Eigen::AngleAxisd(1.1, Vec(-1, 0.5, 0.2).normalized()).toRotationMatrix();
  X_WC.translation() = X_WM * Vec(1.45, 0.3, 0.2);
  // Truth: segment–triangle distances (no crossing when the result exceeds the radius) minus the radius.
  const Vec p0 = X_WM.inverse() * (X_WC * Vec(0, 0, -0.3)), p1 = X_WM.inverse() * (X_WC * Vec(0, 0, 0.3));
  double best = 1e300;
  for (const Tri& t : soup.triangles) {
    const Vec a = soup.vertices[t[0]], b = soup.vertices[t[1]], c = soup.vertices[t[2]];
    best = std::min({best, static_cast<double>(std::sqrt(meshfix::triangleSq(p0, a, b, c))),
                     static_cast<double>(std::sqrt(meshfix::triangleSq(p1, a, b, c))), segmentSegment(p0, p1, a, b),
                     segmentSegment(p0, p1, b, c), segmentSegment(p0, p1, c, a)});
  }
  const double truth = best - 0.1;
  ASSERT_GT(truth, 0.05);
  for (bool swap : {false, true}) {
    const auto r = swap ? unidist::distance(capsule, X_WC, mesh, X_WM) : unidist::distance(mesh, X_WM, capsule, X_WC);
    SCOPED_TRACE(std::string(r.method) + (swap ? " (capsule first)" : ""));
    EXPECT_NEAR(r.distance, truth, 1e-8);
    EXPECT_LE(r.lowerBound, truth + 1e-12);
    EXPECT_GE(r.upperBound, truth - 1e-12);
    EXPECT_LE((r.pointB - r.pointA - r.distance * r.normal).norm(), 1e-9);
  }
}

}  // namespace
