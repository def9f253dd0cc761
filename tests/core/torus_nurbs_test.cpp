// The torus primitive's exact NURBS form (Torus::asNurbs; the sphere's too, Sphere::asNurbs) and the route that
// makes a solid NURBS model meet a torus through the NURBS–NURBS search on it: the form lies on the analytic
// torus, and every distance has a closed form (a torus is the points within r of its core circle, so two tubes
// apart are their circles' distance less both radii; a sphere is dist(centre, circle) − r − its radius from a
// torus).
#include "bench/nurbs_truth.h"
#include "nurbs_fixtures.h"
#include "nurbs_pair_helpers.h"
#include "unidist/distance.h"
#include "unidist/nurbs.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <random>
#include <string>

namespace unidist {
namespace {

using namespace nurbs_fixtures;
using namespace nurbs_pair_helpers;
using Vec = Eigen::Vector3d;

/// The primitive's exact NURBS form, built once on first use, lies on it to rounding with outward normals (but
/// where the chart degenerates: a sphere's poles).
template <class Primitive>
void expectExactForm(const Primitive& primitive, double scale) {
  EXPECT_FALSE(primitive.structures().at(0).built);
  const NurbsModel& form = primitive.asNurbs();
  EXPECT_TRUE(primitive.structures().at(0).built);
  EXPECT_EQ(&form, &primitive.asNurbs());  // built once
  ASSERT_TRUE(form.isSolid());
  const NurbsSurface& s = form.surfaces().at(0);
  for (int i = 0; i <= 40; ++i)
    for (int j = 0; j <= 40; ++j) {
      const double u = i / 40.0, v = j / 40.0;
      const SurfaceDerivatives d = s.derivatives(u, v);
      const SurfacePoint p = primitive.closestPoint(d.point);
      ASSERT_LE(std::abs(p.signedDistance), 1e-15 * scale) << u << " " << v;
      const Vec n = form.orientation() * d.du.cross(d.dv);
      if (n.norm() > 1e-9 * scale * scale) {
        ASSERT_GT(n.normalized().dot(p.normal), 1 - 1e-12) << u << " " << v;
      }
    }
}

TEST(TorusAsNurbs, LiesOnTheTorusWithOutwardNormalsAtEveryScale) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(scale);
    expectExactForm(Torus(0.8 * scale, 0.3 * scale), scale);
  }
}

// The sphere's form (Sphere::asNurbs), which a ball sunk into a non-convex NURBS solid meets it through.
TEST(SphereAsNurbs, LiesOnTheSphereWithOutwardNormalsAtEveryScale) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(scale);
    expectExactForm(Sphere(0.7 * scale), scale);
  }
}

TEST(TorusAsNurbs, NurbsSolidsMeetATorusExactlyAndCertified) {
  const double R = 0.8, r = 0.2;  // the primitive
  const Torus primitive(R, r);
  const auto nurbsTorus = solid(torusSurface(1, 0.25));
  const auto nurbsSphere = solid(sphereSurface(0.3));
  std::mt19937 rng(23);
  int measured = 0;
  for (int k = 0; k < 120 && measured < 24; ++k) {
    const Eigen::Isometry3d X = randomPose(rng, 2);
    const bool sphere = k % 2 == 1;
    const nurbs_truth::Circle core{X.translation(), X.linear() * Vec::UnitZ(), R};
    const double truth = sphere ? nurbs_truth::pointCircle(Vec::Zero(), core) - r - 0.3
                                : nurbs_truth::circleCircle({Vec::Zero(), Vec::UnitZ(), 1}, core) - r - 0.25;
    if (truth < 0.02) continue;
    ++measured;
    const Model& nurbs = sphere ? static_cast<const Model&>(*nurbsSphere) : *nurbsTorus;
    for (double tolerance : {1e-3, 1e-9}) {
      SCOPED_TRACE(testing::Message() << k << " tolerance " << tolerance);
      DistanceOptions opt;
      opt.tolerance = tolerance;
      const DistanceResult ab = distance(nurbs, Eigen::Isometry3d::Identity(), primitive, X, opt);
      const DistanceResult ba = distance(primitive, X, nurbs, Eigen::Isometry3d::Identity(), opt);
      for (const DistanceResult* res : {&ab, &ba}) {
        EXPECT_EQ(std::string(res->method), "nurbs-nurbs-cones-newton");
        EXPECT_EQ(res->status, Status::Certified);
        expectBracket(*res, truth, 1e-12);
        EXPECT_LE(res->upperBound - res->lowerBound, tolerance);
      }
      // The points lie on their own analytic surfaces, and point_b − point_a = distance · normal.
      EXPECT_NEAR(primitive.closestPoint(X.inverse() * ab.pointB).signedDistance, 0, 1e-12);
      EXPECT_NEAR(primitive.closestPoint(X.inverse() * ba.pointA).signedDistance, 0, 1e-12);
      EXPECT_LE((ab.pointB - ab.pointA - ab.distance * ab.normal).norm(), 1e-12);
      EXPECT_LE((ba.pointB - ba.pointA - ba.distance * ba.normal).norm(), 1e-12);
    }
  }
  EXPECT_GE(measured, 16);
}

