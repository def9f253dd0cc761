// closestBoundaryPoint on unions whose answer is known by construction, and against the ray-walking oracle.
#include "raster_fixtures.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

using namespace raster_test;
using unidist::InputError;
using unidist::raster::BoundaryPoint;
using unidist::raster::BoundaryQueryOptions;
using unidist::raster::closestBoundaryPoint;
using unidist::raster::OffscreenContext;
using unidist::raster::resolutionErrorBound;

namespace {

BoundaryQueryOptions at(int resolution, bool refine = true) {
  BoundaryQueryOptions o;
  o.resolution = resolution;
  o.refine = refine;
  return o;
}

/// Every answer: inside, bracket holding the truth, point on the reported ray, pixel answer within its bound.
void expectHonest(const BoundaryPoint& bp, const Vec& O, double truth, double pixelBound) {
  ASSERT_TRUE(bp.inside);
  EXPECT_LE(bp.lowerBound, truth + 1e-12);
  EXPECT_GE(bp.upperBound, truth - 1e-12);
  EXPECT_GE(bp.upperBound, bp.distance);
  EXPECT_NEAR((bp.point - O).norm(), bp.distance, 1e-12);
  EXPECT_NEAR(bp.direction.norm(), 1.0, 1e-12);
  EXPECT_GE(bp.pixelDistance, truth - 1e-9);
  EXPECT_LE(bp.pixelDistance, truth + pixelBound);
  EXPECT_GE(bp.distance, truth - 1e-9);
  EXPECT_LE(bp.distance, bp.pixelDistance);
}

}  // namespace

TEST(RasterClosestBoundary, SingleBoxIsExactAndPixelsAreSecondOrder) {
  OffscreenContext context(8, 8);
  const ConvexUnion pieces{box(Vec(-1, -2, -3), Vec(1, 2, 3))};
  const Vec O(0.3, -0.5, 1.0);
  for (int n : {32, 128}) {
    const BoundaryPoint bp = closestBoundaryPoint(context, pieces, O, at(n));
    const double truth = 0.7;  // the x = 1 face
    expectHonest(bp, O, truth, resolutionErrorBound(truth, n, M_PI / 2));
    EXPECT_NEAR(bp.distance, truth, 1e-12);  // polished to the foot on the face
    EXPECT_NEAR(bp.lowerBound, truth, 1e-12);  // one piece: its depth is the answer
    EXPECT_NEAR(bp.point.x(), 1.0, 1e-12);
    EXPECT_EQ(bp.passes, 6);  // the containing piece once per view, nothing else
    EXPECT_LE(bp.pixelDistance - truth, bp.resolutionBound + 1e-12);
  }
}

TEST(RasterClosestBoundary, ConcaveCreaseOfAPlusIsFirstOrderThenExact) {
  // A plus sign in xy, 2 thick in z; O near the inner corner at (1, 1): the closest point is on the crease.
  OffscreenContext context(8, 8);
  const ConvexUnion pieces{box(Vec(-2, -1, -1), Vec(2, 1, 1)), box(Vec(-1, -2, -1), Vec(1, 2, 1))};
  const Vec O(0.8, 0.8, 0.1);
  const double truth = 0.2 * std::sqrt(2.0);
  for (int n : {32, 64}) {
    const BoundaryPoint pixels = closestBoundaryPoint(context, pieces, O, at(n, false));
    // The outside near the crease is a right-angled wedge around the direction to it: γ = 45°.
    expectHonest(pixels, O, truth, resolutionErrorBound(truth, n, M_PI / 4));
    EXPECT_GT(pixels.pixelDistance - truth, 1e-2 / n);  // first order: visibly worse than at a face
    const BoundaryPoint polished = closestBoundaryPoint(context, pieces, O, at(n));
    expectHonest(polished, O, truth, resolutionErrorBound(truth, n, M_PI / 4));
    EXPECT_NEAR(polished.distance, truth, 1e-12);
    EXPECT_TRUE(polished.refined);
    EXPECT_NEAR(polished.point.x(), 1.0, 1e-12);
    EXPECT_NEAR(polished.point.y(), 1.0, 1e-12);
  }
}

