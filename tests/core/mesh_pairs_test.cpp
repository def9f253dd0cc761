// Mesh–mesh, mesh–cloud and cloud–cloud global distance (core/src/pairs/mesh_mesh.cpp) against exact brute
// force over all triangle pairs (triangle–triangle distance written again here in long double: vertex–triangle
// from the fixtures, segment–segment by normal equations with endpoint fallbacks, and an edge–plane crossing
// test with barycentric coordinates), at fixed random poses. Also the node volumes the search prunes with:
// every rectangle swept sphere (RSS) holds its node's triangles, and the RSS–RSS lower bound never exceeds
// the brute-force distance between two nodes' triangles (flat and sliver nodes, scales 1e-4 to 1e4).
#include "core/mesh_fixtures.h"
#include "mesh/bvh.h"
#include "mesh/point_triangle.h"
#include "mesh/rss.h"
#include "mesh/triangle_triangle.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <memory>
#include <random>
#include <string>
#include <vector>

namespace {

using meshfix::LD;
using meshfix::Soup;
using meshfix::Tri;
using meshfix::Vec;
using meshfix::VecL;
using unidist::DistanceResult;
using unidist::PointCloud;
using unidist::TriangleMesh;

using meshfix::edgeCrosses;
using meshfix::segSegSq;
using meshfix::triTriSq;

/// A shape for the tests: a mesh soup or a cloud (no triangles).
struct Shape {
  Soup soup;
  bool cloud = false;
};

std::vector<VecL> posedPoints(const Shape& s, const Eigen::Isometry3d& X) {
  std::vector<VecL> out;
  for (const Vec& v : s.soup.vertices) out.push_back(X.cast<LD>() * meshfix::toL(v));
  return out;
}

/// Exact unsigned distance between the two posed shapes by brute force.
double bruteDistance(const Shape& a, const Eigen::Isometry3d& Xa, const Shape& b, const Eigen::Isometry3d& Xb) {
  const std::vector<VecL> pa = posedPoints(a, Xa), pb = posedPoints(b, Xb);
  LD best = std::numeric_limits<LD>::infinity();
  auto pt = [](const VecL& v) { return Vec(static_cast<double>(v.x()), static_cast<double>(v.y()), static_cast<double>(v.z())); };
  if (a.cloud && b.cloud) {
    for (const VecL& p : pa)
      for (const VecL& q : pb) best = std::min(best, (p - q).squaredNorm());
  } else if (a.cloud || b.cloud) {
    const Shape& m = a.cloud ? b : a;
    const std::vector<VecL>& pm = a.cloud ? pb : pa;
    const std::vector<VecL>& pc = a.cloud ? pa : pb;
    for (const Tri& t : m.soup.triangles)
      for (const VecL& q : pc) best = std::min(best, meshfix::triangleSq(pt(q), pt(pm[t[0]]), pt(pm[t[1]]), pt(pm[t[2]])));
  } else {
    // Every pair, except those a ball around each triangle proves farther than the best so far (exact skip).
    auto balls = [](const Soup& soup, const std::vector<VecL>& p) {
      std::vector<std::pair<VecL, LD>> out;
      for (const Tri& t : soup.triangles) {
        const VecL c = (p[t[0]] + p[t[1]] + p[t[2]]) / 3;
        out.push_back({c, 1.000001L * std::max({(p[t[0]] - c).norm(), (p[t[1]] - c).norm(), (p[t[2]] - c).norm()})});
      }
      return out;
    };
    const auto ba = balls(a.soup, pa), bb = balls(b.soup, pb);
    for (std::size_t i = 0; i < a.soup.triangles.size(); ++i)
      for (std::size_t j = 0; j < b.soup.triangles.size(); ++j) {
        const LD gap = (ba[i].first - bb[j].first).norm() - ba[i].second - bb[j].second;
        if (gap > 0 && gap * gap > best * 1.000001L) continue;
        const Tri& s = a.soup.triangles[i];
        const Tri& t = b.soup.triangles[j];
        best = std::min(best, triTriSq({pa[s[0]], pa[s[1]], pa[s[2]]}, {pb[t[0]], pb[t[1]], pb[t[2]]}));
      }
  }
  return static_cast<double>(std::sqrt(best));
}

std::unique_ptr<unidist::Model> build(const Shape& s) {
  if (s.cloud) return std::make_unique<PointCloud>(s.soup.vertices);
  return std::make_unique<TriangleMesh>(s.soup.vertices, s.soup.triangles);
}

Shape cloudOf(const Soup& s, int count, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  Shape c;
  c.cloud = true;
  c.soup.vertices = meshfix::queryPoints(s, count, 0.02, 0.0, rng);
  return c;
}

Eigen::Isometry3d randomPose(std::mt19937_64& rng, double reach) {
  std::normal_distribution<double> n01;
  std::uniform_real_distribution<double> u(-reach, reach);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng)).normalized().toRotationMatrix();
  X.translation() = Vec(u(rng), u(rng), u(rng));
  return X;
}

double surfaceDistance(const unidist::Model& m, const Eigen::Isometry3d& X, const Vec& p_W) {
  return std::abs(m.closestPoint(X.inverse() * p_W).signedDistance);
}

