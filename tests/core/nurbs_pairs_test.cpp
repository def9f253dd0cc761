// The NURBS pair routines (core/src/pairs/nurbs_convex.cpp, nurbs_nurbs.cpp) against analytic truth: the
// exact rational sphere and torus, so every distance has a closed form (a ball against a solid is the
// solid's signed distance at the centre minus the radius, also when penetrating a convex solid).
#include "bench/nurbs_truth.h"
#include "mesh_fixtures.h"
#include "nurbs_fixtures.h"
#include "nurbs_pair_helpers.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <random>
#include <string>

namespace unidist {
namespace {

using namespace nurbs_fixtures;
using namespace nurbs_pair_helpers;
using Vec = Eigen::Vector3d;

double boxSignedDistance(const Vec& h, const Vec& q) {
  const Vec d = q.cwiseAbs() - h;
  return d.cwiseMax(0.0).norm() + std::min(d.maxCoeff(), 0.0);
}

double torusSignedDistance(double R, double a, const Vec& q) {
  return std::hypot(std::hypot(q.x(), q.y()) - R, q.z()) - a;
}

TEST(NurbsConvex, BoxAgainstSphereSeparatedIsExactAndCertified) {
  const auto sphere = solid(sphereSurface(1));
  const Vec h(0.8, 0.6, 0.5);
  const Box box(h);
  std::mt19937 rng(7);
  DistanceOptions opt;
  opt.tolerance = 1e-9;
  for (int k = 0; k < 40; ++k) {
    const Eigen::Isometry3d XA = randomPose(rng, 3), XB = randomPose(rng, 3);
    const double truth = boxSignedDistance(h, XA.inverse() * XB.translation()) - 1;
    if (truth < 1e-3) continue;  // separated cases here
    const DistanceResult r = distance(box, XA, *sphere, XB, opt);
    EXPECT_EQ(std::string(r.method), "nurbs-convex-tree-gjk");
    EXPECT_EQ(r.status, Status::Certified);
    expectBracket(r, truth, 1e-12);
    EXPECT_NEAR((r.pointB - r.pointA).norm(), r.distance, 1e-12);
  }
}

TEST(NurbsConvex, BoxPenetratingSphereNearAnEdge) {
  const auto sphere = solid(sphereSurface(1));
  const Vec h(0.8, 0.6, 0.5);
  const Box box(h);
  DistanceOptions opt;
  opt.tolerance = 1e-6;
  // Centre outside the box near its edge (x, y beyond the faces): depth = 1 − distance(centre, box).
  for (const Vec& c : {Vec(1.1, 0.9, 0.1), Vec(1.3, 0.2, -0.3), Vec(0.2, 0.1, 1.2)}) {
    Eigen::Isometry3d XB = Eigen::Isometry3d::Identity();
    XB.translation() = c;
    const double truth = boxSignedDistance(h, c) - 1;
    const DistanceResult r = distance(box, Eigen::Isometry3d::Identity(), *sphere, XB, opt);
    expectBracket(r, truth, 1e-9);
    EXPECT_NEAR(r.distance, truth, 1e-6);
    EXPECT_LT(r.upperBound, 0);
  }
}

TEST(NurbsConvex, BoxInsideSphereIsAnOverlap) {
  const auto sphere = solid(sphereSurface(2));
  const Box box(Vec(0.1, 0.1, 0.1));
  DistanceOptions opt;
  opt.tolerance = 1e-6;
  opt.maxIterations = 1000;  // only the overlap verdict is checked; the depth search near a centre is slow
  Eigen::Isometry3d XA = Eigen::Isometry3d::Identity();
  XA.translation() = Vec(1.2, 0.3, 0);
  const DistanceResult r = distance(box, XA, *sphere, Eigen::Isometry3d::Identity(), opt);
  EXPECT_LT(r.upperBound, 0);  // surfaces apart, yet the interiors overlap
}

TEST(NurbsNurbs, SphereAgainstTorusSeparatedIsExactAndCertified) {
  const double R = 1, a = 0.25, rs = 0.3;
  const auto torus = solid(torusSurface(R, a));
  const auto sphere = solid(sphereSurface(rs));
  std::mt19937 rng(11);
  DistanceOptions opt;
  opt.tolerance = 1e-9;
  int measured = 0;
  for (int k = 0; k < 60 && measured < 12; ++k) {
    const Eigen::Isometry3d XA = randomPose(rng, 1), XB = randomPose(rng, 2);
    const double truth = torusSignedDistance(R, a, XA.inverse() * XB.translation()) - rs;
    if (truth < 1e-3) continue;
    ++measured;
    const DistanceResult r = distance(*torus, XA, *sphere, XB, opt);
    EXPECT_EQ(std::string(r.method), "nurbs-nurbs-cones-newton");
    EXPECT_EQ(r.status, Status::Certified);
    expectBracket(r, truth, 1e-12);
  }
  EXPECT_GE(measured, 8);
}

// Tori in random poses: the solids are the core circles widened by the tube radius, so apart they are the
// circles' distance less 2a apart. Most closest pairs lie on the outer, convex parts (the support plane settles
// them), some on the inner saddles.
TEST(NurbsNurbs, RandomlyPlacedToriAreExactAndCertified) {
  const double R = 1, a = 0.25;
  const auto torus = solid(torusSurface(R, a));
  std::mt19937 rng(17);
  int measured = 0;
  for (int k = 0; k < 80 && measured < 16; ++k) {
    const Eigen::Isometry3d XB = randomPose(rng, 2);
    const nurbs_truth::Circle ca{Vec::Zero(), Vec::UnitZ(), R}, cb{XB.translation(), XB.linear() * Vec::UnitZ(), R};
    const double truth = nurbs_truth::circleCircle(ca, cb) - 2 * a;
    if (truth < 0.02) continue;
    ++measured;
    for (double tolerance : {1e-3, 1e-9}) {
      DistanceOptions opt;
      opt.tolerance = tolerance;
      const DistanceResult r = distance(*torus, Eigen::Isometry3d::Identity(), *torus, XB, opt);
      EXPECT_EQ(std::string(r.method), "nurbs-nurbs-cones-newton");
      EXPECT_EQ(r.status, Status::Certified);
      expectBracket(r, truth, 1e-12);
      EXPECT_LE(r.upperBound - r.lowerBound, tolerance);
    }
  }
  EXPECT_GE(measured, 12);
}

// The support plane's certified heights at tiny and huge scales: the benchmark's tilted tori (a convex contact)
// and two spheres 1e-6 of their size apart, scaled by 1e-4 and 1e4.
TEST(NurbsNurbs, ConvexContactsAtExtremeScalesAreExactAndCertified) {
  const std::vector<nurbs_truth::Placement> placements = nurbs_truth::placements();
  const auto tilted = std::find_if(placements.begin(), placements.end(),
                                   [](const auto& p) { return std::string(p.name) == "torus-torus tilted"; });
  ASSERT_NE(tilted, placements.end());
  for (double scale : {1e-4, 1e4}) {
    SCOPED_TRACE(scale);
    DistanceOptions opt;
    opt.tolerance = 1e-9 * scale;
    const auto torus = solid(torusSurface(1, 0.25, scale));
    Eigen::Isometry3d X = tilted->X_WB;
    X.translation() *= scale;
    const DistanceResult r = distance(*torus, Eigen::Isometry3d::Identity(), *torus, X, opt);
    EXPECT_EQ(r.status, Status::Certified);
    expectBracket(r, tilted->truth * scale, 1e-12 * scale);

    const auto sphere = solid(sphereSurface(scale));
    Eigen::Isometry3d XB = Eigen::Isometry3d::Identity();
    const double gap = 1e-6 * scale;
    XB.translation() = Vec(0.3, -0.5, 0.8).normalized() * (2 * scale + gap);
    const DistanceResult s = distance(*sphere, Eigen::Isometry3d::Identity(), *sphere, XB, opt);
    EXPECT_EQ(s.status, Status::Certified);
    EXPECT_GT(s.lowerBound, 0);
    expectBracket(s, gap, 1e-12 * scale);
  }
}

// A contact on the torus's saddle side (the benchmark's sphere above the torus, and a sphere 1e-6 of the size
// from the inner equator) at tiny and huge scales: the support ball's certificates (support_ball.h) carry the
// bounds there; exact to 1e-12 of the size, certified.
TEST(NurbsNurbs, SaddleContactsAtExtremeScalesAreExactAndCertified) {
  const std::vector<nurbs_truth::Placement> placements = nurbs_truth::placements();
  const auto above = std::find_if(placements.begin(), placements.end(),
                                  [](const auto& p) { return std::string(p.name) == "torus-sphere above"; });
  ASSERT_NE(above, placements.end());
  for (double scale : {1e-4, 1.0, 1e4}) {
    SCOPED_TRACE(scale);
    DistanceOptions opt;
    opt.tolerance = 1e-9 * scale;
    const auto torus = solid(torusSurface(1, 0.25, scale));
    const auto sphere = solid(sphereSurface(0.4 * scale));
    Eigen::Isometry3d X = above->X_WB;
    X.translation() *= scale;
    const DistanceResult r = distance(*torus, Eigen::Isometry3d::Identity(), *sphere, X, opt);
    EXPECT_EQ(r.status, Status::Certified);
    expectBracket(r, above->truth * scale, 1e-12 * scale);
    // A small sphere just inside the hole, off the torus's plane: its closest point on the inner side, a gap of
    // 1e-6 of the size.
    const Vec centre = scale * Vec(0.3, 0.1, 0.12);
    const double gap = 1e-6 * scale;
    const double toCircle = nurbs_truth::pointCircle(centre, {Vec::Zero(), Vec::UnitZ(), scale});
    const double radius = toCircle - 0.25 * scale - gap;
    const auto near = solid(sphereSurface(radius));
    Eigen::Isometry3d XS = Eigen::Isometry3d::Identity();
    XS.translation() = centre;
    const DistanceResult s = distance(*torus, Eigen::Isometry3d::Identity(), *near, XS, opt);
    EXPECT_EQ(s.status, Status::Certified);
    EXPECT_GT(s.lowerBound, 0);
    expectBracket(s, gap, 1e-12 * scale);
  }
}

// A sphere centred on the torus's axis: the closest points form a circle on each model, so no pair of nodes
// holds the minimum alone. The support ball about the sphere's centre fits with no margin; its certificates
// subdivide the distance forms across the circle only (ratio_subdivision.h). Before, such a query spent its
// whole pair budget and came back bounded, 1e-5 wide at 1e-9.
TEST(NurbsNurbs, SphereOnTheTorusAxisIsCertified) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    const auto torus = solid(torusSurface(1, 0.25, scale));
    for (double height : {0.0, 0.05, 0.3, 0.75}) {
      for (double gap : {0.35, 1e-6, 1e-9}) {
        SCOPED_TRACE(::testing::Message() << "scale " << scale << " height " << height << " gap " << gap);
        const Vec centre(0, 0, height * scale);
        const double radius = nurbs_truth::pointCircle(centre, {Vec::Zero(), Vec::UnitZ(), scale}) - 0.25 * scale -
                              gap * scale;
        const auto sphere = solid(sphereSurface(radius));
        Eigen::Isometry3d XS = Eigen::Isometry3d::Identity();
        XS.translation() = centre;
        for (double tolerance : {1e-6, 1e-12}) {
          DistanceOptions opt;
          opt.tolerance = tolerance * scale;
          const DistanceResult r = distance(*torus, Eigen::Isometry3d::Identity(), *sphere, XS, opt);
          EXPECT_EQ(r.status, Status::Certified);
          EXPECT_LE(r.upperBound - r.lowerBound, opt.tolerance);
          expectBracket(r, gap * scale, 1e-12 * scale);
        }
      }
    }
  }
}

