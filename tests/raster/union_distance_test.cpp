// unionDistance: the contract's signed distance of two unions of convex pieces, against exact box–box answers,
// against the ray oracle on the pairwise Minkowski sums, and against GJK on the moved pieces.
#include "convex/gjk.h"
#include "raster_fixtures.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

using namespace raster_test;
using unidist::InputError;
using unidist::Status;
using unidist::raster::OffscreenContext;
using unidist::raster::resolutionErrorBound;
using unidist::raster::unionDistance;
using unidist::raster::unionDistanceReport;
using unidist::raster::UnionDistanceOptions;

namespace {

UnionDistanceOptions at(int resolution, bool refine = true) {
  UnionDistanceOptions o;
  o.resolution = resolution;
  o.refine = refine;
  return o;
}

void expectContract(const unidist::DistanceResult& r) {
  EXPECT_LE(r.lowerBound, r.distance);
  EXPECT_GE(r.upperBound, r.distance);
  EXPECT_NEAR(r.normal.norm(), 1.0, 1e-12);
  EXPECT_LT((r.pointB - r.pointA - r.distance * r.normal).norm(), 1e-12);
}

std::vector<std::vector<Vec>> posedVertices(const ConvexUnion& u, const Eigen::Isometry3d& X) {
  std::vector<std::vector<Vec>> out;
  for (const auto& p : u) {
    out.emplace_back();
    for (const auto& v : p.vertices) out.back().push_back(X * v);
  }
  return out;
}

/// The smallest GJK lower bound over all piece pairs (negative: some pair overlaps at least that much).
double worstPairLower(const ConvexUnion& a, const Eigen::Isometry3d& X_WA, const ConvexUnion& b,
                      const Eigen::Isometry3d& X_WB) {
  const auto A = posedVertices(a, X_WA), B = posedVertices(b, X_WB);
  double worst = std::numeric_limits<double>::infinity();
  for (const auto& ai : A)
    for (const auto& bj : B) {
      const auto d = unidist::detail::convexDistance(unidist::detail::supportOfPointSet(ai),
                                                     unidist::detail::supportOfPointSet(bj), 1e-12, 1000, true);
      worst = std::min(worst, d.distance);
    }
  return worst;
}

/// The union of the pairwise Minkowski sums A_i ⊕ (−B_j), built here from the posed vertices.
ConvexUnion minkowskiSums(const ConvexUnion& a, const Eigen::Isometry3d& X_WA, const ConvexUnion& b,
                          const Eigen::Isometry3d& X_WB) {
  ConvexUnion sums;
  for (const auto& ai : posedVertices(a, X_WA))
    for (const auto& bj : posedVertices(b, X_WB)) {
      std::vector<Vec> d;
      for (const auto& p : ai)
        for (const auto& q : bj) d.push_back(p - q);
      sums.push_back(unidist::raster::convexHull(d));
    }
  return sums;
}

}  // namespace

TEST(RasterUnionDistance, SingleBoxesMatchTheExactBoxBoxDepth) {
  OffscreenContext context(8, 8);
  const Vec ha(1.0, 0.5, 0.3), hb(0.4, 0.4, 0.4);
  const ConvexUnion a{box(-ha, ha)}, b{box(-hb, hb)};
  const Eigen::Isometry3d X_WA = Eigen::Isometry3d(Eigen::AngleAxisd(0.2, Vec::UnitZ()));
  for (const Vec& t : {Vec(1.1, 0.2, 0.1), Vec(0.3, 0.6, -0.2), Vec(0.0, 0.0, 0.05)}) {
    const Eigen::Isometry3d X_WB = Eigen::Translation3d(t) * Eigen::AngleAxisd(0.7, Vec(1, 2, 3).normalized());
    const auto exact = unidist::distance(unidist::Box(ha), X_WA, unidist::Box(hb), X_WB);
    ASSERT_LT(exact.distance, 0);
    for (bool refine : {false, true}) {
      const auto report = unionDistanceReport(context, a, X_WA, b, X_WB, at(64, refine));
      const auto& r = report.result;
      expectContract(r);
      EXPECT_STREQ(r.method, "raster");
      EXPECT_LE(r.lowerBound, exact.distance + 1e-12);
      EXPECT_GE(r.upperBound, exact.distance - 1e-12);
      // Both convex: the closest point of the one sum lies inside a facet (second order in the resolution).
      EXPECT_LE(exact.distance - r.distance, resolutionErrorBound(-exact.distance, 64, M_PI / 2) + 1e-12);
      if (refine) {
        EXPECT_NEAR(r.distance, exact.distance, 1e-10) << t.transpose();
        EXPECT_EQ(r.status, Status::Certified);
        EXPECT_LT((r.normal - exact.normal).norm(), 1e-6);
      }
      EXPECT_EQ(report.overlappingPairs, 1);
    }
  }
}