/// Checks one separated query against the truth (both argument orders).
void checkSeparated(const Shape& a, const Eigen::Isometry3d& Xa, const Shape& b, const Eigen::Isometry3d& Xb,
                    double truth, const std::string& what) {
  const auto ma = build(a), mb = build(b);
  const DistanceResult r = unidist::distance(*ma, Xa, *mb, Xb);
  const DistanceResult s = unidist::distance(*mb, Xb, *ma, Xa);
  const double tol = unidist::defaultTolerance(*ma, Xa, *mb, Xb);
  const double size = std::max(ma->localBounds().diagonal(), mb->localBounds().diagonal());
  const double slack = tol + 1e-13 * size;
  SCOPED_TRACE(what + " truth=" + std::to_string(truth) + " method=" + r.method);
  EXPECT_NEAR(r.distance, truth, slack);
  EXPECT_NEAR(s.distance, truth, slack);
  EXPECT_NEAR(r.distance, s.distance, slack);
  EXPECT_LE(r.lowerBound, truth + 1e-13 * size);
  EXPECT_GE(r.upperBound, truth - 1e-13 * size);
  EXPECT_LE(s.lowerBound, truth + 1e-13 * size);
  EXPECT_GE(s.upperBound, truth - 1e-13 * size);
  EXPECT_EQ(r.status, unidist::Status::Certified);
  EXPECT_EQ(s.status, unidist::Status::Certified);
  EXPECT_NEAR(r.normal.norm(), 1.0, 1e-12);
  EXPECT_LE((r.pointB - r.pointA - r.distance * r.normal).norm(), slack);
  EXPECT_LE((s.pointB - s.pointA - s.distance * s.normal).norm(), slack);
  EXPECT_LE(surfaceDistance(*ma, Xa, r.pointA), slack);
  EXPECT_LE(surfaceDistance(*mb, Xb, r.pointB), slack);
}

struct Family {
  std::string name;
  Shape shape;
};

std::vector<Family> families() {
  std::vector<Family> f;
  f.push_back({"sphere320", {meshfix::icosphere(0.6, 2), false}});
  f.push_back({"torus1k", {meshfix::torus(0.8, 0.25, 32, 16), false}});
  f.push_back({"box", {meshfix::gridBox(Vec(0.5, 0.3, 0.4), 4), false}});
  f.push_back({"sheet", {meshfix::wavySheet(12), false}});
  f.push_back({"cloud", cloudOf(meshfix::torus(0.7, 0.2, 24, 12), 300, 7)});
  return f;
}

TEST(MeshPairs, SeparatedRandomPosesMatchBruteForce) {
  const std::vector<Family> fam = families();
  std::mt19937_64 rng(20261122);
  int checked = 0;
  for (std::size_t i = 0; i < fam.size(); ++i)
    for (std::size_t j = i; j < fam.size(); ++j)
      for (int k = 0; k < 6; ++k) {
        const Eigen::Isometry3d Xa = randomPose(rng, 0.5), Xb = randomPose(rng, 1.6);
        const double truth = bruteDistance(fam[i].shape, Xa, fam[j].shape, Xb);
        if (truth < 1e-3) continue;  // crossing or touching: other tests
        const auto ma = build(fam[i].shape), mb = build(fam[j].shape);
        // Containment is an overlap, not a separation (a small shape in the torus is not contained).
        if (ma->isSolid() && ma->inside(Xa.inverse() * (Xb * fam[j].shape.soup.vertices[0]))) continue;
        if (mb->isSolid() && mb->inside(Xb.inverse() * (Xa * fam[i].shape.soup.vertices[0]))) continue;
        // A cloud reaching into a solid has a negative (signed) answer: the overlap tests cover it.
        auto cloudInside = [](const Shape& c, const Eigen::Isometry3d& Xc, const unidist::Model& solid,
                              const Eigen::Isometry3d& Xs) {
          if (!c.cloud || !solid.isSolid()) return false;
          for (const Vec& p : c.soup.vertices)
            if (solid.inside(Xs.inverse() * (Xc * p))) return true;
          return false;
        };
        if (cloudInside(fam[i].shape, Xa, *mb, Xb) || cloudInside(fam[j].shape, Xb, *ma, Xa)) continue;
        checkSeparated(fam[i].shape, Xa, fam[j].shape, Xb, truth, fam[i].name + "/" + fam[j].name + " #" + std::to_string(k));
        ++checked;
      }
  EXPECT_GT(checked, 50);
}

TEST(MeshPairs, ScalesSmallAndLarge) {
  const std::vector<Family> fam = families();
  std::mt19937_64 rng(99);
  for (double scale : {1e-4, 1e4}) {
    for (std::size_t i = 0; i < fam.size(); ++i) {
      const std::size_t j = (i + 1) % fam.size();
      Shape a = fam[i].shape, b = fam[j].shape;
      a.soup = meshfix::scaled(a.soup, scale);
      b.soup = meshfix::scaled(b.soup, scale, Vec(1e3 * scale, 0, 0));  // far from the origin too
      Eigen::Isometry3d Xa = randomPose(rng, 0.3), Xb = randomPose(rng, 0.3);
      Xa.translation() *= scale;
      Xb.translation() = Xb.translation() * scale - Xb.linear() * Vec(1e3 * scale, 0, 0) + Vec(2.2 * scale, 0, 0);
      const double truth = bruteDistance(a, Xa, b, Xb);
      if (truth < 1e-3 * scale) continue;
      checkSeparated(a, Xa, b, Xb, truth, fam[i].name + "/" + fam[j].name + " scale " + std::to_string(scale));
    }
  }
}

