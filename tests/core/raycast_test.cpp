// Ray casting (unidist/raycast.h) against independent answers: closed-form ray–sphere and ray–box (slabs), the
// first root of the torus's analytic signed distance found by dense sampling and bisection, and a brute-force
// ray–triangle loop over a tessellated sphere. Also: rays starting inside, point clouds (hit within the
// tolerance of a point), unbounded half-spaces, the step cap on a grazing run, and bad input.
#include "core/mesh_fixtures.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"
#include "unidist/raycast.h"

#include <gtest/gtest.h>

#include <chrono>
#include <cmath>
#include <optional>
#include <random>

namespace {

using unidist::raycast;
using unidist::RayHit;
using Vec = Eigen::Vector3d;
using Iso = Eigen::Isometry3d;

Iso randomPose(std::mt19937_64& rng) {
  std::uniform_real_distribution<double> u(-1, 1);
  Iso X = Iso::Identity();
  X.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  X.translation() = Vec(u(rng), u(rng), u(rng));
  return X;
}

Vec randomUnit(std::mt19937_64& rng) {
  std::normal_distribution<double> n;
  return Vec(n(rng), n(rng), n(rng)).normalized();
}

/// A ray from a random point at distance ~3 aimed at a random point near the model's centre.
struct Ray {
  Vec origin, dir;
};
Ray aimedRay(std::mt19937_64& rng, const Vec& centre, double spread) {
  const Vec origin = centre + 3 * randomUnit(rng);
  const Vec target = centre + spread * randomUnit(rng);
  return {origin, (target - origin).normalized()};
}

/// Closed form: first t >= 0 with |o + t d − c| = r (the exit when o is inside), or nothing.
std::optional<double> raySphere(const Vec& o, const Vec& d, const Vec& c, double r, double& margin) {
  const Vec q = o - c;
  const double B = q.dot(d), C = q.squaredNorm() - r * r, k = B * B - C;
  margin = std::abs(k);
  if (k < 0) return std::nullopt;
  double t = -B - std::sqrt(k);
  if (t < 0) t = -B + std::sqrt(k);
  if (t < 0) return std::nullopt;
  return t;
}

TEST(Raycast, SphereMatchesClosedForm) {
  std::mt19937_64 rng(1);
  const unidist::Sphere sphere(0.7);
  const double tol = 1e-7;
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    const Iso X = randomPose(rng);
    const Ray ray = aimedRay(rng, X.translation(), 1.0);
    double margin = 0;
    const auto truth = raySphere(ray.origin, ray.dir, X.translation(), 0.7, margin);
    if (margin < 1e-4) continue;  // grazing within the tolerance: either answer is right
    const RayHit h = raycast(sphere, X, ray.origin, ray.dir, 10, tol);
    ASSERT_EQ(h.hit, truth.has_value()) << i;
    if (!truth) continue;
    ++hits;
    // t is exact up to the tolerance over the slope at which the ray meets the surface (tangent rays).
    const double slope = std::sqrt(margin) / 0.7;
    EXPECT_NEAR(h.t, *truth, std::max(1e-9, 2 * tol / slope)) << i;
    const Vec outward = (h.point - X.translation()).normalized();
    EXPECT_NEAR((h.normal - outward).norm(), 0, 1e-6) << i;
    EXPECT_LE(h.normal.dot(ray.dir), 0);
    EXPECT_FALSE(h.startedInside);
  }
  EXPECT_GT(hits, 100);
}

TEST(Raycast, InsideStartReportsTheExitFacingTheRay) {
  const unidist::Sphere sphere(2);
  const RayHit h = raycast(sphere, Iso::Identity(), Vec(0.5, 0, 0), Vec(1, 0, 0), 10, 1e-8);
  ASSERT_TRUE(h.hit);
  EXPECT_TRUE(h.startedInside);
  EXPECT_NEAR(h.t, 1.5, 1e-9);
  EXPECT_NEAR((h.normal - Vec(-1, 0, 0)).norm(), 0, 1e-9);  // inward: the side the ray comes from
  const RayHit shortRay = raycast(sphere, Iso::Identity(), Vec(0.5, 0, 0), Vec(1, 0, 0), 1.4, 1e-8);
  EXPECT_FALSE(shortRay.hit);
}

