// Every contact reports how exact it is (Contact::errorBound, docs/contacts.md): against analytic truth, the
// reported distance is within the bound of what it measures, and the bound is small where the contact is
// computed in closed form (box corners, also 1e6 from the origin), the search tolerance where a NURBS search or
// a coarse global query answered, and a level of detail's deviation at a level of detail; the same for the
// simulation contacts of a ball resting and rolling on a box (warm start and skin included).
#include "mesh_fixtures.h"
#include "nurbs_fixtures.h"
#include "unidist/contact_manifold.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <cmath>

namespace {

using unidist::Contact;
using Iso = Eigen::Isometry3d;
using Vec = Eigen::Vector3d;

Iso at(const Vec& t) {
  Iso X = Iso::Identity();
  X.translation() = t;
  return X;
}

/// A turned pose: a ball's stand-in mesh then has no vertex at the ball's lowest point, so a level of detail
/// really moves its contacts (by up to the deviation) and the bound must cover it.
Iso turned(const Vec& t) {
  Iso X = at(t);
  X.linear() = Eigen::Quaterniond(0.9, 0.2, -0.3, 0.25).normalized().toRotationMatrix();
  return X;
}

unidist::NurbsModel ball(double r) { return unidist::NurbsModel({nurbs_fixtures::sphereSurface(r)}, true); }

TEST(ContactErrorBound, BoxCornersAreExactAlsoFarFromTheOrigin) {
  const unidist::TriangleMesh a = meshfix::makeMesh(meshfix::gridBox(Vec(1, 1, 1), 1));
  const unidist::TriangleMesh b = meshfix::makeMesh(meshfix::gridBox(Vec(0.5, 0.5, 0.5), 1));
  const double gap = 1e-3;
  unidist::ContactOptions o;
  o.margin = 0.01;
  for (const double offset : {0.0, 1e3, 1e6}) {
    SCOPED_TRACE(offset);
    const Vec far(offset, -offset, offset);
    const std::vector<Contact> cs = unidist::contacts(a, at(far), b, at(far + Vec(0.2, 0, 1.5 + gap)), o);
    ASSERT_EQ(cs.size(), 4u);
    for (const Contact& c : cs) {
      EXPECT_LE(std::abs(c.distance - gap), c.errorBound);
      EXPECT_LE(c.errorBound, 1e-13 * (1 + offset));  // rounding of the coordinates only
    }
  }
}

/// Signed distance from p to the ball of radius r at c: the truth of every contact of a mesh against it (the
/// contact's mesh point is exact; the distance is measured from it, or is the global minimum, which it attains).
double ballDistance(const Vec& p, const Vec& c, double r) { return (p - c).norm() - r; }

TEST(ContactErrorBound, MeshAgainstANurbsBallHoldsTheTruthAtEveryDial) {
  const unidist::TriangleMesh floor = meshfix::makeMesh(meshfix::gridBox(Vec(1, 1, 0.25), 4));
  const unidist::NurbsModel b = ball(0.5);
  const Vec centre(0.1, -0.2, 0.25 + 0.5 + 2e-3);
  for (const double tol : {1e-9, 1e-3, 1e-2}) {
    for (const double detail : {0.0, 0.01}) {
      SCOPED_TRACE(testing::Message() << "tol " << tol << " detail " << detail);
      unidist::ContactOptions o;
      o.margin = 0.05;
      o.tolerance = tol;
      o.detailB = detail;
      const std::vector<Contact> cs = unidist::contacts(floor, Iso::Identity(), b, turned(centre), o);
      ASSERT_FALSE(cs.empty());
      for (const Contact& c : cs) {
        EXPECT_LE(std::abs(c.distance - ballDistance(c.pointA, centre, 0.5)), c.errorBound + 1e-12);
        EXPECT_LE(c.errorBound, detail + 2 * tol + 1e-9);
      }
    }
  }
}

TEST(ContactErrorBound, TwoNurbsBallsAtACoarseTolerance) {
  const unidist::NurbsModel a = ball(1), b = ball(0.5);
  const double gap = 0.05;
  const Vec direction = Vec(1, 2, -0.5).normalized();
  for (const double tol : {1e-10, 1e-4, 1e-2}) {
    SCOPED_TRACE(tol);
    unidist::ContactOptions o;
    o.margin = 0.1;
    o.tolerance = tol;
    const std::vector<Contact> cs = unidist::contacts(a, Iso::Identity(), b, at((1.5 + gap) * direction), o);
    ASSERT_EQ(cs.size(), 1u);
    EXPECT_LE(std::abs(cs[0].distance - gap), cs[0].errorBound);
    EXPECT_LE(cs[0].errorBound, 2 * tol + 1e-12);
  }
}

TEST(ContactErrorBound, SimulationContactsOfABallRestingAndRollingOnABox) {
  const unidist::NurbsModel a = ball(0.5);
  const unidist::Box floor(Vec(2, 2, 0.5));  // top face at z = 0
  for (const double detail : {0.0, 0.01}) {
    SCOPED_TRACE(detail);
    unidist::ManifoldOptions o;
    o.margin = 0.01;
    o.detailA = detail;
    unidist::ContactCache cache;
    // Settling onto the box, a few resting overlaps, then rolling slowly (warm start) and faster (new searches).
    double x = 0;
    for (int step = 0; step < 200; ++step) {
      const double h = step < 50 ? 2e-3 * (1 - step / 50.0) : -2e-5 * std::sin(0.3 * step);
      x += step < 120 ? 1e-6 : 1e-3;
      const Vec centre(x, 0.3, 0.5 + h);
      const std::vector<Contact> cs = unidist::manifoldContacts(a, turned(centre), floor, at(Vec(0, 0, -0.5)), o, &cache);
      ASSERT_FALSE(cs.empty()) << step;
      for (const Contact& c : cs) {
        // The top face is flat and far wider than the ball: the box's signed distance at A's point is its height.
        EXPECT_LE(std::abs(c.distance - c.pointA.z()), c.errorBound + 1e-12) << step;
        EXPECT_LE(c.errorBound, detail + 1e-4) << step;
      }
      // The deepest contact is the ball's lowest point, h above the box (the stand-in's: up to the deviation).
      EXPECT_LE(std::abs(cs.front().distance - h), cs.front().errorBound + 1e-6) << step;
    }
    EXPECT_GT(cache.localUpdates, 0);
    EXPECT_GT(cache.globalSearches, 1);
  }
}

}  // namespace
