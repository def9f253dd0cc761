// Simulation contacts (unidist/contact_manifold.h): resting patches filled in (a torus on a box touches along a
// circle: at least three contacts spread around it; a cylinder on its cap: points on the rim), point contacts
// stay single where the tilt finds nothing closer than the margin, the box-on-box corners, the reduction to
// maxContacts, the warm start (local updates while resting give the same contacts as a fresh search; motion
// beyond the guard triggers a global search; a new contact region is never missed), and bad options.
#include "nurbs_fixtures.h"
#include "unidist/contact_manifold.h"
#include "unidist/mesh.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

namespace {

using unidist::Contact;
using unidist::ContactCache;
using unidist::ManifoldOptions;
using Iso = Eigen::Isometry3d;
using Vec = Eigen::Vector3d;

Iso at(const Vec& t, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  Iso X = Iso::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = t;
  return X;
}

double largestSpread(const std::vector<Contact>& cs) {
  double s = 0;
  for (const Contact& a : cs)
    for (const Contact& b : cs) s = std::max(s, (a.pointA - b.pointA).norm());
  return s;
}

void expectConsistent(const std::vector<Contact>& cs) {
  for (const Contact& c : cs) {
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-9);
    EXPECT_LE((c.pointB - c.pointA - c.distance * c.normal).norm(), 1e-9);
  }
}

TEST(Manifold, TorusRestingOnBoxGetsAPatchAroundTheCircle) {
  const unidist::Torus torus(1, 0.25);
  const unidist::Box table(Vec(2, 2, 0.5));
  ManifoldOptions o;
  o.margin = 0.02;
  const auto cs = unidist::manifoldContacts(torus, at(Vec(0, 0, 0.749)), table, Iso::Identity(), o);
  ASSERT_GE(cs.size(), 3u);
  EXPECT_LE(cs.size(), 4u);
  EXPECT_GT(largestSpread(cs), 1.5);  // across the ring (diameter 2), not bunched at one point
  for (const Contact& c : cs) {
    EXPECT_NEAR(c.distance, -0.001, 2e-4);
    EXPECT_NEAR(c.normal.z(), -1, 1e-6);
    EXPECT_NEAR(std::hypot(c.pointA.x(), c.pointA.y()), 1.0, 1e-3);
  }
  expectConsistent(cs);
}

TEST(Manifold, CylinderOnItsCapGetsRimPoints) {
  const unidist::Cylinder cyl(0.5, 0.25);
  const unidist::Plane floor(Vec(0, 0, 1), 0);
  ManifoldOptions o;
  o.margin = 0.01;
  const auto cs = unidist::manifoldContacts(cyl, at(Vec(0, 0, 0.2495)), floor, Iso::Identity(), o);
  ASSERT_GE(cs.size(), 3u);
  EXPECT_GT(largestSpread(cs), 0.9);
  for (const Contact& c : cs) EXPECT_NEAR(c.distance, -0.0005, 1e-5);
  expectConsistent(cs);
}

TEST(Manifold, SphereOnPlaneKeepsItsDeepestPointFirst) {
  const unidist::Sphere ball(0.5);
  const unidist::Plane floor(Vec(0, 0, 1), 0);
  ManifoldOptions o;
  o.margin = 1e-4;  // the tilted points lie 0.5(1 - cos 0.05) = 6e-4 above the plane: outside this margin
  const auto cs = unidist::manifoldContacts(ball, at(Vec(0.3, -0.2, 0.499)), floor, Iso::Identity(), o);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_NEAR(cs[0].distance, -0.001, 1e-9);
  // The tilted patch points walk back onto it (deepen()) and merge with it: equal to 1e-8 of the radius.
  EXPECT_LT((cs[0].pointA - Vec(0.3, -0.2, -0.001)).norm(), 1e-8) << cs[0].pointA.transpose();
}

TEST(Manifold, BoxOnBoxGivesTheFourCorners) {
  const unidist::Box top(Vec(0.5, 0.5, 0.5)), bottom(Vec(2, 2, 0.5));
  ManifoldOptions o;
  o.margin = 0.01;
  const auto cs = unidist::manifoldContacts(top, at(Vec(0.1, 0, 0.999)), bottom, Iso::Identity(), o);
  ASSERT_EQ(cs.size(), 4u);
  for (const Contact& c : cs) {
    EXPECT_NEAR(c.distance, -0.001, 1e-9);
    EXPECT_NEAR(std::abs(c.pointA.x() - 0.1), 0.5, 1e-9);
    EXPECT_NEAR(std::abs(c.pointA.y()), 0.5, 1e-9);
  }
}