// A ball resting on a ring (on its axis, touching along a circle, at the acceptance case's height 0.75 and inside
// the hole): certified touching. Moving the ball half a tolerance along the axis is proved apart, which bounds the
// depth by that (before: the generic routine, 2.7 s, bounded [−1.68, 0]). The answer keeps the contract's
// point_b − point_a = distance · normal.
TEST(NurbsNurbs, BallRestingOnARingIsCertifiedTouching) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    const auto torus = solid(torusSurface(1, 0.25, scale));
    for (double height : {0.3, 0.75}) {
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " height " << height);
      const Vec centre(0, 0, height * scale);
      const double radius = nurbs_truth::pointCircle(centre, {Vec::Zero(), Vec::UnitZ(), scale}) - 0.25 * scale;
      const auto sphere = solid(sphereSurface(radius));
      Eigen::Isometry3d XS = Eigen::Isometry3d::Identity();
      XS.translation() = centre;
      DistanceOptions opt;
      opt.tolerance = 1e-9 * scale;
      const DistanceResult r = distance(*torus, Eigen::Isometry3d::Identity(), *sphere, XS, opt);
      EXPECT_EQ(r.status, Status::Certified);
      EXPECT_STREQ(r.method, "nurbs-nurbs-touching-escape");
      expectBracket(r, 0.0, 1e-12 * scale);
      // The contract's tie of normal and points (the normal is free only where the points coincide).
      EXPECT_LE((r.pointB - r.pointA - r.distance * r.normal).norm(), 1e-15 * scale);
    }
  }
}