TEST(MeshPairs, NearParallelFaces) {
  const Shape box{meshfix::gridBox(Vec(0.5, 0.5, 0.5), 3), false};
  const Shape sheet{meshfix::wavySheet(6), false};
  for (double gap : {1e-3, 1e-7}) {
    for (const Vec& axis : {Vec(0, 1, 0), Vec(0, 0, 1), Vec(0, 1, 1).normalized()}) {
      Eigen::Isometry3d Xa = Eigen::Isometry3d::Identity(), Xb = Eigen::Isometry3d::Identity();
      Xb.linear() = Eigen::AngleAxisd(1e-6, axis).toRotationMatrix();
      Xb.translation() = Vec(1.0 + gap + 1e-6, 0.1, -0.05);
      const double truth = bruteDistance(box, Xa, box, Xb);
      checkSeparated(box, Xa, box, Xb, truth, "box/box gap " + std::to_string(gap));
      // The same near-parallel approach with the open sheet (not convex, so through the hierarchy).
      Eigen::Isometry3d Xs = Eigen::Isometry3d::Identity();
      Xs.linear() = Eigen::AngleAxisd(1e-6, axis).toRotationMatrix();
      Xs.translation() = Vec(0, 0, 0.5 + 0.2 + gap + 2e-6);
      const double truthSheet = bruteDistance(box, Xa, sheet, Xs);
      checkSeparated(box, Xa, sheet, Xs, truthSheet, "box/sheet gap " + std::to_string(gap));
    }
  }
}

TEST(MeshPairs, TouchingIsExactlyZero) {
  // Two boxes face to face (convex: through GJK), a box and a torus touching at the torus's outer equator
  // (through the hierarchy, then the overlap routine), two sheets touching at a point.
  const Shape box{meshfix::gridBox(Vec(0.5, 0.5, 0.5), 2), false};
  {
    const auto m = build(box);
    Eigen::Isometry3d Xb = Eigen::Isometry3d::Identity();
    Xb.translation() = Vec(1.0, 0.25, 0.125);
    const DistanceResult r = unidist::distance(*m, Eigen::Isometry3d::Identity(), *m, Xb);
    EXPECT_NEAR(r.distance, 0.0, 1e-12);
    EXPECT_LE(r.lowerBound, 0.0);
    EXPECT_GE(r.upperBound, 0.0);
  }
  {
    const Shape sheet{meshfix::wavySheet(8), false};
    const auto m = build(sheet);
    // Lift B so its lowest vertex touches A's highest one exactly: the sheet values at grid points are known.
    double top = -1e9, bottom = 1e9;
    Vec topV = Vec::Zero(), bottomV = Vec::Zero();
    for (const Vec& v : sheet.soup.vertices) {
      if (v.z() > top) top = v.z(), topV = v;
      if (v.z() < bottom) bottom = v.z(), bottomV = v;
    }
    Eigen::Isometry3d Xb = Eigen::Isometry3d::Identity();
    Xb.translation() = topV - bottomV;
    const DistanceResult r = unidist::distance(*m, Eigen::Isometry3d::Identity(), *m, Xb);
    EXPECT_EQ(r.distance, 0.0);
    EXPECT_EQ(r.lowerBound, 0.0);
    EXPECT_EQ(r.upperBound, 0.0);
    EXPECT_EQ(r.status, unidist::Status::Certified);
    EXPECT_NEAR(r.normal.norm(), 1.0, 1e-12);
  }
}

TEST(MeshPairs, CrossingOpenSurfacesGiveZeroOnBoth) {
  const Shape sheet{meshfix::wavySheet(10), false};
  const auto m = build(sheet);
  std::mt19937_64 rng(5);
  for (int k = 0; k < 5; ++k) {
    Eigen::Isometry3d Xb = randomPose(rng, 0.2);
    const DistanceResult r = unidist::distance(*m, Eigen::Isometry3d::Identity(), *m, Xb);
    ASSERT_EQ(bruteDistance(sheet, Eigen::Isometry3d::Identity(), sheet, Xb), 0.0);
    EXPECT_EQ(r.distance, 0.0);
    EXPECT_EQ(r.status, unidist::Status::Certified);
    EXPECT_LE(surfaceDistance(*m, Eigen::Isometry3d::Identity(), r.pointA), 1e-12);
    EXPECT_LE(surfaceDistance(*m, Xb, r.pointB), 1e-12);
  }
}