TEST(Manifold, AtMostMaxContacts) {
  const unidist::Box top(Vec(0.5, 0.5, 0.5)), bottom(Vec(2, 2, 0.5));
  ManifoldOptions o;
  o.margin = 0.01;
  o.maxContacts = 2;
  const auto cs = unidist::manifoldContacts(top, at(Vec(0, 0, 0.999)), bottom, Iso::Identity(), o);
  ASSERT_EQ(cs.size(), 2u);
  EXPECT_NEAR((cs[0].pointA - cs[1].pointA).norm(), std::sqrt(2.0), 1e-9);  // a diagonal: the most spread pair
}

TEST(Manifold, WarmStartWhileRestingMatchesAFreshSearch) {
  const unidist::Torus torus(1, 0.25);
  const unidist::Box table(Vec(2, 2, 0.5));
  ManifoldOptions o;
  o.margin = 0.02;
  o.tolerance = 1e-4;
  ContactCache cache;
  // The first touch searches at the true pose, the second lifted off along its normal (the skin).
  unidist::manifoldContacts(torus, at(Vec(0, 0, 0.749)), table, Iso::Identity(), o, &cache);
  unidist::manifoldContacts(torus, at(Vec(0, 0, 0.749)), table, Iso::Identity(), o, &cache);
  EXPECT_EQ(cache.globalSearches, 2);
  EXPECT_TRUE(cache.hasLift);
  // Jitter well below the guard (10 × tolerance): local updates, depths follow the motion.
  for (int i = 1; i <= 5; ++i) {
    const Iso X = at(Vec(1e-5 * i, 0, 0.749 - 1e-5 * i), Eigen::Quaterniond(Eigen::AngleAxisd(1e-6 * i, Vec::UnitX())));
    const auto warm = unidist::manifoldContacts(torus, X, table, Iso::Identity(), o, &cache);
    const auto fresh = unidist::manifoldContacts(torus, X, table, Iso::Identity(), o);
    ASSERT_FALSE(warm.empty());
    EXPECT_NEAR(warm.front().distance, fresh.front().distance, 2e-4);
    EXPECT_GE(warm.size(), 3u);
    expectConsistent(warm);
  }
  EXPECT_EQ(cache.globalSearches, 2);
  EXPECT_EQ(cache.localUpdates, 5);
  // A move beyond the guard searches globally again.
  unidist::manifoldContacts(torus, at(Vec(0, 0, 0.74)), table, Iso::Identity(), o, &cache);
  EXPECT_EQ(cache.globalSearches, 3);
}

TEST(Manifold, WarmStartOfNurbsModelsProjectsLocallyAndMatchesAFreshSearch) {
  // A NURBS torus resting on a box, and a NURBS ball on a NURBS ball (both sides curved, turned so that no pole
  // is at the contact): while they jitter below the guard the warm start follows the contacts with the
  // tracker's point Newton from each contact's (u, v), with the same deepest contact as a fresh search.
  const unidist::NurbsModel torus({nurbs_fixtures::torusSurface(1, 0.25)}, true);
  const unidist::NurbsModel ball({nurbs_fixtures::sphereSurface(0.5)}, true);
  const unidist::Box table(Vec(2, 2, 0.5));
  const Eigen::Quaterniond turn(0.9, 0.2, -0.3, 0.25);
  struct Case {
    const unidist::Model& a;
    const unidist::Model& b;
    Iso X_WB;
    double restHeight;
    Eigen::Quaterniond turnA;
  };
  const Case cases[] = {{torus, table, at(Vec(0, 0, -0.5)), 0.25, Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec::UnitZ()))},
                        {ball, ball, at(Vec(0, 0, 0), turn), 1.0, turn}};
  for (const Case& k : cases) {
    ManifoldOptions o;
    o.margin = 0.02;
    o.tolerance = 1e-4;
    ContactCache cache;
    for (int i = 0; i <= 8; ++i) {
      const Iso X = at(Vec(1e-5 * i, 0, k.restHeight - 1e-4 + 1e-5 * (i % 3)),
                       k.turnA * Eigen::Quaterniond(Eigen::AngleAxisd(1e-6 * i, Vec::UnitX())));
      const auto warm = unidist::manifoldContacts(k.a, X, k.b, k.X_WB, o, &cache);
      const auto fresh = unidist::manifoldContacts(k.a, X, k.b, k.X_WB, o);
      ASSERT_FALSE(warm.empty());
      ASSERT_FALSE(fresh.empty());
      EXPECT_NEAR(warm.front().distance, fresh.front().distance, 2e-4) << i;
      EXPECT_LE((warm.front().pointA - fresh.front().pointA).norm(), 0.02) << i;
      expectConsistent(warm);
    }
    EXPECT_GT(cache.localUpdates, 4);
    EXPECT_GT(cache.localProjections, 0);  // the warm start did project locally ...
    EXPECT_LT(cache.projectionFallbacks * 10, cache.localProjections);  // ... and seldom needed the exact search
  }
}