// A torus lying on a box, and on another torus, touches it along a circle in one plane: the supporting planes
// across the contact normal settle every node at once (before: the box 1.1 s and bounded [−2.0, 0] after the node
// budget; the torus pair the generic routine). Tilted poses and three scales; 1e-7 apart stays proved apart.
TEST(NurbsNurbs, TorusLyingOnABoxOrATorusIsCertifiedTouching) {
  for (double scale : {1e-4, 1.0, 1e4}) {
    const auto torus = solid(torusSurface(1, 0.25, scale));
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.linear() = Eigen::AngleAxisd(0.7, Vec(1, 2, 3).normalized()).toRotationMatrix();
    X.translation() = Vec(0.3, -0.2, 0.1) * scale;
    const Vec down = X.linear() * Vec(0, 0, -1);
    const Box box(Vec(2, 2, 1) * scale);
    for (double gap : {0.0, 1e-7}) {
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " gap " << gap);
      DistanceOptions opt;
      opt.tolerance = 1e-9 * scale;
      Eigen::Isometry3d XB = X;
      XB.translation() += (1.25 + gap) * scale * down;  // the box's top face 0.25 below the torus's plane
      const DistanceResult onBox = distance(*torus, X, box, XB, opt);
      EXPECT_EQ(onBox.status, Status::Certified);
      expectBracket(onBox, gap * scale, 1e-12 * scale);
      Eigen::Isometry3d XT = X;
      XT.translation() += (0.5 + gap) * scale * down;
      const DistanceResult onTorus = distance(*torus, X, *torus, XT, opt);
      EXPECT_EQ(onTorus.status, Status::Certified);
      expectBracket(onTorus, gap * scale, 1e-12 * scale);
    }
  }
}

