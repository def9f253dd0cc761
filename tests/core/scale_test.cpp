// The same configurations at scales 1e-4, 1 and 1e4 must give the same answers relative to their size:
// every tolerance in the library is relative to the models' size, none is a fixed number of metres.
#include "core/pair_fixtures.h"

#include <gtest/gtest.h>

namespace {

using oracle::Pose;
using oracle::Shape;
using oracle::Vec;

class ScaleTest : public ::testing::TestWithParam<double> {};

TEST_P(ScaleTest, ConvexSeparationAndPenetrationScaleExactly) {
  const double scale = GetParam();
  std::mt19937_64 rng(77);
  const auto shapes = fixtures::convexShapes(scale);
  for (const Shape& sa : shapes)
    for (const Shape& sb : shapes)
      for (double gap : {0.1, 1e-6, -0.05}) {
        Pose XA = oracle::randomPose(rng, 1.0), XB = oracle::randomPose(rng, 1.0);
        XA.translation() *= scale;
        fixtures::placeAtGap(sa, XA, sb, XB, oracle::randomUnit(rng), gap * scale);
        const auto a = fixtures::makeModel(sa), b = fixtures::makeModel(sb);
        unidist::DistanceOptions opt;
        opt.tolerance = (gap > 0 ? 1e-9 : 1e-8) * scale;
        const auto r = unidist::distance(*a, XA, *b, XB, opt);
        SCOPED_TRACE(sa.kind + "-" + sb.kind + " gap " + std::to_string(gap) + " " + r.method);
        if (gap > 0) {
          EXPECT_NEAR(r.distance / scale, gap, 2e-9);
          // The placement itself rounds at ~1e-16 of the coordinates (size ~ scale).
          EXPECT_LE(r.lowerBound, (gap + 1e-14) * scale);
          EXPECT_GE(r.upperBound, (gap - 1e-14) * scale);
        } else {
          fixtures::expectPenetrationMatchesOracle(sa, XA, sb, XB, r, 1e-7 * scale);
        }
        EXPECT_TRUE(r.pointA.allFinite() && r.pointB.allFinite() && r.normal.allFinite());
      }
}

TEST_P(ScaleTest, TorusSeparationScales) {
  const double scale = GetParam();
  const Shape torus = fixtures::torusShape(scale);
  const Shape box{"box", 0.3 * scale, 0.6 * scale, 0.45 * scale};
  const auto tm = fixtures::makeModel(torus), bm = fixtures::makeModel(box);
  Pose XB = Pose::Identity();
  XB.translation() = Vec(1.5, 0.2, 0.1) * scale;
  const double truth = oracle::torusSeparation(torus, Pose::Identity(), box, XB);
  const auto r = unidist::distance(*tm, Pose::Identity(), *bm, XB);
  EXPECT_NEAR(r.distance / scale, truth / scale, 2e-9);
  EXPECT_EQ(r.status, unidist::Status::Certified);
}

INSTANTIATE_TEST_SUITE_P(Scales, ScaleTest, ::testing::Values(1e-4, 1.0, 1e4));

}  // namespace