TEST(MeshPairs, CloudPointInsideSolidIsNegative) {
  const Shape sphere{meshfix::icosphere(1.0, 2), false};
  Shape cloud;
  cloud.cloud = true;
  cloud.soup.vertices = {Vec(0.5, 0, 0), Vec(3, 0, 0), Vec(0, 4, 0)};
  const auto ms = build(sphere), mc = build(cloud);
  const DistanceResult r = unidist::distance(*ms, Eigen::Isometry3d::Identity(), *mc, Eigen::Isometry3d::Identity());
  EXPECT_LT(r.distance, -0.4);
  EXPECT_GT(r.distance, -0.5);
  EXPECT_LE(r.lowerBound, r.distance);
  EXPECT_GE(r.upperBound, r.distance);
  // The whole cloud outside: the plain minimum.
  cloud.soup.vertices = {Vec(1.5, 0, 0), Vec(3, 0, 0)};
  const auto mc2 = build(cloud);
  const DistanceResult s = unidist::distance(*mc2, Eigen::Isometry3d::Identity(), *ms, Eigen::Isometry3d::Identity());
  EXPECT_NEAR(s.distance, bruteDistance(cloud, Eigen::Isometry3d::Identity(), sphere, Eigen::Isometry3d::Identity()), 1e-9);
  EXPECT_EQ(s.status, unidist::Status::Certified);
}

TEST(MeshPairs, SphereInsideHollowIsAnOverlap) {
  // A small ball wholly inside a big one: surfaces apart, but the solids overlap (containment).
  const Shape big{meshfix::torus(1.0, 0.5, 24, 12), false};
  const Shape small{meshfix::icosphere(0.1, 1), false};
  const auto mb = build(big), ms = build(small);
  Eigen::Isometry3d Xs = Eigen::Isometry3d::Identity();
  Xs.translation() = Vec(1.0, 0, 0);
  const DistanceResult r = unidist::distance(*mb, Eigen::Isometry3d::Identity(), *ms, Xs);
  EXPECT_LT(r.distance, 0.0);
  EXPECT_LE(r.lowerBound, r.distance);
}

TEST(MeshPairs, BudgetExhaustedIsBoundedAndHonest) {
  const Shape t{meshfix::torus(0.8, 0.25, 32, 16), false};
  const auto m = build(t);
  Eigen::Isometry3d Xb = Eigen::Isometry3d::Identity();
  Xb.linear() = Eigen::AngleAxisd(M_PI / 2, Vec::UnitX()).toRotationMatrix();
  Xb.translation() = Vec(0.8, 0, 0);  // linked rings, 0.3 apart everywhere along the link
  unidist::DistanceOptions o;
  o.maxIterations = 1;
  const DistanceResult r = unidist::distance(*m, Eigen::Isometry3d::Identity(), *m, Xb, o);
  const double truth = bruteDistance(t, Eigen::Isometry3d::Identity(), t, Xb);
  EXPECT_LE(r.lowerBound, truth);
  EXPECT_GE(r.upperBound, truth);
  EXPECT_NEAR(truth, 0.3, 0.05);
  EXPECT_EQ(r.status, unidist::Status::Bounded);
}

// ---- Node volumes (mesh/rss.h) -------------------------------------------------------------------------

/// Distance (long double) from p to the RSS's rectangle, minus its radius: <= 0 when p is inside.
LD outsideRss(const unidist::mesh::Rss& r, const Vec& p) {
  const VecL d = meshfix::toL(p) - meshfix::toL(r.center);
  const Eigen::Matrix<LD, 3, 3> U = r.axes.cast<LD>();
  const LD x = U.col(0).dot(d), y = U.col(1).dot(d), z = U.col(2).dot(d);
  const LD hx = r.half[0], hy = r.half[1];
  const LD gx = std::max<LD>(0, std::abs(x) - hx), gy = std::max<LD>(0, std::abs(y) - hy);
  return std::sqrt(gx * gx + gy * gy + z * z) - static_cast<LD>(r.radius);
}

/// Meshes with awkward nodes: curved, boxy, flat (every node's RSS has radius ~0), slivers (needle triangles
/// along a line: nodes with one side ~0), at scales 1e-4, 1 and 1e4, the small and large ones far from the origin.
std::vector<Family> volumeFamilies() {
  std::vector<Family> f;
  f.push_back({"torus", {meshfix::torus(0.8, 0.25, 24, 12), false}});
  f.push_back({"box", {meshfix::gridBox(Vec(0.5, 0.3, 0.4), 3), false}});
  Soup flat = meshfix::wavySheet(8);
  for (Vec& v : flat.vertices) v.z() = 0;
  f.push_back({"flat", {flat, false}});
  Soup needle;
  for (int i = 0; i <= 24; ++i) {
    needle.vertices.emplace_back(0.1 * i, 0, 0);
    needle.vertices.emplace_back(0.1 * i + 0.05, 1e-7 * (1 + i % 3), 1e-8 * i);
  }
  for (std::uint32_t i = 0; i + 3 < needle.vertices.size(); i += 2) {
    needle.triangles.push_back({i, i + 2, i + 1});
    needle.triangles.push_back({i + 1, i + 2, i + 3});
  }
  f.push_back({"sliver", {needle, false}});
  const std::size_t base = f.size();
  for (double k : {1e-4, 1e4})
    for (std::size_t i = 0; i < base; ++i)
      f.push_back({f[i].name + " x" + std::to_string(k), {meshfix::scaled(f[i].shape.soup, k, Vec(3e3 * k, -1e3 * k, 0)), false}});
  return f;
}