TEST(NurbsNurbs, NearlyTouchingSpheresAreProvedApart) {
  const auto s = solid(sphereSurface(1));
  DistanceOptions opt;
  opt.tolerance = 1e-12;
  for (double gap : {1e-3, 1e-6, 1e-9}) {
    Eigen::Isometry3d XB = Eigen::Isometry3d::Identity();
    XB.translation() = Vec(2 + gap, 0.3, -0.2).normalized() * (2 + gap);
    const DistanceResult r = distance(*s, Eigen::Isometry3d::Identity(), *s, XB, opt);
    EXPECT_EQ(std::string(r.method), "nurbs-nurbs-cones-newton");
    EXPECT_GT(r.lowerBound, 0);
    expectBracket(r, gap, 1e-13);
  }
}

// Interpenetrating tori whose core circles are coplanar (side by side, centres D apart) or coaxial (h apart
// along the axis): the circles' distance is 1-Lipschitz in the translation and the tubes separate when it reaches
// 2a, so the depth is exactly 2a minus the circles' distance, reached along the line of closest circle points.
TEST(NurbsNurbs, InterpenetratingToriGetTheExactMinimumTranslation) {
  const double R = 1, a = 0.25;
  std::mt19937 rng(5);
  for (double scale : {1e-4, 1.0, 1e4}) {
    const auto torus = solid(torusSurface(R * scale, a * scale));
    DistanceOptions opt;
    opt.tolerance = 1e-9 * scale;
    struct Placement {
      Vec offset;
      double depth;
      bool shallow;  // the deepest surface point is as deep as the translation: proved at once
    };
    for (const Placement& p : {Placement{Vec(2.3, 0, 0), 0.2, true}, Placement{Vec(0, 2.45, 0), 0.05, true},
                               Placement{Vec(0, 0, 0.35), 0.15, true}, Placement{Vec(0, 0, 0.1), 0.4, false}}) {
      SCOPED_TRACE(::testing::Message() << "scale " << scale << " offset " << p.offset.transpose());
      const Eigen::Isometry3d XA = randomPose(rng, scale);
      Eigen::Isometry3d XB = XA;
      XB.translation() += XA.linear() * (p.offset * scale);
      const DistanceResult r = distance(*torus, XA, *torus, XB, opt);
      // A deep overlap (the deepest point only 0.1 deep for a 0.4 translation): the escape is exact; the balls
      // inscribed in both tubes at its contact prove it where that contact pair is collinear to the tolerance,
      // else the first-order cone search brackets it within a few 1e-3 (bounded, never wrong).
      if (p.shallow) {
        EXPECT_EQ(r.status, Status::Certified);
      }
      expectBracket(r, -p.depth * scale, 1e-12 * scale);
      EXPECT_NEAR(r.distance, -p.depth * scale, 1e-9 * scale);
      EXPECT_LT(r.upperBound - r.lowerBound, 1e-2 * scale);
      // The normal is the way B leaves: along the circles' closest-point line.
      const Vec away = XA.linear() * p.offset.normalized();
      EXPECT_GT(std::abs(r.normal.dot(away)), 1 - 1e-6);
    }
  }
}

