// The generic routine (alternating projection + surface branch and bound) works for any pair through point
// queries alone; here it is held to the same truth as the special routines, and its bounds must be honest.
#include "core/pair_fixtures.h"

#include <gtest/gtest.h>

namespace {

using oracle::Pose;
using oracle::Shape;
using oracle::Vec;

TEST(Generic, SeparationOfConvexPairsMatchesGapWithHonestBounds) {
  std::mt19937_64 rng(99);
  const auto shapes = fixtures::convexShapes();
  int certified = 0, total = 0;
  for (const Shape& sa : shapes)
    for (const Shape& sb : shapes)
      for (double gap : {0.25, 1e-3}) {
        const Pose XA = oracle::randomPose(rng, 1.0);
        Pose XB = oracle::randomPose(rng, 1.0);
        fixtures::placeAtGap(sa, XA, sb, XB, oracle::randomUnit(rng), gap);
        const auto a = fixtures::makeModel(sa), b = fixtures::makeModel(sb);
        unidist::DistanceOptions opt;
        opt.tolerance = 1e-6;
        const auto r = unidist::genericDistance(*a, XA, *b, XB, opt);
        SCOPED_TRACE(sa.kind + "-" + sb.kind + " gap " + std::to_string(gap));
        // The upper bound is realised by real surface points, so it can never be below the truth.
        EXPECT_GE(r.upperBound, gap - 1e-12);
        EXPECT_LE(r.lowerBound, gap + 1e-12);
        EXPECT_NEAR(r.distance, gap, 1e-5);
        EXPECT_LE((r.pointB - r.pointA - r.distance * r.normal).norm(), 1e-9);
        certified += r.status == unidist::Status::Certified;
        ++total;
      }
  // Alternation converges linearly on flat contacts, so not every answer reaches 1e-6; most do.
  EXPECT_GT(certified, total / 2);
}

TEST(Generic, PenetrationIsBracketedByProvedBounds) {
  std::mt19937_64 rng(1234);
  const auto shapes = fixtures::convexShapes();
  for (const Shape& sa : shapes)
    for (const Shape& sb : shapes) {
      const Pose XA = oracle::randomPose(rng, 0.2);
      Pose XB = oracle::randomPose(rng, 0.2);
      fixtures::placeAtGap(sa, XA, sb, XB, oracle::randomUnit(rng), -0.1);
      // The direction oracle bounds the depth from above and may sit ~1e-5 deep of it on ridges.
      const double truth = -oracle::convexPenetration(sa, XA, sb, XB);
      const auto a = fixtures::makeModel(sa), b = fixtures::makeModel(sb);
      unidist::DistanceOptions opt;
      opt.tolerance = 1e-4;
      const auto r = unidist::genericDistance(*a, XA, *b, XB, opt);
      SCOPED_TRACE(sa.kind + "-" + sb.kind);
      EXPECT_LT(r.distance, 0);
      EXPECT_LE(r.lowerBound, truth + 1e-4);
      EXPECT_GE(r.upperBound, truth - 1e-9);
    }
}

TEST(Generic, ContainmentIsAnOverlap) {
  const unidist::Sphere ball(0.5);
  const unidist::Box box(Vec(1, 1, 1));
  const auto r = unidist::genericDistance(ball, Pose::Identity(), box, Pose::Identity());
  // A unit-ball-in-a-box containment: the true signed distance is −(1 + 0.5) = −1.5.
  EXPECT_LT(r.distance, 0);
  EXPECT_LE(r.lowerBound, -1.5 + 1e-12);
  EXPECT_GE(r.upperBound, -1.5 - 1e-12);
}

TEST(Generic, TorusSeparationAgreesWithTheCircleSearch) {
  std::mt19937_64 rng(42);
  const Shape torus = fixtures::torusShape();
  const auto tm = fixtures::makeModel(torus);
  int tested = 0;
  for (const Shape& s : fixtures::convexShapes())
    for (int trial = 0; trial < 5; ++trial) {
      const Pose XT = oracle::randomPose(rng, 1.0), XS = oracle::randomPose(rng, 1.5);
      const double truth = oracle::torusSeparation(torus, XT, s, XS);
      if (truth <= 1e-3) continue;
      const auto m = fixtures::makeModel(s);
      unidist::DistanceOptions opt;
      opt.tolerance = 1e-6;
      const auto r = unidist::genericDistance(*tm, XT, *m, XS, opt);
      SCOPED_TRACE(s.kind + " trial " + std::to_string(trial));
      EXPECT_NEAR(r.distance, truth, 1e-5);
      EXPECT_GE(r.upperBound, truth - 1e-12);
      EXPECT_LE(r.lowerBound, truth + 1e-12);
      ++tested;
    }
  EXPECT_GT(tested, 5);
}

}  // namespace