TEST(MeshVolumes, EveryTriangleIsInsideItsNodesRss) {
  for (const Family& fam : volumeFamilies()) {
    const TriangleMesh m(fam.shape.soup.vertices, fam.shape.soup.triangles);
    const unidist::mesh::MeshBvh& h = m.bvh();
    EXPECT_FALSE(h.rssFitted());
    const auto& rss = h.rss(m.vertices(), m.triangles());
    ASSERT_TRUE(h.rssFitted());
    ASSERT_EQ(rss.size(), h.tree.nodes.size());
    LD worst = -1;
    for (std::size_t n = 0; n < rss.size(); ++n) {
      ASSERT_TRUE(rss[n].axes.allFinite() && std::isfinite(rss[n].radius)) << fam.name;
      // The volume is convex and a triangle is the hull of its vertices: the vertices suffice.
      for (std::uint32_t s = h.ranges[n][0]; s < h.ranges[n][1]; ++s)
        for (std::uint32_t v : m.triangles()[h.tree.order[s]]) worst = std::max(worst, outsideRss(rss[n], m.vertices()[v]));
    }
    EXPECT_LE(worst, 0.0L) << fam.name;
  }
}

TEST(MeshVolumes, LargeHierarchiesOnHugePageBoundariesHoldTheirTriangles) {
  // ~45k triangles: the nodes, ranges and RSS arrays pass BigArrayAllocator's threshold (mesh/big_array.h),
  // so this is the path large meshes take; the volumes must be as sound as on the ordinary path.
  const Soup t = meshfix::torus(1.0, 0.3, 212, 106);
  const TriangleMesh m(t.vertices, t.triangles);
  const unidist::mesh::MeshBvh& h = m.bvh();
  const auto& rss = h.rss(m.vertices(), m.triangles());
  using unidist::mesh::BigArrayAllocator;
  ASSERT_TRUE(BigArrayAllocator<unidist::mesh::Rss>::big(rss.size()));
  ASSERT_TRUE(BigArrayAllocator<unidist::mesh::BvhNode>::big(h.tree.nodes.size()));
  for (const void* p : {static_cast<const void*>(rss.data()), static_cast<const void*>(h.tree.nodes.data())})
    EXPECT_EQ(reinterpret_cast<std::uintptr_t>(p) % unidist::mesh::kHugePageBytes, 0u);
  LD worst = -1;
  for (std::size_t n = 0; n < rss.size(); ++n)
    for (std::uint32_t s = h.ranges[n][0]; s < h.ranges[n][1]; ++s)
      for (std::uint32_t v : m.triangles()[h.tree.order[s]]) worst = std::max(worst, outsideRss(rss[n], m.vertices()[v]));
  EXPECT_LE(worst, 0.0L);
}

TEST(MeshVolumes, BigVectorKeepsItsElementsAcrossTheThreshold) {
  // Growing from ordinary memory past the threshold moves the elements into a huge-page-aligned buffer;
  // shrinking back below it returns to the ordinary allocator.
  unidist::mesh::BigVector<std::uint64_t> v;
  const std::size_t big = unidist::mesh::kBigArrayBytes / sizeof(std::uint64_t) + 1;
  for (std::uint64_t i = 0; i < big; ++i) v.push_back(i * 2654435761u);
  EXPECT_EQ(reinterpret_cast<std::uintptr_t>(v.data()) % unidist::mesh::kHugePageBytes, 0u);
  for (std::uint64_t i = 0; i < big; ++i) ASSERT_EQ(v[i], i * 2654435761u);
  // Memory reports count whole huge pages.
  const std::size_t footprint = unidist::mesh::footprintBytes(v);
  EXPECT_EQ(footprint % unidist::mesh::kHugePageBytes, 0u);
  EXPECT_GE(footprint, v.capacity() * sizeof(std::uint64_t));
  EXPECT_LT(footprint, v.capacity() * sizeof(std::uint64_t) + unidist::mesh::kHugePageBytes);
  v.resize(10);
  v.shrink_to_fit();
  ASSERT_EQ(v.size(), 10u);
  for (std::uint64_t i = 0; i < 10; ++i) EXPECT_EQ(v[i], i * 2654435761u);
  EXPECT_EQ(unidist::mesh::footprintBytes(v), v.capacity() * sizeof(std::uint64_t));
}

TEST(MeshVolumes, FitHoldsDegeneratePointSets) {
  const std::vector<std::vector<Vec>> sets = {
      {Vec(1, 2, 3)}, {Vec(1, 2, 3), Vec(1, 2, 3), Vec(1, 2, 3)}, {Vec(0, 0, 0), Vec(1, 1, 1), Vec(2, 2, 2)},
      {Vec(1e4, 0, 0), Vec(1e4 + 1e-6, 0, 0), Vec(1e4, 1e-6, 0)}};
  for (const auto& pts : sets) {
    const unidist::mesh::Rss r = unidist::mesh::fitRss(pts.data(), pts.size());
    ASSERT_TRUE(r.axes.allFinite());
    EXPECT_NEAR((r.axes.transpose() * r.axes - Eigen::Matrix3d::Identity()).norm(), 0.0, 1e-14);
    for (const Vec& p : pts) EXPECT_LE(outsideRss(r, p), 0.0L);
  }
}