TEST(RasterUnionDistance, SeparatedUnionsGiveTheExactPairMinimum) {
  OffscreenContext context(8, 8);
  const ConvexUnion a{box(Vec(-2, -1, -1), Vec(2, 1, 1)), box(Vec(-1, -2, -1), Vec(1, 2, 1))};  // a plus
  const ConvexUnion b{box(Vec(-0.2, -0.2, -0.2), Vec(0.2, 0.2, 0.2))};
  const Eigen::Isometry3d X_WB(Eigen::Translation3d(1.5, 1.5, 0));  // in the notch, 0.3 from both arms
  const auto r = unionDistance(context, a, Eigen::Isometry3d::Identity(), b, X_WB, at(32));
  expectContract(r);
  EXPECT_STREQ(r.method, "convex pieces");
  EXPECT_NEAR(r.distance, 0.3, 1e-9);
  EXPECT_EQ(r.status, Status::Certified);
}

TEST(RasterUnionDistance, CubeInTheNotchOfAnLMustClearTwoWalls) {
  // The L of translation_depth_test: B overlaps both arms at the inner corner; truth by construction.
  OffscreenContext context(8, 8);
  const ConvexUnion a{box(Vec(0, 0, 0), Vec(3, 1, 1)), box(Vec(0, 0, 0), Vec(1, 3, 1))};
  const ConvexUnion b{box(Vec(-0.25, -0.25, -0.25), Vec(0.25, 0.25, 0.25))};
  const Eigen::Isometry3d X_WB(Eigen::Translation3d(1.15, 1.1, 0.5));  // 0.1 into the upright arm, 0.15 into the other
  // Clearing one arm leaves B in the other: it must leave both, by (0.1, 0.15, 0): the crease of the sums.
  const Vec escape(0.1, 0.15, 0.0);
  const auto report = unionDistanceReport(context, a, Eigen::Isometry3d::Identity(), b, X_WB, at(64));
  const auto& r = report.result;
  expectContract(r);
  EXPECT_NEAR(r.distance, -escape.norm(), 1e-9);
  EXPECT_LT((r.normal - escape.normalized()).norm(), 1e-6);
  EXPECT_GT(report.boundary.pixelDistance, escape.norm());  // the image alone is first order here
  EXPECT_LE(report.boundary.pixelDistance, escape.norm() + resolutionErrorBound(escape.norm(), 64, 0.5));
  EXPECT_EQ(r.status, Status::Bounded);  // the deepest single pair (0.15) does not reach the crease
  EXPECT_NEAR(r.upperBound, -0.15, 1e-9);
}