TEST(Raycast, BoxMatchesSlabs) {
  std::mt19937_64 rng(2);
  const Vec h(0.4, 0.6, 0.3);
  const unidist::Box box(h);
  int hits = 0;
  for (int i = 0; i < 400; ++i) {
    const Iso X = randomPose(rng);
    const Ray ray = aimedRay(rng, X.translation(), 1.0);
    const Vec o = X.inverse() * ray.origin, d = X.linear().transpose() * ray.dir;
    double lo = -1e300, hi = 1e300;
    int face = -1;
    for (int k = 0; k < 3; ++k) {
      double a = (-h[k] - o[k]) / d[k], b = (h[k] - o[k]) / d[k];
      if (a > b) std::swap(a, b);
      if (a > lo) lo = a, face = k;
      hi = std::min(hi, b);
    }
    const bool truth = lo <= hi && lo >= 0;
    if (std::abs(lo - hi) < 1e-4) continue;  // clipping an edge within the tolerance
    const RayHit r = raycast(box, X, ray.origin, ray.dir, 10, 1e-7);
    ASSERT_EQ(r.hit, truth) << i;
    if (!truth) continue;
    ++hits;
    EXPECT_NEAR(r.t, lo, 1e-9) << i;
    Vec n = Vec::Zero();
    n[face] = d[face] > 0 ? -1 : 1;
    EXPECT_NEAR((r.normal - X.linear() * n).norm(), 0, 1e-6) << i;
  }
  EXPECT_GT(hits, 60);
}

/// Analytic signed distance of the torus (R, r) about z.
double torusDistance(const Vec& p, double R, double r) {
  return std::hypot(std::hypot(p.x(), p.y()) - R, p.z()) - r;
}

TEST(Raycast, TorusMatchesDenseSampling) {
  std::mt19937_64 rng(3);
  const double R = 1, r = 0.3;
  const unidist::Torus torus(R, r);
  int hits = 0, checked = 0;
  for (int i = 0; i < 200; ++i) {
    const Iso X = randomPose(rng);
    const Ray ray = aimedRay(rng, X.translation(), 1.3);
    const Vec o = X.inverse() * ray.origin, d = X.linear().transpose() * ray.dir;
    // First sign change of the analytic distance on a fine grid, then bisection; skip near-tangent rays.
    const double step = 1e-3;
    std::optional<double> truth;
    double closest = 1e9;
    for (double t = 0; t < 6 && !truth; t += step) {
      const double f0 = torusDistance(o + t * d, R, r), f1 = torusDistance(o + (t + step) * d, R, r);
      closest = std::min(closest, std::abs(f0));
      if (f0 > 0 && f1 <= 0) {
        double a = t, b = t + step;
        for (int k = 0; k < 60; ++k) {
          const double m = 0.5 * (a + b);
          (torusDistance(o + m * d, R, r) > 0 ? a : b) = m;
        }
        truth = a;
      }
    }
    if (closest < 2e-3 && !truth) continue;  // grazing: the grid may have stepped over a tangent touch
    const RayHit h = raycast(torus, X, ray.origin, ray.dir, 6, 1e-7);
    ++checked;
    ASSERT_EQ(h.hit, truth.has_value()) << i;
    if (!truth) continue;
    ++hits;
    const Vec p = o + *truth * d;
    Vec radial(p.x(), p.y(), 0);
    radial = radial.normalized() * R;
    const double slope = std::abs(d.dot((p - radial).normalized()));  // cosine of the incidence
    EXPECT_NEAR(h.t, *truth, std::max(1e-8, 2e-7 / slope)) << i;
    EXPECT_NEAR(torusDistance(X.inverse() * h.point, R, r), 0, 1e-7) << i;
  }
  EXPECT_GT(hits, 60);
  EXPECT_GT(checked, 150);
}

/// Möller–Trumbore over every triangle: the smallest t >= 0.
std::optional<double> bruteRayMesh(const meshfix::Soup& s, const Vec& o, const Vec& d) {
  std::optional<double> best;
  for (const auto& tri : s.triangles) {
    const Vec a = s.vertices[tri[0]], e1 = s.vertices[tri[1]] - a, e2 = s.vertices[tri[2]] - a;
    const Vec p = d.cross(e2);
    const double det = e1.dot(p);
    if (std::abs(det) < 1e-14) continue;
    const Vec tv = o - a;
    const double u = tv.dot(p) / det;
    const Vec q = tv.cross(e1);
    const double v = d.dot(q) / det, t = e2.dot(q) / det;
    if (u < 0 || v < 0 || u + v > 1 || t < 0) continue;
    if (!best || t < *best) best = t;
  }
  return best;
}