TEST(NurbsNurbs, OverlappingSpheresGetTheirExactDepth) {
  const auto s = solid(sphereSurface(1));
  DistanceOptions opt;
  opt.tolerance = 1e-10;
  for (double d : {1.999, 1.5, 0.7}) {
    SCOPED_TRACE(::testing::Message() << "centres " << d << " apart");
    Eigen::Isometry3d XB = Eigen::Isometry3d::Identity();
    XB.translation() = Vec(0.3, -1, 0.5).normalized() * d;
    const DistanceResult r = distance(*s, Eigen::Isometry3d::Identity(), *s, XB, opt);
    // Past the centres (d < 1) the deepest surface point (depth 1 − (1 − d) = d = 0.7) no longer proves the depth
    // (1.3): the answer is exact but only bracketed.
    if (d > 1) {
      EXPECT_EQ(r.status, Status::Certified);
    }
    expectBracket(r, d - 2, 1e-12);
    EXPECT_NEAR(r.distance, d - 2, 1e-9);
  }
}

// A NURBS ball against a mesh is the mesh's distance to the centre minus the radius (when apart): the long-double
// point–triangle oracle of the mesh tests gives the truth. Solid (non-convex torus) and open (wavy sheet) meshes.
TEST(NurbsMesh, BallAgainstMeshesMatchesThePointTriangleOracle) {
  const double rs = 0.3;
  const auto ball = solid(sphereSurface(rs));
  const meshfix::Soup torus = meshfix::torus(1, 0.3, 24, 12), sheet = meshfix::wavySheet(12);
  DistanceOptions opt;
  opt.tolerance = 1e-10;
  std::mt19937 rng(3);
  for (const meshfix::Soup* soup : {&torus, &sheet}) {
    const TriangleMesh mesh = meshfix::makeMesh(*soup);
    int measured = 0;
    for (int k = 0; k < 200 && measured < 15; ++k) {
      const Eigen::Isometry3d XA = randomPose(rng, 1.5), XB = randomPose(rng, 0.5);
      const Vec centreInMesh = XB.inverse() * XA.translation();
      if (mesh.isSolid() && meshfix::bruteWinding(*soup, centreInMesh) > 0.5) continue;  // centre inside the torus
      const double truth = meshfix::bruteDistance(*soup, centreInMesh) - rs;
      if (truth < 1e-3) continue;
      ++measured;
      const DistanceResult r = distance(*ball, XA, mesh, XB, opt);
      EXPECT_EQ(std::string(r.method), "nurbs-mesh-cones-gjk");
      EXPECT_EQ(r.status, Status::Certified);
      expectBracket(r, truth, 1e-12);
      const DistanceResult back = distance(mesh, XB, *ball, XA, opt);  // the other order, the same answer
      EXPECT_NEAR(back.distance, r.distance, 1e-12);
    }
    EXPECT_GE(measured, 10);
  }
}

