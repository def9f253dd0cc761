// The certified support value of a patch along a direction (core/src/nurbs/support_bound.cpp) against exact
// truth on the rational sphere and torus, and against dense sampling refined around its best sample on random
// subpatches of the sphere, the torus and the bicubic wavy patch: never below the surface, exact to rounding
// where proved, refused where the patch does not curve away (a saddle, a patch seen from behind).
#include "nurbs/bspline.h"
#include "nurbs/patch_tree.h"
#include "nurbs/support_bound.h"
#include "nurbs_fixtures.h"
#include "unidist/nurbs.h"

#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>

namespace unidist {
namespace {

using namespace nurbs_fixtures;
using Vec = Eigen::Vector3d;

/// max of f(S) over the patch by a 101² grid, then finer grids around the best sample (each 1/20 of the last
/// one's span): below the true maximum by less than 1e-14 for these surfaces.
template <class F>
double sampledMax(const RationalBezierPatch& p, const F& f) {
  double best = -std::numeric_limits<double>::infinity(), bs = 0.5, bt = 0.5;
  double span = 1, lo_s = 0, lo_t = 0;
  for (int level = 0; level < 6; ++level) {
    const int count = level == 0 ? 100 : 40;
    const double step = span / count;
    const double s0 = lo_s, t0 = lo_t;
    for (int i = 0; i <= count; ++i)
      for (int j = 0; j <= count; ++j) {
        const double s = std::clamp(s0 + i * step, 0.0, 1.0), t = std::clamp(t0 + j * step, 0.0, 1.0);
        if (const double v = f(p.evaluate(s, t)); v > best) best = v, bs = s, bt = t;
      }
    span = 2 * step;
    lo_s = bs - step;
    lo_t = bt - step;
  }
  return best;
}

double sampledSupport(const RationalBezierPatch& p, const Vec& n) {
  return sampledMax(p, [&](const Vec& x) { return n.dot(x); });
}

TEST(SupportBound, SpherePatchesFacingTheDirectionGiveTheRadius) {
  for (double radius : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(radius);
    const NurbsModel sphere({sphereSurface(radius)}, true);
    for (const RationalBezierPatch& patch : sphere.patches()) {
      // The patch's middle, away from the pole its edge collapses to (there the height's Hessian in the
      // parameters is singular and the coefficient test refuses).
      const RationalBezierPatch p = nurbs::subpatch(patch, 0.25, 0.75, 0.25, 0.75);
      for (double s : {0.3, 0.5, 0.8}) {
        // Along the outward normal at an interior point, the support of the sphere's patch is that point: r.
        const Vec n = p.evaluate(s, 0.4).normalized();
        const nurbs::SupportBound b = nurbs::certifySupport(p, n);
        ASSERT_TRUE(b.proved);
        EXPECT_GE(b.upper, radius * (1 - 1e-15));
        EXPECT_LE(b.upper, radius * (1 + 1e-13));
      }
    }
  }
}

TEST(SupportBound, CylinderAcrossItsAxisIsExactAlongItsFlatDirection) {
  // Across the axis, the height is constant along each ruling: a Hessian that is zero along the axis, which
  // the rounding allowance must accept without loosening the value.
  const double r = 0.5;
  const NurbsModel cylinder({cylinderSurface(r, 1)}, false);
  for (const RationalBezierPatch& p : cylinder.patches())
    for (double s : {0.2, 0.5, 1.0}) {
      const Vec c = p.evaluate(s, 0.5);
      const Vec n = Vec(c.x(), c.y(), 0).normalized();
      const nurbs::SupportBound b = nurbs::certifySupport(p, n);
      ASSERT_TRUE(b.proved);
      EXPECT_GE(b.upper, r);
      EXPECT_LE(b.upper, r * (1 + 1e-13));  // the allowance for rounding: ~30 ulps
    }
}

TEST(SupportBound, SaddleAndBackFacingPatchesAreRefused) {
  const double R = 1, a = 0.25;
  const NurbsModel torus({torusSurface(R, a)}, true);
  int saddles = 0, backs = 0;
  for (const RationalBezierPatch& p : torus.patches()) {
    // Quarter-size nodes around the tube's inner equator (x² + y² = (R − a)², z = 0): looked at along the
    // surface's normal there, the height rises along the ring and falls across the tube.
    for (double s0 = 0; s0 < 1; s0 += 0.25)
      for (double t0 = 0; t0 < 1; t0 += 0.25) {
        const RationalBezierPatch node = nurbs::subpatch(p, s0, s0 + 0.25, t0, t0 + 0.25);
        const Vec c = node.evaluate(0.5, 0.5);
        if (std::abs(c.z()) > 0.05 || std::hypot(c.x(), c.y()) > R - a + 0.05) continue;
        const Vec inward = -Vec(c.x(), c.y(), 0).normalized();  // the normal at the inner equator
        ++saddles;
        EXPECT_FALSE(nurbs::certifySupport(node, inward).proved);
      }
    // A sphere-like outer node seen from behind: its height along −normal is convex.
    const RationalBezierPatch node = nurbs::subpatch(p, 0.4, 0.6, 0.4, 0.6);
    const Vec c = node.evaluate(0.5, 0.5);
    if (std::hypot(c.x(), c.y()) > R + 0.1) {
      ++backs;
      EXPECT_FALSE(nurbs::certifySupport(node, -Vec(c.x(), c.y(), c.z()).normalized()).proved);
    }
  }
  EXPECT_GE(saddles, 4);
  EXPECT_GE(backs, 2);
}

TEST(SupportBound, RandomSubpatchesAndDirectionsAreNeverBelowTheSurface) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> u(0, 1), v(-1, 1);
  for (const NurbsSurface& surface : {torusSurface(), sphereSurface(), wavySurface()}) {
    const NurbsModel model({surface}, false);
    int proved = 0, tried = 0;
    for (int k = 0; k < 150; ++k) {
      const RationalBezierPatch& patch = model.patches()[rng() % model.patches().size()];
      const double size = std::ldexp(1.0, -static_cast<int>(rng() % 5));
      const double s0 = u(rng) * (1 - size), t0 = u(rng) * (1 - size);
      const RationalBezierPatch node = nurbs::subpatch(patch, s0, s0 + size, t0, t0 + size);
      // Half the directions random, half near the node's normal at a random point (where proofs are expected).
      Vec n(v(rng), v(rng), v(rng));
      if (k % 2 == 0) {
        const SurfaceDerivatives d = node.derivatives(u(rng), u(rng));
        n = d.du.cross(d.dv).normalized() + 0.2 * n;
      }
      n.normalize();
      const nurbs::SupportBound b = nurbs::certifySupport(node, n);
      ++tried;
      if (!b.proved) continue;
      ++proved;
      const double sampled = sampledSupport(node, n);
      EXPECT_GE(b.upper, sampled) << "k " << k;
      EXPECT_LE(b.upper, sampled + 1e-12) << "k " << k;
    }
    EXPECT_GE(proved, tried / 20) << tried;  // not vacuous (random sizes and directions are mostly refused)
  }
}

// The distance extremes (the support ball's certificates): from a sphere's centre both are its radius, at
// every scale and for every patch.
TEST(DistanceExtreme, SphereSeenFromItsCentreIsItsRadiusAtEveryScale) {
  for (double r : {1e-4, 1.0, 1e4}) {
    const Vec centre = r * Vec(0.3, -0.2, 0.7);
    const NurbsModel sphere({sphereSurface(r, centre)}, true);
    for (const RationalBezierPatch& patch : sphere.patches())
      for (bool farthest : {true, false}) {
        const nurbs::DistanceExtreme e = nurbs::certifyDistanceExtreme(patch, centre, farthest);
        ASSERT_TRUE(e.proved);
        EXPECT_NEAR(e.value, r, 1e-13 * r) << farthest;
        EXPECT_TRUE(farthest ? e.value >= r * (1 - 1e-15) : e.value <= r * (1 + 1e-15));
      }
  }
}

// Random subpatches of the three surfaces and random points: the value is always on the safe side of dense
// sampling; and where the point sits on the normal through a surface point, past the centres of curvature
// (farthest) or on the convex side (nearest), the sphere about it touches the subpatch there and the value is
// exact to rounding.
TEST(DistanceExtreme, RandomSubpatchesAreBoundedAndExactWhereASphereTouchesThem) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(0, 1), v(-1, 1);
  for (const NurbsSurface& surface : {torusSurface(), sphereSurface(), wavySurface()}) {
    const NurbsModel model({surface}, false);
    const bool wavy = surface.degreeU() == 3;
    int touching = 0, exact = 0;
    for (int k = 0; k < 120; ++k) {
      const RationalBezierPatch& patch = model.patches()[rng() % model.patches().size()];
      const double size = std::ldexp(1.0, -static_cast<int>(2 + rng() % 4));
      const double s0 = u(rng) * (1 - size), t0 = u(rng) * (1 - size);
      const RationalBezierPatch node = nurbs::subpatch(patch, s0, s0 + size, t0, t0 + size);
      const SurfaceDerivatives d = node.derivatives(0.2 + 0.6 * u(rng), 0.2 + 0.6 * u(rng));
      Vec normal = d.du.cross(d.dv).normalized();
      // The normal turned to the convex side (the surface curves away from it), where there is one.
      const double uu = normal.dot(d.duu), vv = normal.dot(d.dvv), uv = normal.dot(d.duv);
      const bool convex = uu * vv > uv * uv;
      if (convex && uu > 0) normal = -normal;
      const bool farthest = k % 2 == 0;
      Vec c = 2 * Vec(v(rng), v(rng), v(rng));
      const bool touches = convex && k % 4 < 2;
      // Farthest: 3 behind the surface (past its centres of curvature: radii <= 1.25 on the torus and sphere);
      // nearest: 0.5 in front of it.
      if (touches) c = farthest ? Vec(d.point - 3 * normal) : Vec(d.point + 0.5 * normal);
      const nurbs::DistanceExtreme e = nurbs::certifyDistanceExtreme(node, c, farthest);
      ASSERT_TRUE(e.proved);
      const double sampled = farthest ? sampledMax(node, [&](const Vec& x) { return (x - c).norm(); })
                                      : -sampledMax(node, [&](const Vec& x) { return -(x - c).norm(); });
      if (farthest) {
        EXPECT_GE(e.value, sampled) << "k " << k;
      } else {
        EXPECT_LE(e.value, sampled) << "k " << k;
      }
      if (!touches || wavy) continue;  // the wavy patch's curvature varies too much for fixed distances
      ++touching;
      if (std::abs(e.value - sampled) <= 1e-12) ++exact;
    }
    if (!wavy) {
      EXPECT_GE(exact, touching * 3 / 4) << touching;
    }
  }
}