/// A random rotation (columns orthonormal, right-handed).
Eigen::Matrix3d randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n01;
  return Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng)).normalized().toRotationMatrix();
}

/// Worst departure of U from a right-handed orthonormal frame.
double frameError(const Eigen::Matrix3d& U) {
  return std::max((U.transpose() * U - Eigen::Matrix3d::Identity()).cwiseAbs().maxCoeff(),
                  (U.col(0).cross(U.col(1)) - U.col(2)).cwiseAbs().maxCoeff());
}

TEST(MeshVolumes, PrincipalAxesFromAnyGuessAreOrthonormal) {
  // The fit pads for axes orthonormal to a few ε, whatever the covariance (flat, round, a line, nothing) and
  // however far the guess.
  std::mt19937_64 rng(2718);
  const std::vector<Vec> spectra = {Vec(1, 0.3, 1e-3), Vec(1, 1, 0), Vec(1, 0, 0), Vec(0, 0, 0), Vec(1, 1, 1),
                                    Vec(1e-12, 1e-13, 0), Vec(1e8, 2e8, 3e8)};
  for (const Vec& spectrum : spectra)
    for (int k = 0; k < 200; ++k) {
      const Eigen::Matrix3d Q = randomRotation(rng);
      const Eigen::Matrix3d C = Q * spectrum.asDiagonal() * Q.transpose();
      const Eigen::Matrix3d guess = k % 2 ? randomRotation(rng) : Q * randomRotation(rng).transpose() * randomRotation(rng);
      const Eigen::Matrix3d U = unidist::mesh::principalAxesFrom(C, guess);
      ASSERT_TRUE(U.allFinite());
      EXPECT_LE(frameError(U), 8 * std::numeric_limits<double>::epsilon()) << spectrum.transpose() << " #" << k;
    }
}

TEST(MeshVolumes, PrincipalAxesFromANearGuessFindTheAxes) {
  // A child's axes a few degrees off its parent's: the result is as principal as a direct solve, to second
  // order in the guess's error.
  std::mt19937_64 rng(31415);
  std::normal_distribution<double> n01;
  for (int k = 0; k < 500; ++k) {
    const Eigen::Matrix3d Q = randomRotation(rng);
    const Eigen::Matrix3d C = Q * Vec(1, 0.3, 1e-3).asDiagonal() * Q.transpose();
    const Vec axis = Vec(n01(rng), n01(rng), n01(rng)).normalized();
    const Eigen::Matrix3d guess = Q * Eigen::AngleAxisd(0.03, axis).toRotationMatrix();
    const Eigen::Matrix3d U = unidist::mesh::principalAxesFrom(C, guess);
    for (int c = 0; c < 3; ++c) EXPECT_GT(std::abs(U.col(c).dot(Q.col(c))), std::cos(5e-3)) << "#" << k << " axis " << c;
  }
}

TEST(MeshVolumes, MergedVolumeHoldsBothChildrensPointsInItsBox) {
  // mergeRss bounds the children by their boxes [±half0, ±half1, ±radius]: every point of either child must
  // lie in the merged RSS and in its box, on any axes, at any scale and offset.
  std::mt19937_64 rng(1618);
  std::normal_distribution<double> n01;
  for (int k = 0; k < 300; ++k) {
    const double scale = std::pow(10.0, static_cast<double>(k % 9) - 4);
    const Vec offset = Vec(n01(rng), n01(rng), n01(rng)) * scale * (k % 3 == 0 ? 1e3 : 1.0);
    std::vector<Vec> left, right;
    const Vec shift = Vec(n01(rng), n01(rng), n01(rng)) * scale;
    const Vec flat(1, 0.5, k % 4 == 0 ? 0.0 : 0.05);
    for (int i = 0; i < 12; ++i) {
      left.push_back(offset + scale * Vec(n01(rng), n01(rng), n01(rng)).cwiseProduct(flat));
      right.push_back(offset + shift + scale * Vec(n01(rng), n01(rng), n01(rng)).cwiseProduct(flat));
    }
    const auto a = unidist::mesh::fitRss(randomRotation(rng), left.data(), left.size());
    const auto b = unidist::mesh::fitRss(randomRotation(rng), right.data(), right.size());
    const auto m = unidist::mesh::mergeRss(randomRotation(rng), a, b);
    for (const auto* set : {&left, &right})
      for (const Vec& p : *set) {
        EXPECT_LE(outsideRss(m, p), 0.0L) << "#" << k;
        const VecL d = meshfix::toL(p) - meshfix::toL(m.center);
        const Eigen::Matrix<LD, 3, 3> U = m.axes.cast<LD>();
        EXPECT_LE(std::abs(U.col(0).dot(d)), static_cast<LD>(m.half[0])) << "#" << k;
        EXPECT_LE(std::abs(U.col(1).dot(d)), static_cast<LD>(m.half[1])) << "#" << k;
        EXPECT_LE(std::abs(U.col(2).dot(d)), static_cast<LD>(m.radius)) << "#" << k;
      }
  }
}