// An exact torus against a tessellation of the same torus (vertices on the surface, so the mesh lies inside
// the smooth solid by at most its chord error): side by side, overlapping by 0.2. The depth lies in
// [0.2 − chord error, 0.2]; the separation tests of the depth search run through the NURBS–mesh search.
TEST(NurbsMesh, InterpenetratingTorusAndItsTessellation) {
  const double R = 1, a = 0.25;
  const auto torus = solid(torusSurface(R, a));
  const int nu = 64, nv = 32;
  const double chord = a * (1 - std::cos(M_PI / nv)) + (R + a) * (1 - std::cos(M_PI / nu));
  const TriangleMesh mesh = meshfix::makeMesh(meshfix::torus(R, a, nu, nv));
  DistanceOptions opt;
  opt.tolerance = 1e-6;
  Eigen::Isometry3d XB = Eigen::Isometry3d::Identity();
  XB.translation() = Vec(2.3, 0, 0);
  const DistanceResult r = distance(*torus, Eigen::Isometry3d::Identity(), mesh, XB, opt);
  EXPECT_LT(r.upperBound, 0);
  EXPECT_LE(r.lowerBound, -0.2 + chord + 1e-9);
  EXPECT_GE(r.upperBound, -0.2 - 1e-9);
  // The reported escape really separates (it is no shorter than the depth) and is within the tolerance of it.
  EXPECT_GE(r.distance, -0.2 - opt.tolerance);
  EXPECT_LE(r.distance, -0.2 + chord);
  // Moved apart by 0.1, the surfaces are 0.1 apart where the outer rims face each other (vertices lie there).
  XB.translation() = Vec(2.6, 0, 0);
  const DistanceResult apart = distance(*torus, Eigen::Isometry3d::Identity(), mesh, XB, opt);
  EXPECT_EQ(std::string(apart.method), "nurbs-mesh-cones-gjk");
  EXPECT_EQ(apart.status, Status::Certified);
  EXPECT_NEAR(apart.distance, 0.1, 1e-6);
}

}  // namespace
}  // namespace unidist