TEST(Manifold, WarmStartSeesANewRegionWithinTheGuard) {
  // A box hovering just outside the margin over a plane: the cached search saw its corners within the grown
  // margin, so lowering it by less than the guard reports them (a cache that forgot them would report nothing).
  const unidist::Box box(Vec(0.5, 0.5, 0.5));
  const unidist::Plane floor(Vec(0, 0, 1), 0);
  ManifoldOptions o;
  o.margin = 0;
  o.tolerance = 1e-4;
  ContactCache cache;
  EXPECT_TRUE(unidist::manifoldContacts(box, at(Vec(0, 0, 0.5005)), floor, Iso::Identity(), o, &cache).empty());
  const auto cs = unidist::manifoldContacts(box, at(Vec(0, 0, 0.4995)), floor, Iso::Identity(), o, &cache);
  EXPECT_EQ(cache.localUpdates, 1);
  ASSERT_EQ(cs.size(), 4u);
  for (const Contact& c : cs) EXPECT_NEAR(c.distance, -0.0005, 1e-9);
}

TEST(Manifold, SkinMeasuresAnOverlapWithAnOpenFloorAsASeparation) {
  // An open floor has no inside: a box corner just below it would read a small positive distance with the
  // normal the wrong way. After a step touching from above, the lifted measurement gives the four corners at
  // the true (negative) depth, pushing up.
  std::vector<Vec> v = {{-2, -2, 0}, {2, -2, 0}, {2, 2, 0}, {-2, 2, 0}};
  const unidist::TriangleMesh floor(v, {{0, 1, 2}, {0, 2, 3}});
  const unidist::Box box(Vec(0.25, 0.25, 0.25));
  ManifoldOptions o;
  o.margin = 0.01;
  ContactCache cache;
  ASSERT_FALSE(unidist::manifoldContacts(box, at(Vec(0.3, 0.1, 0.2505)), floor, Iso::Identity(), o, &cache).empty());
  const auto cs = unidist::manifoldContacts(box, at(Vec(0.3, 0.1, 0.2497)), floor, Iso::Identity(), o, &cache);
  ASSERT_EQ(cs.size(), 4u);
  for (const Contact& c : cs) {
    EXPECT_NEAR(c.distance, -0.0003, 1e-9);
    EXPECT_NEAR(c.normal.z(), -1, 1e-9);
    EXPECT_NEAR(std::abs(c.pointA.x() - 0.3), 0.25, 1e-9);
  }
  expectConsistent(cs);
}

TEST(Manifold, BadOptionsAreErrors) {
  const unidist::Sphere s(1);
  ManifoldOptions o;
  o.maxContacts = 0;
  EXPECT_THROW(unidist::manifoldContacts(s, Iso::Identity(), s, Iso::Identity(), o), unidist::InputError);
  o = ManifoldOptions{};
  o.margin = -1;
  EXPECT_THROW(unidist::manifoldContacts(s, Iso::Identity(), s, Iso::Identity(), o), unidist::InputError);
  o = ManifoldOptions{};
  o.tolerance = std::nan("");
  EXPECT_THROW(unidist::manifoldContacts(s, Iso::Identity(), s, Iso::Identity(), o), unidist::InputError);
  Iso bad = Iso::Identity();
  bad.translation().x() = std::nan("");
  EXPECT_THROW(unidist::manifoldContacts(s, bad, s, Iso::Identity(), ManifoldOptions{}), unidist::InputError);
}

}  // namespace