TEST(MeshVolumes, RssLowerBoundNeverExceedsTheTrianglesDistance) {
  const std::vector<Family> fam = volumeFamilies();
  std::mt19937_64 rng(424242);
  int checked = 0, useful = 0;
  for (std::size_t i = 0; i < fam.size(); ++i) {
    const std::size_t j = (i * 5 + 3) % fam.size();
    const Soup& sa = fam[i].shape.soup;
    const Soup& sb = fam[j].shape.soup;
    const TriangleMesh ma(sa.vertices, sa.triangles), mb(sb.vertices, sb.triangles);
    const auto& ha = ma.bvh();
    const auto& hb = mb.bvh();
    const auto& ra = ha.rss(ma.vertices(), ma.triangles());
    const auto& rb = hb.rss(mb.vertices(), mb.triangles());
    const double size = std::max(ma.localBounds().diagonal(), mb.localBounds().diagonal());
    for (int k = 0; k < 30; ++k) {
      // B posed near A: B's centre moved to A's centre, then shifted by up to the size.
      Eigen::Isometry3d X = randomPose(rng, 0.0);
      X.translation() = ma.localBounds().center() - X.linear() * mb.localBounds().center() +
                        size * Vec::Random() * (k % 3 == 0 ? 0.05 : 0.6);
      // Random nodes of at most 64 triangles (brute force stays cheap), both small and large.
      auto pick = [&](const unidist::mesh::MeshBvh& h) {
        for (;;) {
          const auto n = static_cast<std::uint32_t>(rng() % h.tree.nodes.size());
          if (h.ranges[n][1] - h.ranges[n][0] <= 64) return n;
        }
      };
      const std::uint32_t na = pick(ha), nb = pick(hb);
      LD truth = std::numeric_limits<LD>::infinity();
      for (std::uint32_t s = ha.ranges[na][0]; s < ha.ranges[na][1]; ++s)
        for (std::uint32_t u = hb.ranges[nb][0]; u < hb.ranges[nb][1]; ++u) {
          const auto& ta = ma.triangles()[ha.tree.order[s]];
          const auto& tb = mb.triangles()[hb.tree.order[u]];
          const std::array<VecL, 3> A = {meshfix::toL(ma.vertices()[ta[0]]), meshfix::toL(ma.vertices()[ta[1]]),
                                         meshfix::toL(ma.vertices()[ta[2]])};
          std::array<VecL, 3> B;
          for (int c = 0; c < 3; ++c) B[c] = X.cast<LD>() * meshfix::toL(mb.vertices()[tb[c]]);
          truth = std::min(truth, triTriSq(A, B));
        }
      truth = std::sqrt(truth);
      const double lb = unidist::mesh::rssLowerBound(ra[na], rb[nb], X.linear(), X.translation());
      const double early = unidist::mesh::rssLowerBound(ra[na], rb[nb], X.linear(), X.translation(), 0.5 * lb);
      // Rounding of the coordinates (a few ε of the scale) is the callers' slack, not the bound's.
      const LD slack = 1e-13L * static_cast<LD>(size + X.translation().norm());
      EXPECT_LE(static_cast<LD>(lb), truth + slack) << fam[i].name << " / " << fam[j].name << " #" << k;
      EXPECT_LE(static_cast<LD>(early), truth + slack) << fam[i].name << " / " << fam[j].name << " #" << k;
      ++checked;
      if (truth > 0 && lb > 0.5 * static_cast<double>(truth)) ++useful;
    }
  }
  EXPECT_EQ(checked, static_cast<int>(fam.size()) * 30);
  EXPECT_GT(useful, checked / 4);  // not vacuous: the bound is close on many separated pairs
}

