// Every primitive pair against independent truth: support-plane constructions (exact separations), a dense
// direction search for convex penetration depths, a dense angle search for torus separations, and
// constructed torus penetrations whose minimum translation is known in closed form.
#include "core/pair_fixtures.h"

#include <gtest/gtest.h>

namespace {

using oracle::Pose;
using oracle::Shape;
using oracle::Vec;

void expectConsistent(const unidist::DistanceResult& r, double tol) {
  EXPECT_NEAR(r.normal.norm(), 1.0, 1e-9);
  EXPECT_LE((r.pointB - r.pointA - r.distance * r.normal).norm(), 2 * tol + 1e-12);
  EXPECT_LE(r.lowerBound, r.distance + 1e-15);
  EXPECT_GE(r.upperBound, r.distance - 1e-15);
}

void expectOnSurface(const Shape& s, const Pose& X, const Vec& p_W, double tol) {
  EXPECT_LE(std::abs(s.signedDistance(X.inverse() * p_W)), tol) << s.kind;
}

TEST(ConvexPairs, SeparationEqualsConstructedGap) {
  std::mt19937_64 rng(20261122);
  const auto shapes = fixtures::convexShapes();
  int cases = 0;
  for (const Shape& sa : shapes)
    for (const Shape& sb : shapes)
      for (double gap : {0.3, 1e-3, 1e-7, 0.0})
        for (int trial = 0; trial < 6; ++trial) {
          const Pose XA = oracle::randomPose(rng, 1.0);
          Pose XB = oracle::randomPose(rng, 1.0);
          const Vec n = oracle::randomUnit(rng);
          fixtures::placeAtGap(sa, XA, sb, XB, n, gap);
          const auto a = fixtures::makeModel(sa), b = fixtures::makeModel(sb);
          const double tol = 1e-9;
          unidist::DistanceOptions opt;
          opt.tolerance = tol;
          const auto r = unidist::distance(*a, XA, *b, XB, opt);
          SCOPED_TRACE(sa.kind + "-" + sb.kind + " gap " + std::to_string(gap) + " trial " + std::to_string(trial));
          EXPECT_NEAR(r.distance, gap, 2 * tol);
          EXPECT_LE(r.lowerBound, gap + 1e-12);
          EXPECT_GE(r.upperBound, gap - 1e-12);
          EXPECT_EQ(r.status, unidist::Status::Certified) << r.method;
          expectConsistent(r, tol);
          expectOnSurface(sa, XA, r.pointA, 4 * tol);
          expectOnSurface(sb, XB, r.pointB, 4 * tol);
          if (gap > 1e-6) {
            EXPECT_LE((r.normal - n).norm(), 10 * std::sqrt(tol));  // a distance within tol fixes the direction to ~sqrt(tol / size)
          }
          ++cases;
        }
  EXPECT_EQ(cases, 5 * 5 * 4 * 6);
}

TEST(ConvexPairs, PenetrationEqualsMinimumTranslation) {
  std::mt19937_64 rng(7);
  const auto shapes = fixtures::convexShapes();
  int penetrating = 0;
  for (const Shape& sa : shapes)
    for (const Shape& sb : shapes)
      for (int trial = 0; trial < 4; ++trial) {
        const Pose XA = oracle::randomPose(rng, 0.2);
        Pose XB = oracle::randomPose(rng, 0.2);
        // Overlap by a random fraction of the support overlap along a random direction.
        const Vec n = oracle::randomUnit(rng);
        fixtures::placeAtGap(sa, XA, sb, XB, n, -std::uniform_real_distribution<double>(0.01, 0.3)(rng));
        Vec oracleDir;
        const double depth = oracle::convexPenetration(sa, XA, sb, XB, &oracleDir);
        ASSERT_GT(depth, 0);
        const auto a = fixtures::makeModel(sa), b = fixtures::makeModel(sb);
        unidist::DistanceOptions opt;
        opt.tolerance = 1e-8;
        const auto r = unidist::distance(*a, XA, *b, XB, opt);
        SCOPED_TRACE(sa.kind + "-" + sb.kind + " trial " + std::to_string(trial) + " method " + r.method);
        fixtures::expectPenetrationMatchesOracle(sa, XA, sb, XB, r, 1e-7);
        expectConsistent(r, 1e-7);
        // Moving B by 1 % less than the depth along the normal keeps an overlap; 1 % more separates.
        Pose less = XB, more = XB;
        less.translation() += 0.99 * depth * r.normal;
        more.translation() += 1.01 * depth * r.normal;
        EXPECT_LT(unidist::distance(*a, XA, *b, less, opt).distance, 0);
        EXPECT_GT(unidist::distance(*a, XA, *b, more, opt).distance, 0);
        ++penetrating;
      }
  EXPECT_EQ(penetrating, 100);
}

TEST(PlanePairs, LowestPointDecidesAgainstEveryModel) {
  std::mt19937_64 rng(11);
  auto shapes = fixtures::convexShapes();
  shapes.push_back(fixtures::torusShape());
  for (const Shape& s : shapes)
    for (int trial = 0; trial < 20; ++trial) {
      const Vec n = oracle::randomUnit(rng);
      const double d = std::uniform_real_distribution<double>(-0.5, 0.5)(rng);
      const Pose XP = oracle::randomPose(rng, 1.0), XS = oracle::randomPose(rng, 1.0);
      const unidist::Plane plane(3.0 * n, 3.0 * d);  // an unnormalised normal is normalised with d
      const auto m = fixtures::makeModel(s);
      const Vec n_W = XP.linear() * n;
      const double d_W = d + n_W.dot(XP.translation());
      const double truth = n_W.dot(oracle::worldSupport(s, XS, -n_W)) - d_W;
      const auto r = unidist::distance(plane, XP, *m, XS);
      SCOPED_TRACE(s.kind + " trial " + std::to_string(trial));
      EXPECT_NEAR(r.distance, truth, 1e-12);
      EXPECT_EQ(r.status, unidist::Status::Certified);
      expectConsistent(r, 1e-12);
      const auto flipped = unidist::distance(*m, XS, plane, XP);
      EXPECT_NEAR(flipped.distance, truth, 1e-12);
      EXPECT_LE((flipped.normal + r.normal).norm(), 1e-12);
    }
  const unidist::Plane p(Vec::UnitZ(), 0);
  EXPECT_THROW(unidist::distance(p, Pose::Identity(), p, Pose::Identity()), unidist::InputError);
}

TEST(TorusPairs, SeparationMatchesDenseAngleSearch) {
  std::mt19937_64 rng(3);
  auto shapes = fixtures::convexShapes();
  shapes.push_back({"torus", 0.6, 0.15});
  const Shape torus = fixtures::torusShape();
  const auto tm = fixtures::makeModel(torus);
  int tested = 0;
  for (const Shape& s : shapes)
    for (int trial = 0; trial < 40 && tested < 1000; ++trial) {
      const Pose XT = oracle::randomPose(rng, 1.0), XS = oracle::randomPose(rng, 1.5);
      const double truth = oracle::torusSeparation(torus, XT, s, XS);
      if (truth <= 1e-6) continue;  // penetrations are tested below
      const auto m = fixtures::makeModel(s);
      const auto r = unidist::distance(*tm, XT, *m, XS);
      const double tol = unidist::defaultTolerance(*tm, XT, *m, XS);
      SCOPED_TRACE(s.kind + " trial " + std::to_string(trial) + " " + r.method);
      EXPECT_NEAR(r.distance, truth, 2 * tol + 1e-12);
      EXPECT_LE(r.lowerBound, truth + 1e-12);
      EXPECT_GE(r.upperBound, truth - 1e-12);
      EXPECT_EQ(r.status, unidist::Status::Certified);
      expectConsistent(r, tol);
      expectOnSurface(torus, XT, r.pointA, 4 * tol);
      expectOnSurface(s, XS, r.pointB, 4 * tol);
      const auto back = unidist::distance(*m, XS, *tm, XT);
      EXPECT_NEAR(back.distance, r.distance, 2 * tol);
      ++tested;
    }
  EXPECT_GT(tested, 60);
}

// A box pushed radially into the tube by delta: the ring is locally convex there, so the way out is straight
// back and the depth is delta (any other way needs a translation of at least the box's half size).
TEST(TorusPairs, RadialPenetrationIsCertified) {
  const unidist::Torus torus(1.0, 0.25);
  const unidist::Box box(Vec(0.3, 0.1, 0.1));
  for (double delta : {0.0, 1e-6, 1e-3, 0.05}) {  // 0: touching
    Pose XB = Pose::Identity();
    XB.translation() = Vec(1.25 + 0.3 - delta, 0, 0);
    const auto r = unidist::distance(torus, Pose::Identity(), box, XB);
    SCOPED_TRACE(delta);
    EXPECT_NEAR(r.distance, -delta, 1e-8);
    EXPECT_LE((r.normal - Vec::UnitX()).norm(), 1e-6);
    EXPECT_EQ(r.status, unidist::Status::Certified);
    expectConsistent(r, 1e-8);
  }
}

// A ball in the hole that touches the whole inner rim: straight out sideways is blocked by the ring, so the
// minimum translation is along the axis, where the centre must reach distance R_ball + r from the circle:
// z = sqrt((R_ball + r)^2 − R^2).
TEST(TorusPairs, BallInTheHoleLeavesAlongTheAxis) {
  const unidist::Torus torus(1.0, 0.25);
  const unidist::Sphere ball(0.8);
  const double truth = -std::sqrt(1.05 * 1.05 - 1.0);
  const auto r = unidist::distance(torus, Pose::Identity(), ball, Pose::Identity());
  EXPECT_NEAR(r.distance, truth, 1e-6);
  EXPECT_LE(r.lowerBound, truth + 1e-9);
  EXPECT_GE(r.upperBound, truth - 1e-9);
  EXPECT_NEAR(std::abs(r.normal.z()), 1.0, 1e-6);
  expectConsistent(r, 1e-6);
}

TEST(SpherePairs, ExactAgainstEveryConvexShape) {
  std::mt19937_64 rng(5);
  const Shape ball{"sphere", 0.37};
  const unidist::Sphere sphere(ball.p0);
  for (const Shape& s : fixtures::convexShapes())
    for (int trial = 0; trial < 200; ++trial) {
      const Pose XS = oracle::randomPose(rng, 1.0);
      const Pose XC = oracle::randomPose(rng, 1.0);
      const auto m = fixtures::makeModel(s);
      const double centreDepth = s.signedDistance(XS.inverse() * XC.translation());
      const double truth = centreDepth - ball.p0;  // exact for a ball against a convex solid, in or out
      const auto r = unidist::distance(sphere, XC, *m, XS);
      SCOPED_TRACE(s.kind + " trial " + std::to_string(trial));
      EXPECT_NEAR(r.distance, truth, 1e-12);
      EXPECT_EQ(r.status, unidist::Status::Certified);
      expectConsistent(r, 1e-12);
    }
}

TEST(CapsulePairs, ParallelAndCrossingAxes) {
  const unidist::Capsule a(0.2, 0.5), b(0.3, 0.25);
  Pose XB = Pose::Identity();
  XB.translation() = Vec(0.7, 0, 0.1);  // parallel axes 0.7 apart: 0.7 − 0.5
  EXPECT_NEAR(unidist::distance(a, Pose::Identity(), b, XB).distance, 0.2, 1e-15);
  XB.linear() = Eigen::AngleAxisd(M_PI / 2, Vec::UnitX()).toRotationMatrix();
  XB.translation().setZero();  // crossing axes: the depth is the sum of the radii
  const auto r = unidist::distance(a, Pose::Identity(), b, XB);
  EXPECT_NEAR(r.distance, -0.5, 1e-15);
  expectConsistent(r, 1e-15);
}

}  // namespace