TEST(RasterUnionDistance, InterlockedTorusPiecesAgreeWithTheRayOracleAndTheEscapeSeparates) {
  OffscreenContext context(8, 8);
  const ConvexUnion a = torusPieces(1.0, 0.3, 12, 6, Eigen::Isometry3d::Identity());
  const ConvexUnion b = torusPieces(1.0, 0.3, 12, 6, Eigen::Isometry3d::Identity());
  const Eigen::Isometry3d X_WB = Eigen::Translation3d(1.5, 0.05, 0.02) * Eigen::AngleAxisd(M_PI / 2, Vec::UnitX());
  ASSERT_LT(worstPairLower(a, Eigen::Isometry3d::Identity(), b, X_WB), -0.01);  // they interpenetrate

  const auto report = unionDistanceReport(context, a, Eigen::Isometry3d::Identity(), b, X_WB, at(64));
  const auto& r = report.result;
  expectContract(r);
  EXPECT_STREQ(r.method, "raster");
  EXPECT_GT(report.overlappingPairs, 0);

  const ConvexUnion sums = minkowskiSums(a, Eigen::Isometry3d::Identity(), b, X_WB);
  const double oracle = oracleDistance(sums, Vec::Zero(), 32);
  EXPECT_LE(-r.upperBound, oracle + 1e-9);       // the proved depth bracket holds the (polished) truth
  EXPECT_LE(-r.distance, oracle + 1e-9);         // never worse than the oracle
  EXPECT_GE(-r.distance, -r.upperBound - 1e-12);
  EXPECT_LE(report.boundary.pixelDistance, oracle + resolutionErrorBound(oracle, 64, M_PI / 6));

  // The escape really separates: B moved a little beyond it overlaps no piece of A.
  const Eigen::Isometry3d moved = Eigen::Translation3d((-r.distance + 1e-7) * r.normal) * X_WB;
  EXPECT_GT(worstPairLower(a, Eigen::Isometry3d::Identity(), b, moved), -1e-9);
  // The witness points lie on the pieces' surfaces (within the push-out).
  bool onA = false;
  for (const auto& piece : a) {
    double worst = -1e300;
    for (const auto& plane : piece.planes) worst = std::max(worst, plane.head<3>().dot(r.pointA) + plane.w());
    onA = onA || std::abs(worst) < 1e-9;
  }
  EXPECT_TRUE(onA);
}

TEST(RasterUnionDistance, TouchingToriAreAtDistanceZero) {
  OffscreenContext context(8, 8);
  const ConvexUnion a = torusPieces(1.0, 0.3, 12, 6, Eigen::Isometry3d::Identity());
  // Side by side in the plane, outer tube faces parallel: B's piece at angle π faces A's at angle 0.
  const double outer = 1.0 + 0.3 * std::cos(M_PI / 6);  // the flat outer face of the hexagonal tube
  const ConvexUnion b = torusPieces(1.0, 0.3, 12, 6, Eigen::Isometry3d::Identity());
  const Eigen::Isometry3d X_WB(Eigen::Translation3d(2 * outer, 0, 0));  // the θ = 0 and θ = π edges meet
  const auto r = unionDistance(context, a, Eigen::Isometry3d::Identity(), b, X_WB, at(32));
  expectContract(r);
  EXPECT_NEAR(r.distance, 0.0, 1e-9);
  EXPECT_LE(r.lowerBound, 0.0);
  EXPECT_GE(r.upperBound, 0.0);
}

TEST(RasterUnionDistance, BadInputIsAnInputError) {
  OffscreenContext context(8, 8);
  const ConvexUnion a{box(Vec(-1, -1, -1), Vec(1, 1, 1))};
  const Eigen::Isometry3d I = Eigen::Isometry3d::Identity();
  EXPECT_THROW(unionDistance(context, {}, I, a, I), InputError);
  EXPECT_THROW(unionDistance(context, a, I, {}, I), InputError);
  Eigen::Isometry3d nan = I;
  nan.translation().x() = std::nan("");
  EXPECT_THROW(unionDistance(context, a, nan, a, I), InputError);
  EXPECT_THROW(unionDistance(context, a, I, a, I, at(7)), InputError);
  UnionDistanceOptions badTolerance;
  badTolerance.tolerance = std::nan("");
  EXPECT_THROW(unionDistance(context, a, I, a, I, badTolerance), InputError);
}