// The exact triangle pair alone (it skips edge pairs on proved lower bounds and solves only interior edge–edge
// points), against triTriSq on pairs made to hit those skips: generic, slivers, collinear and repeated-vertex
// triangles, parallel and coplanar ones (touching or overlapping), parallel edges, shared vertices, far from
// the origin; each also with a cutoff around the answer.
TEST(TriangleTriangle, SkipsKeepTheExactAnswerOnDegenerateAndParallelPairs) {
  std::mt19937_64 rng(20261122);
  std::uniform_real_distribution<double> U(-1, 1);
  const auto rnd = [&] { return Vec(U(rng), U(rng), U(rng)); };
  int finite = 0, zero = 0, cut = 0;
  for (int it = 0; it < 60000; ++it) {
    const int kind = it % 8;
    Vec a[3] = {rnd(), rnd(), rnd()}, b[3] = {rnd(), rnd(), rnd()};
    const Vec shift = rnd() * (kind == 0 ? 3.0 : 1.0);
    for (Vec& v : b) v += shift;
    const Vec n = (a[1] - a[0]).cross(a[2] - a[0]).normalized();
    const double h = std::array<double, 4>{0.0, 1e-9, 1e-3, 0.3}[static_cast<std::size_t>(it / 8 % 4)];
    switch (kind) {
      case 1: a[2] = 0.5 * (a[0] + a[1]) + 1e-9 * rnd(); break;               // sliver
      case 2: b[2] = b[0] + 0.37 * (b[1] - b[0]); if (it % 16 < 8) b[1] = b[0]; break;  // collinear / repeated
      case 3:                                                                   // parallel planes, coplanar at h = 0
        for (Vec& v : b) v = a[0] + 0.6 * ((v - shift) - (v - shift).dot(n) * n) + h * n;
        break;
      case 4: b[1] = b[0] + 0.8 * (a[1] - a[0]); break;                         // an edge parallel to one of A's
      case 5: b[0] = a[static_cast<std::size_t>(it / 8 % 3)]; break;            // a shared vertex
      case 6:                                                                   // in A's plane, touching an edge
        b[0] = a[0] + 0.5 * (a[1] - a[0]);
        for (int k = 1; k < 3; ++k) b[k] = b[0] + (b[k] - b[0]) - (b[k] - b[0]).dot(n) * n + h * n;
        break;
      case 7: for (Vec& v : a) v += Vec(1e3, -2e3, 5e2); for (Vec& v : b) v += Vec(1e3, -2e3, 5e2); break;
      default: break;
    }
    const std::array<VecL, 3> A{meshfix::toL(a[0]), meshfix::toL(a[1]), meshfix::toL(a[2])};
    const std::array<VecL, 3> B{meshfix::toL(b[0]), meshfix::toL(b[1]), meshfix::toL(b[2])};
    const double truth = static_cast<double>(std::sqrt(triTriSq(A, B, kind != 2)));
    double scale = 1;
    for (int k = 0; k < 3; ++k)
      scale = std::max({scale, a[k].lpNorm<Eigen::Infinity>(), b[k].lpNorm<Eigen::Infinity>()});
    const double tol = 1e-13 * scale;
    const Vec na = unidist::mesh::accurateUnitNormal(a[0], a[1], a[2]);
    const Vec nb = unidist::mesh::accurateUnitNormal(b[0], b[1], b[2]);
    const std::string what = "case " + std::to_string(it) + " kind " + std::to_string(kind);
    const auto c = unidist::mesh::closestTriangleTriangle(a, na, b, nb);
    ASSERT_NEAR(c.distance, truth, tol) << what;
    ASSERT_NEAR((c.pointA - c.pointB).norm(), c.distance, tol) << what;
    // Points on their triangles. Inside a sliver or a nearly collinear triangle the oracle's barycentric solve
    // is itself unreliable (its determinant cancels), so there a point within 1e-8 of an edge passes too.
    const double width = kind == 1 || kind == 2 ? 1e-8 : 0.0;
    const auto onTriangle = [&](const Vec& p, const Vec* t) {
      const VecL q = meshfix::toL(p);
      LD d = meshfix::triangleSq(p, t[0], t[1], t[2]);
      for (int k = 0; k < 3; ++k)
        d = std::min(d, meshfix::segmentSq(q, meshfix::toL(t[k]), meshfix::toL(t[(k + 1) % 3])));
      return std::sqrt(static_cast<double>(d));
    };
    ASSERT_LE(onTriangle(c.pointA, a), tol + width) << what;
    ASSERT_LE(onTriangle(c.pointB, b), tol + width) << what;
    (truth > tol ? finite : zero) += 1;
    // A cutoff on either side of the answer: below it the exact answer must come back; at or above it the
    // routine may stop early (infinity, or a feature distance it had measured, never below the truth).
    const double cutoff = truth * (0.5 + std::uniform_real_distribution<double>(0, 1)(rng));
    const auto d = unidist::mesh::closestTriangleTriangle(a, na, b, nb, cutoff);
    if (d.distance >= cutoff - tol) {
      ASSERT_GE(truth, cutoff - tol) << what;
      ASSERT_GE(d.distance, truth - tol) << what;
      ++cut;
    } else {
      ASSERT_NEAR(d.distance, truth, tol) << what;
    }
  }
  EXPECT_GT(zero, 1000);  // touching and crossing pairs are exercised
  EXPECT_GT(finite, 30000);
  EXPECT_GT(cut, 10000);
}

TEST(MeshVolumes, LinkedToriMatchBruteForceThroughTheRssSearch) {
  // The case the RSS bounds were added for: a whole circle of triangle pairs at nearly the same distance.
  const Shape t{meshfix::torus(1.0, 0.25, 32, 16), false};
  Eigen::Isometry3d Xb = Eigen::Isometry3d::Identity();
  Xb.linear() = Eigen::AngleAxisd(M_PI / 2, Vec::UnitX()).toRotationMatrix();
  Xb.translation() = Vec(1.0, 0, 0);
  const double truth = bruteDistance(t, Eigen::Isometry3d::Identity(), t, Xb);
  checkSeparated(t, Eigen::Isometry3d::Identity(), t, Xb, truth, "linked tori");
  for (double k : {1e-4, 1e4}) {
    const Shape s{meshfix::scaled(t.soup, k, Vec(2e3 * k, 0, 0)), false};
    Eigen::Isometry3d Xa = Eigen::Isometry3d::Identity(), Xs = Xb;
    Xa.translation() = Vec(-2e3 * k, 0, 0);
    Xs.translation() = k * Vec(1.0, 0, 0) - Xb.linear() * Vec(2e3 * k, 0, 0);
    checkSeparated(s, Xa, s, Xs, bruteDistance(s, Xa, s, Xs), "linked tori x" + std::to_string(k));
  }
}

}  // namespace