TEST(TorusAsNurbs, ExtremeScalesAndNearTouchingStayExact) {
  for (double scale : {1e-4, 1e4}) {
    for (double gap : {1e-1, 1e-6}) {
      SCOPED_TRACE(testing::Message() << scale << " gap " << gap);
      const Torus primitive(scale, 0.25 * scale);
      const auto nurbsTorus = solid(torusSurface(1, 0.25, scale));
      Eigen::Isometry3d X = Eigen::Isometry3d::Identity();  // side by side, coplanar: circles 2.5 + gap apart
      X.translation() = scale * Vec(2.5 + gap, 0, 0);
      DistanceOptions opt;
      opt.tolerance = 1e-10 * scale;
      const DistanceResult res = distance(*nurbsTorus, Eigen::Isometry3d::Identity(), primitive, X, opt);
      EXPECT_EQ(res.status, Status::Certified);
      EXPECT_GT(res.lowerBound, 0);
      expectBracket(res, gap * scale, 1e-12 * scale);
    }
  }
}

// Interpenetrating: the analytic torus–torus routine (its own circle search) is the peer; both brackets must hold
// the closed-form depth of side-by-side coplanar tori, 2a less the circles' distance.
TEST(TorusAsNurbs, InterpenetratingTorusHasTheClosedFormDepth) {
  const Torus primitive(1, 0.25);
  const auto nurbsTorus = solid(torusSurface(1, 0.25));
  for (double overlap : {0.05, 0.2}) {
    SCOPED_TRACE(overlap);
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = Vec(2.5 - overlap, 0, 0);
    DistanceOptions opt;
    opt.tolerance = 1e-9;
    const DistanceResult ours = distance(*nurbsTorus, Eigen::Isometry3d::Identity(), primitive, X, opt);
    const DistanceResult peer = distance(primitive, Eigen::Isometry3d::Identity(), primitive, X, opt);
    expectBracket(ours, -overlap, 1e-9);
    expectBracket(peer, -overlap, 1e-9);
    EXPECT_EQ(ours.status, Status::Certified);
  }
}

TEST(TorusAsNurbs, OpenNurbsKeepsTheGenericRoutine) {
  const Torus primitive(0.5, 0.1);
  std::vector<NurbsSurface> v;
  v.push_back(wavySurface());
  const NurbsModel sheet(std::move(v), false);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.translation() = Vec(0, 0, 1.5);
  DistanceOptions opt;
  opt.tolerance = 1e-6;
  const DistanceResult res = distance(sheet, Eigen::Isometry3d::Identity(), primitive, X, opt);
  EXPECT_NE(std::string(res.method), "nurbs-nurbs-cones-newton");
  EXPECT_GT(res.lowerBound, 0.5);
  EXPECT_FALSE(primitive.structures().at(0).built);
}

}  // namespace
}  // namespace unidist