TEST(RasterClosestBoundary, SharedFacesOfTouchingPiecesAreNotBoundary) {
  // Left box and a right half cut in two along y: the faces at x = 0 coincide (triangulated differently),
  // and so do the two right halves' faces at y = 0. O sits 0.05 from the shared face.
  OffscreenContext context(8, 8);
  const ConvexUnion pieces{box(Vec(-2, -1, -1), Vec(0, 1, 1)), box(Vec(0, -1, -1), Vec(2, 0, 1)),
                           box(Vec(0, 0, -1), Vec(2, 1, 1))};
  for (const Vec& O : {Vec(-0.05, 0.02, 0.1), Vec(0.03, -0.01, 0.1), Vec(0.0, 0.0, 0.2)}) {
    const double truth = 1.0 - std::abs(O.z());  // the z faces; y and x are farther
    const BoundaryPoint bp = closestBoundaryPoint(context, pieces, O, at(48));
    expectHonest(bp, O, truth, resolutionErrorBound(truth, 48, M_PI / 2));
    EXPECT_NEAR(bp.distance, truth, 1e-12) << O.transpose();
  }
}

TEST(RasterClosestBoundary, CubeOfTetrahedraSharingEveryFace) {
  OffscreenContext context(8, 8);
  const ConvexUnion pieces = cubeOfTetrahedra(Vec(-1, -1, -1), 2.0);
  const Vec O(-0.4, -0.1, 0.2);  // 0.6 from x = −1, nearest face
  const BoundaryPoint bp = closestBoundaryPoint(context, pieces, O, at(64));
  expectHonest(bp, O, 0.6, resolutionErrorBound(0.6, 64, M_PI / 2));
  EXPECT_NEAR(bp.distance, 0.6, 1e-12);
  EXPECT_LT(bp.lowerBound, 0.6);  // no single tetrahedron holds the whole ball
}

TEST(RasterClosestBoundary, PieceHoldingOIsCoveredByOthers) {
  OffscreenContext context(8, 8);
  const ConvexUnion pieces{box(Vec(-0.3, -0.3, -0.3), Vec(0.3, 0.3, 0.3)),  // holds O, inside the others
                           box(Vec(-2, -1, -1.5), Vec(0.1, 1, 1.5)), box(Vec(-0.1, -1, -1.5), Vec(2, 1, 1.5))};
  const Vec O(0.05, 0.1, 0.0);
  const BoundaryPoint bp = closestBoundaryPoint(context, pieces, O, at(48));
  expectHonest(bp, O, 0.9, resolutionErrorBound(0.9, 48, M_PI / 2));
  EXPECT_NEAR(bp.distance, 0.9, 1e-12);
  EXPECT_NEAR(bp.point.y(), 1.0, 1e-12);
}

TEST(RasterClosestBoundary, ChainOfOverlappingBoxesNeedsSeveralPasses) {
  // A staircase: each box reaches the next only through the previous one.
  OffscreenContext context(8, 8);
  ConvexUnion pieces;
  for (int k = 0; k < 5; ++k)
    pieces.push_back(box(Vec(k * 0.8 - 0.5, k * 0.3 - 0.5, -0.5), Vec(k * 0.8 + 0.5, k * 0.3 + 0.5, 0.5)));
  const Vec O(0.0, 0.0, 0.3);
  Vec direction;
  const double truth = oracleDistance(pieces, O, 48, 1e-11, &direction);
  const BoundaryPoint bp = closestBoundaryPoint(context, pieces, O, at(64));
  expectHonest(bp, O, truth, resolutionErrorBound(truth, 64, M_PI / 4));
  EXPECT_NEAR(bp.distance, truth, 1e-9);
  EXPECT_GT(bp.passes, 6);
}