TEST(DistanceExtreme, BrokenNetsAreRefusedWithoutACrash) {
  const NurbsModel sphere({sphereSurface(1)}, true);
  RationalBezierPatch p = sphere.patches().front();
  RationalBezierPatch nan = p;
  nan.at(1, 1)[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(nurbs::certifyDistanceExtreme(nan, Vec::Zero(), true).proved);
  RationalBezierPatch zeroWeight = p;
  zeroWeight.at(0, 1) = Eigen::Vector4d::Zero();
  EXPECT_FALSE(nurbs::certifyDistanceExtreme(zeroWeight, Vec::Zero(), false).proved);
  EXPECT_FALSE(nurbs::certifyDistanceExtreme(p, Vec(std::nan(""), 0, 0), true).proved);
}

TEST(SupportBound, BrokenNetsAreRefusedWithoutACrash) {
  const NurbsModel sphere({sphereSurface(1)}, true);
  RationalBezierPatch p = sphere.patches().front();
  const Vec n = p.evaluate(0.5, 0.5).normalized();
  RationalBezierPatch nan = p;
  nan.at(1, 1)[0] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(nurbs::certifySupport(nan, n).proved);
  RationalBezierPatch zeroWeight = p;
  zeroWeight.at(0, 1) = Eigen::Vector4d::Zero();
  EXPECT_FALSE(nurbs::certifySupport(zeroWeight, n).proved);
  EXPECT_FALSE(nurbs::certifySupport(p, Vec(std::nan(""), 0, 0)).proved);
}

// ---- certifyPolynomialMaximum (the tube separator's quartic) ----------------------------------------------

/// Bernstein coefficients (degree n × n, u-major) of f, by interpolation on a uniform grid.
template <class F>
std::vector<double> bernsteinOf(int n, const F& f) {
  const int count = (n + 1) * (n + 1);
  Eigen::MatrixXd basis(count, count);
  Eigen::VectorXd values(count);
  for (int a = 0; a <= n; ++a)
    for (int b = 0; b <= n; ++b) {
      const double s = double(a) / n, t = double(b) / n;
      std::array<std::array<double, kMaxNurbsDegree + 1>, 3> bs, bt;
      nurbs::bernstein(n, s, bs);
      nurbs::bernstein(n, t, bt);
      for (int i = 0; i <= n; ++i)
        for (int j = 0; j <= n; ++j)
          basis(a * (n + 1) + b, i * (n + 1) + j) = bs[0][std::size_t(i)] * bt[0][std::size_t(j)];
      values[a * (n + 1) + b] = f(s, t);
    }
  const Eigen::VectorXd c = basis.fullPivLu().solve(values);
  return std::vector<double>(c.data(), c.data() + count);
}

/// The polynomial's value from its coefficients, sampled on a grid, refined around the best sample.
double sampledPolynomialMax(int n, const std::vector<double>& c) {
  const auto at = [&](double s, double t) {
    std::array<std::array<double, kMaxNurbsDegree + 1>, 3> bs, bt;
    nurbs::bernstein(n, s, bs);
    nurbs::bernstein(n, t, bt);
    double sum = 0;
    for (int i = 0; i <= n; ++i)
      for (int j = 0; j <= n; ++j)
        sum += bs[0][std::size_t(i)] * bt[0][std::size_t(j)] * c[std::size_t(i * (n + 1) + j)];
    return sum;
  };
  double best = -std::numeric_limits<double>::infinity(), bs = 0.5, bt = 0.5, span = 1;
  for (int level = 0; level < 6; ++level, span /= 20) {
    const double s0 = std::max(0.0, bs - span / 2), t0 = std::max(0.0, bt - span / 2);
    for (int a = 0; a <= 40; ++a)
      for (int b = 0; b <= 40; ++b) {
        const double s = std::min(1.0, s0 + span * a / 40), t = std::min(1.0, t0 + span * b / 40);
        if (const double v = at(s, t); v > best) best = v, bs = s, bt = t;
      }
  }
  return best;
}

// A concave quadratic with a strong cross term, held at degree 8 as the tube's quartic of a biquadratic patch
// is: its coefficients stay short of its maximum, which concavity proves exactly (wherever it lies, inside the
// square or on its edge); a saddle is refused; no bound ever falls below a sample.
TEST(PolynomialMaximum, ConcaveFormsAreExactSaddlesRefusedNothingUnderestimated) {
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> centre(-0.3, 1.3), cross(-1.9, 1.9), level(-1, 1);
  int exactInside = 0;
  for (int trial = 0; trial < 200; ++trial) {
    const double a = centre(rng), b = centre(rng), k = cross(rng), d = level(rng);
    const auto concave = [&](double s, double t) {
      return d - ((s - a) * (s - a) + (t - b) * (t - b) + k * (s - a) * (t - b));
    };
    const std::vector<double> c = bernsteinOf(8, concave);
    double coefficientMax = -std::numeric_limits<double>::infinity();
    for (double x : c) coefficientMax = std::max(coefficientMax, x);
    const nurbs::SupportBound bound = nurbs::certifyPolynomialMaximum(8, 8, c.data(), 0);
    const double sampled = sampledPolynomialMax(8, c);
    ASSERT_TRUE(bound.proved) << a << " " << b << " " << k;
    EXPECT_GE(bound.upper, sampled - 1e-15);
    EXPECT_LE(bound.upper, sampled + 1e-12);
    if (a > 0 && a < 1 && b > 0 && b < 1) {
      EXPECT_NEAR(bound.upper, d, 1e-12);
      EXPECT_GT(coefficientMax, d + 1e-6);  // what the coefficients alone give
      ++exactInside;
    }
    const std::vector<double> saddle = bernsteinOf(8, [&](double s, double t) {
      return d - ((s - a) * (s - a) - (t - b) * (t - b) + k * (s - a) * (t - b));
    });
    const nurbs::SupportBound refused = nurbs::certifyPolynomialMaximum(8, 8, saddle.data(), 0);
    if (refused.proved) {
      EXPECT_GE(refused.upper, sampledPolynomialMax(8, saddle) - 1e-15);
    }
  }
  EXPECT_GT(exactInside, 50);
}

TEST(PolynomialMaximum, NonFiniteCoefficientsAreNotProved) {
  std::vector<double> c(81, -1.0);
  c[40] = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(nurbs::certifyPolynomialMaximum(8, 8, c.data(), 0).proved);
  c[40] = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(nurbs::certifyPolynomialMaximum(8, 8, c.data(), 0).proved);
}

}  // namespace
}  // namespace unidist