TEST(Raycast, MeshMatchesBruteForce) {
  std::mt19937_64 rng(4);
  const meshfix::Soup soup = meshfix::icosphere(0.8, 2);
  const unidist::TriangleMesh mesh = meshfix::makeMesh(soup);
  int hits = 0;
  for (int i = 0; i < 300; ++i) {
    const Iso X = randomPose(rng);
    const Ray ray = aimedRay(rng, X.translation(), 1.0);
    const Vec o = X.inverse() * ray.origin, d = X.linear().transpose() * ray.dir;
    const auto truth = bruteRayMesh(soup, o, d);
    // Skip rays that pass within 1e-4 of the silhouette (either answer is within the tolerance there).
    const RayHit nearMiss = raycast(mesh, X, ray.origin, ray.dir, 10, 1e-4);
    if (nearMiss.hit != truth.has_value()) {
      ASSERT_FALSE(truth.has_value());
      continue;
    }
    const RayHit h = raycast(mesh, X, ray.origin, ray.dir, 10, 1e-8);
    ASSERT_EQ(h.hit, truth.has_value()) << i;
    if (!truth) continue;
    ++hits;
    EXPECT_NEAR(h.t, *truth, 1e-7) << i;
    const Vec n = X.linear() * mesh.faceNormal(h.feature);
    EXPECT_LE(h.normal.dot(ray.dir), 0);
    EXPECT_GT(n.dot(h.normal), 0.5) << i;  // the face normal (or its edge/vertex pseudo-normal)
  }
  EXPECT_GT(hits, 80);
}

TEST(Raycast, PointCloudHitsWithinTolerance) {
  std::vector<Vec> pts;
  for (int i = 0; i < 10; ++i)
    for (int j = 0; j < 10; ++j) pts.emplace_back(0.1 * i, 0.1 * j, 0);
  const unidist::PointCloud cloud(pts);
  const double tol = 1e-3;
  // Straight down onto point (3, 4): hit at t = 1 (within the tolerance), feature = that point.
  const RayHit on = raycast(cloud, Iso::Identity(), Vec(0.3, 0.4, 1), Vec(0, 0, -1), 5, tol);
  ASSERT_TRUE(on.hit);
  EXPECT_NEAR(on.t, 1, tol);
  EXPECT_EQ(on.feature, 34);
  EXPECT_NEAR(on.normal.z(), 1, 1e-9);
  // Between the points (0.05 off every point): no hit.
  const RayHit between = raycast(cloud, Iso::Identity(), Vec(0.35, 0.45, 1), Vec(0, 0, -1), 5, tol);
  EXPECT_FALSE(between.hit);
  // Passing 0.5·tol beside a point: hit; 2·tol: miss.
  EXPECT_TRUE(raycast(cloud, Iso::Identity(), Vec(0.3 + 0.5 * tol, 0.4, 1), Vec(0, 0, -1), 5, tol).hit);
  EXPECT_FALSE(raycast(cloud, Iso::Identity(), Vec(0.3 + 2 * tol, 0.4, 1), Vec(0, 0, -1), 5, tol).hit);
}

TEST(Raycast, HalfSpaceAndStepCap) {
  const unidist::Plane ground(Vec(0, 0, 1), 0);
  const Vec down = Vec(1, 0, -1).normalized();
  const RayHit h = raycast(ground, Iso::Identity(), Vec(0, 0, 2), down, 100, 1e-9);
  ASSERT_TRUE(h.hit);
  EXPECT_NEAR(h.t, 2 * std::sqrt(2.0), 1e-9);
  EXPECT_NEAR(h.point.z(), 0, 1e-9);
  // A run parallel to the plane just above the tolerance must end by the cap, not hang.
  const auto start = std::chrono::steady_clock::now();
  const RayHit graze = raycast(ground, Iso::Identity(), Vec(0, 0, 2e-6), Vec(1, 0, 0), 1e6, 1e-6);
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  EXPECT_FALSE(graze.hit);
  EXPECT_TRUE(graze.exhausted);
  EXPECT_LT(seconds, 5);
  // Missing the bounds altogether: no stepping at all, no hit.
  const unidist::Sphere s(1);
  EXPECT_FALSE(raycast(s, Iso::Identity(), Vec(0, 5, 0), Vec(1, 0, 0), 1e9, 1e-9).hit);
}

TEST(Raycast, RejectsBadInput) {
  const unidist::Sphere s(1);
  EXPECT_THROW(raycast(s, Iso::Identity(), Vec(0, 0, 5), Vec(0, 0, -2), 10, 1e-6), unidist::InputError);
  EXPECT_THROW(raycast(s, Iso::Identity(), Vec(0, 0, 5), Vec(0, 0, -1), -1, 1e-6), unidist::InputError);
  EXPECT_THROW(raycast(s, Iso::Identity(), Vec(0, 0, 5), Vec(0, 0, -1), 10, 0), unidist::InputError);
  EXPECT_THROW(raycast(s, Iso::Identity(), Vec(0, 0, NAN), Vec(0, 0, -1), 10, 1e-6), unidist::InputError);
}

}  // namespace