TEST(RasterClosestBoundary, RandomUnionsAgreeWithTheRayOracle) {
  OffscreenContext context(8, 8);
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> centre(-0.6, 0.6), size(0.3, 0.9), angle(-M_PI, M_PI);
  for (int trial = 0; trial < 4; ++trial) {
    ConvexUnion pieces;
    for (int k = 0; k < 8; ++k) {
      const Eigen::Isometry3d X = Eigen::Translation3d(centre(rng), centre(rng), centre(rng)) *
                                  Eigen::AngleAxisd(angle(rng), Vec(centre(rng), centre(rng), 1).normalized());
      std::vector<Vec> points;
      for (int c = 0; c < 12; ++c) points.push_back(X * (size(rng) * Vec::Random()));
      pieces.push_back(unidist::raster::convexHull(points));
    }
    const Vec O = Vec::Zero();
    const BoundaryPoint bp = closestBoundaryPoint(context, pieces, O, at(64));
    if (!bp.inside) continue;
    const double truth = oracleDistance(pieces, O, 48);
    EXPECT_LE(bp.lowerBound, truth + 1e-12) << trial;
    EXPECT_LE(bp.distance, truth + 1e-9) << trial;  // never worse than the polished oracle
    EXPECT_GE(bp.upperBound, bp.distance);
    EXPECT_LE(bp.pixelDistance, truth + resolutionErrorBound(truth, 64, M_PI / 6)) << trial;
  }
}

TEST(RasterClosestBoundary, OutsideTheUnionIsDistanceZero) {
  OffscreenContext context(8, 8);
  const ConvexUnion pieces{box(Vec(-1, -1, -1), Vec(1, 1, 1))};
  const BoundaryPoint bp = closestBoundaryPoint(context, pieces, Vec(3, 0, 0), at(32));
  EXPECT_FALSE(bp.inside);
  EXPECT_EQ(bp.distance, 0.0);
  EXPECT_EQ(bp.point, Vec(3, 0, 0));
}

TEST(RasterClosestBoundary, OnTheBoundaryIsDistanceZero) {
  OffscreenContext context(8, 8);
  const ConvexUnion pieces{box(Vec(-1, -1, -1), Vec(0, 1, 1)), box(Vec(0, -1, -1), Vec(1, 1, 1))};
  const BoundaryPoint onFace = closestBoundaryPoint(context, pieces, Vec(0.3, 0.2, 1.0), at(32));
  EXPECT_FALSE(onFace.inside);
  EXPECT_EQ(onFace.distance, 0.0);
  // On the shared face (inside no single piece) but inside the union: found through both pieces.
  const BoundaryPoint shared = closestBoundaryPoint(context, pieces, Vec(0.0, 0.2, 0.5), at(32));
  EXPECT_TRUE(shared.inside);
  EXPECT_NEAR(shared.distance, 0.5, 1e-12);
  EXPECT_EQ(shared.lowerBound, 0.0);
}

TEST(RasterClosestBoundary, BadInputIsAnInputError) {
  OffscreenContext context(8, 8);
  const ConvexUnion pieces{box(Vec(-1, -1, -1), Vec(1, 1, 1))};
  EXPECT_THROW(closestBoundaryPoint(context, {}, Vec::Zero(), at(32)), InputError);
  EXPECT_THROW(closestBoundaryPoint(context, pieces, Vec(std::nan(""), 0, 0), at(32)), InputError);
  EXPECT_THROW(closestBoundaryPoint(context, pieces, Vec::Zero(), at(4)), InputError);
  EXPECT_THROW(closestBoundaryPoint(context, pieces, Vec::Zero(), at(5000)), InputError);
  ConvexUnion broken = pieces;
  broken[0].triangles[0][1] = 99;
  EXPECT_THROW(closestBoundaryPoint(context, broken, Vec::Zero(), at(32)), InputError);
  broken = pieces;
  broken[0].planes.clear();
  EXPECT_THROW(closestBoundaryPoint(context, broken, Vec::Zero(), at(32)), InputError);
}
