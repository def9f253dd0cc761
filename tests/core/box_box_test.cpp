// Tests of the exact box–box signed distance (core/src/pairs/box_box.cpp).
//
// Oracles, written here and independent of the code under test:
//  * apart: the distance of two disjoint convex polytopes is attained between a vertex and the other solid or
//    between two edges, so it is the minimum over the 16 vertex–box distances (clamp in the box frame) and the
//    144 edge–edge distances (ternary search on one parameter of the exact point–segment distance);
//  * overlapping: the depth is the origin's distance to the boundary of D = hull{a_i − b_j} (64 points), i.e.
//    the smallest h_D(n) over the facets of D; the facets are found by brute force over all triples of the 64
//    points (a plane through three of them with every point on one side). Using h_D(n) = max_k n·(a_i − b_j) as
//    the value makes every accepted plane, even one with a rounding-blurred normal, an upper bound on the depth,
//    and the true facets are among them: the oracle is exact to rounding;
//  * a dense set of directions: the overlap along any direction is >= the depth (a weaker, separate check).
#include "core/case_budget.h"
#include "pairs/box_box.h"

#include <gtest/gtest.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

namespace {

using Eigen::Isometry3d;
using Eigen::Vector3d;
using unidist::detail::boxBox;
using unidist::detail::ConvexDistance;
using unidist::detail::convexDistance;
using unidist::detail::SupportFn;

using namespace unidist::testing;

struct Box {
  Vector3d h;
  Isometry3d X;
};

std::array<Vector3d, 8> corners(const Box& b) {
  std::array<Vector3d, 8> c;
  for (int i = 0; i < 8; ++i)
    c[i] = b.X * Vector3d((i & 1) ? b.h.x() : -b.h.x(), (i & 2) ? b.h.y() : -b.h.y(), (i & 4) ? b.h.z() : -b.h.z());
  return c;
}

std::vector<std::pair<Vector3d, Vector3d>> edges(const Box& b) {
  const auto c = corners(b);
  std::vector<std::pair<Vector3d, Vector3d>> e;
  for (int i = 0; i < 8; ++i)
    for (int bit : {1, 2, 4})
      if (!(i & bit)) e.emplace_back(c[i], c[i | bit]);
  return e;
}

double pointSegmentDistance(const Vector3d& p, const Vector3d& a, const Vector3d& b) {
  const Vector3d d = b - a;
  const double t = std::clamp((p - a).dot(d) / d.squaredNorm(), 0.0, 1.0);
  return (p - (a + t * d)).norm();
}

double segmentSegmentOracle(const Vector3d& p1, const Vector3d& q1, const Vector3d& p2, const Vector3d& q2) {
  auto f = [&](double s) { return pointSegmentDistance(p1 + s * (q1 - p1), p2, q2); };
  double lo = 0, hi = 1;
  for (int i = 0; i < 200; ++i) {
    const double m1 = lo + (hi - lo) / 3, m2 = hi - (hi - lo) / 3;
    if (f(m1) <= f(m2)) hi = m2; else lo = m1;
  }
  return std::min({f(0.5 * (lo + hi)), f(0), f(1)});
}

double pointBoxDistance(const Vector3d& p, const Box& b) {
  const Vector3d q = b.X.inverse() * p;
  return (q - q.cwiseMax(-b.h).cwiseMin(b.h)).norm();
}

// Distance of two disjoint boxes by brute force over vertex–solid and edge–edge pairs.
double separatedOracle(const Box& a, const Box& b) {
  double d = kInf;
  for (const Vector3d& c : corners(a)) d = std::min(d, pointBoxDistance(c, b));
  for (const Vector3d& c : corners(b)) d = std::min(d, pointBoxDistance(c, a));
  for (const auto& ea : edges(a))
    for (const auto& eb : edges(b)) d = std::min(d, segmentSegmentOracle(ea.first, ea.second, eb.first, eb.second));
  return d;
}

// Penetration depth by facet enumeration of hull{a_i − b_j} (see the file comment).
double depthOracle(const Box& a, const Box& b, double planeTol) {
  std::vector<Vector3d> pts;
  for (const Vector3d& p : corners(a))
    for (const Vector3d& q : corners(b)) pts.push_back(p - q);
  const int n = static_cast<int>(pts.size());
  double best = kInf;
  for (int i = 0; i < n; ++i)
    for (int j = i + 1; j < n; ++j)
      for (int k = j + 1; k < n; ++k) {
        Vector3d nrm = (pts[j] - pts[i]).cross(pts[k] - pts[i]);
        const double len = nrm.norm();
        if (!(len > 1e-300)) continue;
        nrm /= len;
        const double off = nrm.dot(pts[i]);
        double hi = -kInf, lo = kInf;
        for (const Vector3d& p : pts) {
          const double x = nrm.dot(p);
          hi = std::max(hi, x);
          lo = std::min(lo, x);
        }
        if (hi <= off + planeTol) best = std::min(best, hi);
        if (lo >= off - planeTol) best = std::min(best, -lo);
      }
  return best;
}

// Overlap of the boxes' projections on unit n: min(h_D(n), h_D(−n)).
double overlapAlong(const Box& a, const Box& b, const Vector3d& n) {
  double aMin = kInf, aMax = -kInf, bMin = kInf, bMax = -kInf;
  for (const Vector3d& c : corners(a)) {
    aMin = std::min(aMin, n.dot(c));
    aMax = std::max(aMax, n.dot(c));
  }
  for (const Vector3d& c : corners(b)) {
    bMin = std::min(bMin, n.dot(c));
    bMax = std::max(bMax, n.dot(c));
  }
  return std::min(aMax - bMin, bMax - aMin);
}

double denseDirectionDepth(const Box& a, const Box& b, int samples) {
  double best = kInf;
  const double golden = kPi * (3 - std::sqrt(5.0));
  for (int i = 0; i < samples; ++i) {
    const double z = 1 - 2 * (i + 0.5) / samples, rho = std::sqrt(1 - z * z);
    best = std::min(best, overlapAlong(a, b, Vector3d(rho * std::cos(golden * i), rho * std::sin(golden * i), z)));
  }
  return best;
}

double boxSignedDistance(const Vector3d& p, const Box& b) {
  const Vector3d q = (b.X.inverse() * p).cwiseAbs() - b.h;
  return q.cwiseMax(0.0).norm() + std::min(q.maxCoeff(), 0.0);
}

SupportFn boxSupport(const Box& b) {
  return [b](const Vector3d& dW) {
    const Vector3d d = b.X.linear().transpose() * dW;
    return Vector3d(b.X * Vector3d(d.x() >= 0 ? b.h.x() : -b.h.x(), d.y() >= 0 ? b.h.y() : -b.h.y(),
                                   d.z() >= 0 ? b.h.z() : -b.h.z()));
  };
}

Isometry3d randomPose(std::mt19937_64& rng, double extent) {
  std::normal_distribution<double> N(0, 1);
  std::uniform_real_distribution<double> U(-extent, extent);
  Isometry3d X = Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(N(rng), N(rng), N(rng), N(rng)).normalized().toRotationMatrix();
  X.translation() = Vector3d(U(rng), U(rng), U(rng));
  return X;
}

ConvexDistance run(const Box& a, const Box& b, double tol) { return boxBox(a.h, a.X, b.h, b.X, tol); }

// Contract checks common to every answer. size: sum of the box diagonals; slack: rounding allowance.
void expectContract(const ConvexDistance& r, const Box& a, const Box& b, double truth, double tol, double slack) {
  EXPECT_NEAR(r.distance, truth, tol + slack);
  EXPECT_LE(r.lowerBound, truth + slack);
  EXPECT_GE(r.upperBound, truth - slack);
  EXPECT_LE(r.lowerBound, r.distance);
  EXPECT_LE(r.distance, r.upperBound);
  EXPECT_NEAR(r.normal.norm(), 1.0, 1e-14);
  EXPECT_LE((r.pointB - r.pointA - r.distance * r.normal).norm(), slack);
  EXPECT_LE(std::abs(boxSignedDistance(r.pointA, a)), tol + slack) << "pointA not on A";
  EXPECT_LE(std::abs(boxSignedDistance(r.pointB, b)), tol + slack) << "pointB not on B";
}

// Moving B by −s·distance·normal: for overlap both 0.99 (still overlapping) and 1.01 (apart) always hold; apart,
// 0.99 keeps the sign and 1.01 leaves at most 1 % of the distance (it overlaps unless the contact is a glancing
// corner or edge, counted by the caller).
bool moveInvariants(const ConvexDistance& r, const Box& a, const Box& b, double tol) {
  auto moved = [&](double s) {
    Box c = b;
    c.X.translation() -= s * r.distance * r.normal;
    return run(a, c, tol);
  };
  const ConvexDistance keep = moved(0.99), flip = moved(1.01);
  EXPECT_GT(keep.distance * r.distance, 0);
  if (r.distance < 0) {
    EXPECT_GT(flip.distance, 0);
  } else {
    EXPECT_LE(flip.distance, 0.01 * r.distance + tol);
  }
  return flip.distance * r.distance < 0;
}

TEST(BoxBox, CoincidentBoxesDepthIsSmallestFullExtent) {
  // Two identical boxes at the same pose: B must move by the smallest full extent, 2·0.3, along ±y of the box.
  const Vector3d h(0.5, 0.3, 0.8);
  std::mt19937_64 rng(1);
  for (int i = 0; i < cases(20); ++i) {
    const Isometry3d X = i == 0 ? Isometry3d::Identity() : randomPose(rng, 2.0);
    const Box a{h, X}, b{h, X};
    for (double tol : {1e-9, 0.0}) {
      const auto r = run(a, b, tol);
      SCOPED_TRACE("i=" + std::to_string(i));
      // Exact: 0.3 + 0.3 − 0 in double. Rotated poses round the axis products: 1e-15.
      if (i == 0) {
        EXPECT_EQ(r.distance, -0.6);
      }
      expectContract(r, a, b, -0.6, 0, 1e-14);
      EXPECT_NEAR(std::abs(r.normal.dot(X.linear().col(1))), 1.0, 1e-14);
      EXPECT_TRUE(r.converged);
    }
  }
}

TEST(BoxBox, SeparatedRandomPosesAgainstBruteForce) {
  std::mt19937_64 rng(2718);
  std::uniform_real_distribution<double> H(0.05, 1.0);
  int separated = 0, flips = 0, moves = 0;
  double worst = 0;
  int maxIts = 0;
  for (int i = 0; i < cases(400) && separated < cases(150); ++i) {
    const Box a{Vector3d(H(rng), H(rng), H(rng)), randomPose(rng, 0.5)};
    const Box b{Vector3d(H(rng), H(rng), H(rng)), randomPose(rng, 2.5)};
    const double size = 2 * (a.h.norm() + b.h.norm());
    if (denseDirectionDepth(a, b, 500) >= 0) continue;  // keep the pairs some sampled axis proves apart
    const double truth = separatedOracle(a, b);
    ++separated;
    // GJK ends exactly on polytopes: 1e-12·size; slack 1e-13·size for the oracle's and our rounding.
    const double tol = 1e-12 * size;
    const auto r = run(a, b, tol);
    SCOPED_TRACE("i=" + std::to_string(i) + " truth=" + std::to_string(truth));
    expectContract(r, a, b, truth, tol, 1e-13 * size);
    EXPECT_TRUE(r.converged);
    worst = std::max(worst, std::abs(r.distance - truth) / size);
    maxIts = std::max(maxIts, r.iterations);
    ++moves;
    flips += moveInvariants(r, a, b, tol);
  }
  EXPECT_GE(separated, cases(100));
  EXPECT_GT(flips, moves / 2);
  RecordProperty("worst_relative_error", sci(worst));
  RecordProperty("max_iterations", maxIts);
}

TEST(BoxBox, PenetratingRandomPosesAgainstFacetEnumeration) {
  std::mt19937_64 rng(16180);
  std::uniform_real_distribution<double> H(0.1, 1.0);
  int penetrating = 0;
  double worst = 0;
  for (int i = 0; i < cases(300) && penetrating < cases(80); ++i) {
    const Box a{Vector3d(H(rng), H(rng), H(rng)), randomPose(rng, 0.3)};
    const Box b{Vector3d(H(rng), H(rng), H(rng)), randomPose(rng, 1.0)};
    const double size = 2 * (a.h.norm() + b.h.norm());
    const double dense = denseDirectionDepth(a, b, 2000);
    if (dense <= 0) continue;  // apart along some sampled direction
    const double depth = depthOracle(a, b, 1e-12 * size);
    ++penetrating;
    const auto r = run(a, b, 1e-9 * size);
    SCOPED_TRACE("i=" + std::to_string(i) + " depth=" + std::to_string(depth));
    // SAT is exact: rounding only, 1e-14·size.
    expectContract(r, a, b, -depth, 0, 1e-14 * size);
    EXPECT_LE(-r.distance, dense + 1e-14 * size);  // no sampled direction separates with less
    EXPECT_TRUE(moveInvariants(r, a, b, 1e-9 * size));
    worst = std::max(worst, std::abs(r.distance + depth) / size);
  }
  EXPECT_GE(penetrating, cases(50));
  RecordProperty("worst_relative_error", sci(worst));
}

TEST(BoxBox, NearParallelFacesExactTo1em11) {
  // B rests over A's top face, tilted by a tiny angle about a random axis, apart by a gap g or overlapping by −g.
  // The truth is by brute force (apart) or facet enumeration (overlap), both exact to rounding; the budget is
  // 1e-11 absolute on sizes ~1.
  std::mt19937_64 rng(555);
  std::normal_distribution<double> N(0, 1);
  for (double angle : {1e-3, 1e-5, 1e-7, 1e-9, 0.0}) {
    for (int k = 0; k < cases(4); ++k) {
      const Vector3d axis = Vector3d(N(rng), N(rng), N(rng)).normalized();
      for (double gap : {1e-3, 1e-7, 1e-10, -1e-10, -1e-7, -1e-3}) {
        const Box a{Vector3d(1.0, 0.7, 0.4), Isometry3d::Identity()};
        Box b{Vector3d(0.6, 0.5, 0.3), Isometry3d::Identity()};
        b.X.linear() = Eigen::AngleAxisd(angle, axis).toRotationMatrix();
        // Place B's lowest vertex at height 0.4 + gap (over A's top face); the oracles decide the truth exactly.
        double lowest = kInf;
        for (const Vector3d& c : corners(b)) lowest = std::min(lowest, c.z());
        b.X.translation() = Vector3d(0.1, 0.05, 0.4 + gap - lowest);
        const double truth = gap > 0 ? separatedOracle(a, b) : -depthOracle(a, b, 1e-13);
        SCOPED_TRACE("angle=" + std::to_string(angle) + " k=" + std::to_string(k) + " gap=" + std::to_string(gap));
        ASSERT_GT(truth * gap, 0);
        for (double tol : {1e-12, 0.0}) {
          const auto r = run(a, b, tol);
          EXPECT_NEAR(r.distance, truth, 1e-11);
          expectContract(r, a, b, truth, 1e-12, 1e-13);
          EXPECT_GT(r.normal.z(), 0.999);  // B moves up / A is below
        }
      }
    }
  }
}

TEST(BoxBox, TouchingFaceToFaceIsZero) {
  // Exactly representable contacts: face on face (B's bottom at z = 0.4), B rotated 30° about z (still face on
  // face), and an edge of B (rotated 45° about x) lying on A's top face.
  const Box a{Vector3d(1.0, 0.7, 0.4), Isometry3d::Identity()};
  Box b{Vector3d(0.5, 0.25, 0.5), Isometry3d::Identity()};
  b.X.translation() = Vector3d(0.25, -0.125, 0.9);
  Box c = b;
  c.X.linear() = Eigen::AngleAxisd(kPi / 6, Vector3d::UnitZ()).toRotationMatrix();
  Box e{Vector3d(0.5, 0.25, 0.25), Isometry3d::Identity()};
  e.X.linear() = Eigen::AngleAxisd(kPi / 4, Vector3d::UnitX()).toRotationMatrix();
  e.X.translation() = Vector3d(0, 0, 0.4 + 0.25 * std::sqrt(2.0));
  for (const Box& top : {b, c, e}) {
    for (double tol : {1e-9, 0.0}) {
      const auto r = run(a, top, tol);
      EXPECT_NEAR(r.distance, 0.0, 1e-15);
      EXPECT_LE(r.lowerBound, 1e-15);
      EXPECT_GE(r.upperBound, -1e-15);
      EXPECT_LE((r.pointB - r.pointA - r.distance * r.normal).norm(), 1e-15);
      EXPECT_NEAR(r.pointA.z(), 0.4, 1e-15);
      EXPECT_LE(std::abs(boxSignedDistance(r.pointB, top)), 1e-15);
      EXPECT_NEAR(std::abs(r.normal.z()), 1.0, 1e-12);
    }
  }
}

TEST(BoxBox, ScalesKeepRelativeAccuracy) {
  // The same configurations at 1e-4 and 1e4, placed 1e3 sizes from the world origin: relative accuracy holds
  // because everything is computed in A's frame (world rounding enters once, ~1e-16 × |position|).
  std::mt19937_64 rng(99);
  std::uniform_real_distribution<double> H(0.1, 1.0);
  for (double scale : {1e-4, 1.0, 1e4}) {
    int apart = 0, overlap = 0;
    for (int i = 0; i < cases(120); ++i) {
      Box a{scale * Vector3d(H(rng), H(rng), H(rng)), randomPose(rng, 0.5)};
      Box b{scale * Vector3d(H(rng), H(rng), H(rng)), randomPose(rng, 1.5)};
      const Vector3d far = scale * Vector3d(1e3, -2e3, 5e2);
      a.X.translation() = scale * a.X.translation() + far;
      b.X.translation() = scale * b.X.translation() + far;
      const double size = 2 * (a.h.norm() + b.h.norm());
      const double dense = denseDirectionDepth(a, b, 300);
      double truth;
      if (dense > 0) {
        // Overlapping (no sampled direction separates): facet enumeration in A's frame for a fair oracle.
        if (++overlap > cases(12)) continue;
        Box al{a.h, Isometry3d::Identity()}, bl{b.h, a.X.inverse() * b.X};
        truth = -depthOracle(al, bl, 1e-12 * size);
      } else {
        if (++apart > cases(30)) continue;
        truth = separatedOracle(a, b);
      }
      const double tol = 1e-9 * size;  // the library default
      const auto r = run(a, b, tol);
      SCOPED_TRACE("scale=" + std::to_string(scale) + " i=" + std::to_string(i));
      // Slack: rounding of world coordinates ~1e3 sizes from the origin (1e-16 × 2e3 × size), with margin.
      expectContract(r, a, b, truth, tol, 1e-12 * size);
    }
    EXPECT_GT(apart, cases(10));
    EXPECT_GT(overlap, cases(5));
  }
}

TEST(BoxBox, AgreesWithGenericConvexDistance) {
  // The exact pair function and GJK/EPA on the boxes' support maps answer the same question.
  std::mt19937_64 rng(4);
  std::uniform_real_distribution<double> H(0.1, 1.0);
  for (int i = 0; i < cases(200); ++i) {
    const Box a{Vector3d(H(rng), H(rng), H(rng)), randomPose(rng, 0.5)};
    const Box b{Vector3d(H(rng), H(rng), H(rng)), randomPose(rng, 1.5)};
    const double size = 2 * (a.h.norm() + b.h.norm());
    const auto exact = run(a, b, 1e-12 * size);
    const auto generic = convexDistance(boxSupport(a), boxSupport(b), 1e-12 * size, 1000);
    // Both are exact on polytopes (EPA ends on the true facet); 1e-12·size covers both tolerances and rounding.
    EXPECT_NEAR(exact.distance, generic.distance, 2e-12 * size) << "i=" << i;
    EXPECT_TRUE(generic.converged) << "i=" << i;
  }
}

}  // namespace
