// The box–box contact manifold (core/src/contacts/box_box_contacts.cpp) against oracles, on hundreds of random
// poses of every kind (fixed seeds): face on face resting with tiny tilts, edge–edge crossings, a vertex in a face,
// boxes apart within the margin, identical coincident boxes, scales 1e-4 and 1e4, very thin boxes.
//  (a) the deepest contact's distance is the exact signed distance (unidist::distance at full accuracy), within
//      1e-9 × size; contacts exist exactly when that distance is within the margin;
//  (b) every pointA lies on A's surface and pointB on B's (closest-point distance ~0), pointB − pointA = distance ·
//      normal, the normal is unit;
//  (c) face on face, the contact points' convex hull covers the true overlap of the two faces' projections (a fine
//      grid over the overlap, computed by brute force from the two rectangles);
//  (d) no contact is deeper than the true penetration.
// manifoldContacts() is checked to answer a box pair through the same routine (same contacts, both orders).
#include "contacts/box_box_contacts.h"
#include "core/case_budget.h"
#include "unidist/contact_manifold.h"
#include "unidist/distance.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

namespace {

using unidist::Box;
using unidist::Contact;
using Iso = Eigen::Isometry3d;
using Vec = Eigen::Vector3d;
using Vec2 = Eigen::Vector2d;
using namespace unidist::testing;

/// A posed pair and the margin to ask with.
struct Case {
  Box a, b;
  Iso X_WA, X_WB;
  double margin;
  bool faceOnFace = false;  ///< B's bottom face (local −z) rests on A's top face (local +z)
  std::string label;
};

double sizeOf(const Case& c) { return 2 * std::max(c.a.halfExtents().norm(), c.b.halfExtents().norm()); }

class Sampler {
 public:
  explicit Sampler(unsigned seed) : rng_(seed) {}
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng_); }
  Vec unitVector() {
    Vec v;
    do v = Vec(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    while (v.squaredNorm() > 1 || v.squaredNorm() < 1e-4);
    return v.normalized();
  }
  Eigen::Matrix3d rotation() { return Eigen::AngleAxisd(uniform(0, kPi), unitVector()).toRotationMatrix(); }
  Iso pose(double reach) {
    Iso X = Iso::Identity();
    X.linear() = rotation();
    X.translation() = reach * Vec(uniform(-1, 1), uniform(-1, 1), uniform(-1, 1));
    return X;
  }
  Vec halfExtents(double lo, double hi) { return Vec(uniform(lo, hi), uniform(lo, hi), uniform(lo, hi)); }

 private:
  std::mt19937 rng_;
};

Iso fromParts(const Eigen::Matrix3d& R, const Vec& t) {
  Iso X = Iso::Identity();
  X.linear() = R;
  X.translation() = t;
  return X;
}

/// B lies on A's top face, turned about the normal, tilted by a tiny angle, offset sideways so that the faces
/// overlap in part or wholly, at a gap of ±1 % of the size.
Case faceOnFace(Sampler& s, double scale, const Vec& hA, const Vec& hB) {
  const Eigen::Matrix3d spin = Eigen::AngleAxisd(s.uniform(-kPi, kPi), Vec::UnitZ()).toRotationMatrix();
  const double tiltAngle = std::pow(10.0, s.uniform(-7, -3));
  const Eigen::Matrix3d tilt = Eigen::AngleAxisd(tiltAngle, Vec(s.uniform(-1, 1), s.uniform(-1, 1), 0).normalized())
                                   .toRotationMatrix();
  const Eigen::Matrix3d R = tilt * spin;
  const double gap = s.uniform(-0.01, 0.01) * hB.z();
  const Vec offset(s.uniform(-1, 1) * hA.x(), s.uniform(-1, 1) * hA.y(), 0);
  // B's bottom centre sits at offset + (0, 0, hA.z + gap) (up to the tilt's second-order drop of its corners).
  const Vec t = offset + Vec(0, 0, hA.z() + gap) + R * Vec(0, 0, hB.z());
  const Iso X_WA = s.pose(2 * scale);
  // Every corner of the contact polygon within the margin: the gap, plus what the tilt lifts a corner by.
  const double margin = std::abs(gap) + 0.05 * hB.z() + 4 * tiltAngle * (hA.norm() + hB.norm());
  return Case{Box(hA), Box(hB), X_WA, X_WA * fromParts(R, t), margin, true, "face on face"};
}

/// An edge of B crossing A's top edge along x (at y = +hy, z = +hz) at a random angle, gap ±2 % of the size.
Case edgeEdge(Sampler& s, double scale, const Vec& hA, const Vec& hB) {
  const Vec n = Vec(0, 1, 1).normalized();          // outward direction of A's edge
  const Vec side = Vec(0, 1, -1).normalized();      // the other direction perpendicular to x and n
  const double beta = s.uniform(0.3, 1.3);
  const Vec dB = std::cos(beta) * Vec::UnitX() + std::sin(beta) * side;  // B's edge direction
  // B's local x → dB, B's local corner direction (0, 1, 1)/√2 → n: its edge at (y, z) = (−hy, −hz) faces −n.
  Eigen::Matrix3d local, world;
  local << Vec::UnitX(), Vec(0, 1, 1).normalized(), Vec(0, -1, 1).normalized();
  world << dB, n, dB.cross(n);
  const Eigen::Matrix3d wobble = Eigen::AngleAxisd(s.uniform(-0.2, 0.2), n).toRotationMatrix();
  const Eigen::Matrix3d R = wobble * world * local.transpose();
  const double gap = s.uniform(-0.02, 0.02) * std::min(hA.minCoeff(), hB.minCoeff());
  const Vec onEdgeA(s.uniform(-0.5, 0.5) * hA.x(), hA.y(), hA.z());
  const Vec t = onEdgeA + gap * n - R * Vec(s.uniform(-0.5, 0.5) * hB.x(), -hB.y(), -hB.z());
  const Iso X_WA = s.pose(2 * scale);
  return Case{Box(hA), Box(hB), X_WA, X_WA * fromParts(R, t), 0.05 * std::min(hA.minCoeff(), hB.minCoeff()), false,
              "edge-edge"};
}

/// A corner of B pointing into A's top face, ±2 % deep.
Case vertexInFace(Sampler& s, double scale, const Vec& hA, const Vec& hB) {
  const Vec down = -Vec::UnitZ();
  const Vec corner = (-hB).normalized();  // in the normal cone of B's corner −hB
  const Eigen::Matrix3d align = Eigen::Quaterniond::FromTwoVectors(corner, down).toRotationMatrix();
  const Eigen::Matrix3d R =
      Eigen::AngleAxisd(s.uniform(-kPi, kPi), Vec::UnitZ()).toRotationMatrix() * align *
      Eigen::AngleAxisd(s.uniform(-0.2, 0.2), corner).toRotationMatrix();
  const double depth = s.uniform(-0.02, 0.02) * std::min(hA.minCoeff(), hB.minCoeff());
  const Vec at(s.uniform(-0.8, 0.8) * hA.x(), s.uniform(-0.8, 0.8) * hA.y(), hA.z() - depth);
  const Vec t = at - R * (-hB);
  const Iso X_WA = s.pose(2 * scale);
  return Case{Box(hA), Box(hB), X_WA, X_WA * fromParts(R, t), 0.05 * std::min(hA.minCoeff(), hB.minCoeff()), false,
              "vertex in face"};
}

/// Arbitrary relative pose, B slid along a random direction to a random signed distance within ±the margin.
Case anyPose(Sampler& s, double scale, const Vec& hA, const Vec& hB) {
  const Iso X_WA = s.pose(2 * scale);
  Iso X_WB = X_WA * s.pose(0);
  const Vec dir = s.unitVector();
  const double margin = 0.1 * std::min(hA.minCoeff(), hB.minCoeff()) + 0.05 * std::max(hA.maxCoeff(), hB.maxCoeff());
  const double target = s.uniform(-1, 1.2) * margin;
  // Bisection on the slide: distance(t) is increasing along a fixed direction once the boxes are apart.
  auto at = [&](double t) {
    Iso X = X_WB;
    X.translation() = X_WA.translation() + t * dir;
    return X;
  };
  unidist::DistanceOptions exact;
  exact.tolerance = 0;
  double lo = 0, hi = 4 * (hA.norm() + hB.norm()) + margin;
  for (int i = 0; i < 60; ++i) {
    const double mid = 0.5 * (lo + hi);
    (unidist::distance(Box(hA), X_WA, Box(hB), at(mid), exact).distance < target ? lo : hi) = mid;
  }
  return Case{Box(hA), Box(hB), X_WA, at(lo), margin, false, "any pose"};
}

Case coincident(Sampler& s, double scale, const Vec& hA) {
  const Iso X = s.pose(2 * scale);
  return Case{Box(hA), Box(hA), X, X, 0.01 * hA.minCoeff(), false, "coincident"};
}

double exactDistance(const Case& c) {
  unidist::DistanceOptions o;
  o.tolerance = 0;
  return unidist::distance(c.a, c.X_WA, c.b, c.X_WB, o).distance;
}

double surfaceDistance(const Box& box, const Iso& X_WM, const Vec& p_W) {
  return std::abs(box.closestPoint(X_WM.inverse() * p_W).signedDistance);
}

// ---- 2D helpers for the overlap check (in A's top-face coordinates) ------------------------------------------

double cross2(const Vec2& o, const Vec2& a, const Vec2& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

/// Convex hull, counter-clockwise (Andrew's monotone chain).
std::vector<Vec2> hull(std::vector<Vec2> p) {
  std::sort(p.begin(), p.end(), [](const Vec2& x, const Vec2& y) { return x.x() < y.x() || (x.x() == y.x() && x.y() < y.y()); });
  if (p.size() < 3) return p;
  std::vector<Vec2> h(2 * p.size());
  std::size_t k = 0;
  for (std::size_t i = 0; i < p.size(); ++i) {
    while (k >= 2 && cross2(h[k - 2], h[k - 1], p[i]) <= 0) --k;
    h[k++] = p[i];
  }
  for (std::size_t i = p.size() - 1, t = k + 1; i > 0; --i) {
    while (k >= t && cross2(h[k - 2], h[k - 1], p[i - 1]) <= 0) --k;
    h[k++] = p[i - 1];
  }
  h.resize(k - 1);
  return h;
}

/// Signed distance of q outside a counter-clockwise convex polygon's edges (the largest over the edges).
double outsideBy(const std::vector<Vec2>& poly, const Vec2& q) {
  double worst = -kInf;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Vec2 a = poly[i], b = poly[(i + 1) % poly.size()];
    const Vec2 e = (b - a).normalized();
    worst = std::max(worst, -(e.x() * (q.y() - a.y()) - e.y() * (q.x() - a.x())));
  }
  return worst;
}

/// (c): every point of the true overlap of A's top face and B's bottom face seen from above lies in the hull of
/// the contacts' points (projected likewise), up to slack.
void expectHullCoversOverlap(const Case& c, const std::vector<Contact>& cs) {
  const Vec hA = c.a.halfExtents(), hB = c.b.halfExtents();
  const Iso X_AW = c.X_WA.inverse(), X_AB = X_AW * c.X_WB;
  std::vector<Vec2> bottomB;  // B's bottom face in A's frame, seen along A's z (counter-clockwise)
  for (const auto& sgn : {Vec2(1, 1), Vec2(-1, 1), Vec2(-1, -1), Vec2(1, -1)})
    bottomB.push_back((X_AB * Vec(sgn.x() * hB.x(), sgn.y() * hB.y(), -hB.z())).head<2>());
  bottomB = hull(bottomB);
  std::vector<Vec2> points;
  for (const Contact& k : cs) points.push_back((X_AW * k.pointA).head<2>());
  const std::vector<Vec2> h = hull(points);
  const double slack = 1e-7 * sizeOf(c);
  constexpr int kGrid = 60;
  int inOverlap = 0;
  for (int i = 0; i <= kGrid; ++i)
    for (int j = 0; j <= kGrid; ++j) {
      const Vec2 q(hA.x() * (2.0 * i / kGrid - 1), hA.y() * (2.0 * j / kGrid - 1));
      if (outsideBy(bottomB, q) > -slack) continue;  // not clearly inside both faces (A's holds every grid point)
      ++inOverlap;
      ASSERT_GE(h.size(), 3u) << c.label << ": " << cs.size() << " contacts for an area";
      EXPECT_LE(outsideBy(h, q), slack) << c.label << ": overlap point " << q.transpose() << " outside the hull";
    }
  EXPECT_GT(inOverlap, 0) << c.label << ": the faces were meant to overlap";
}

/// (a), (b), (d) for one case; (c) for face-on-face ones. Returns the exact distance (for coverage counts).
double checkCase(const Case& c) {
  const double size = sizeOf(c), tol = 1e-9 * size;
  const std::vector<Contact> cs = unidist::contact::boxBoxContacts(c.a, c.X_WA, c.b, c.X_WB, c.margin, 1e-12 * size, 0);
  const double exact = exactDistance(c);
  SCOPED_TRACE(c.label + " size " + sci(size) + " exact " + sci(exact) + " margin " + sci(c.margin));
  if (exact > c.margin + tol) {
    EXPECT_TRUE(cs.empty());
    return exact;
  }
  if (exact <= c.margin - tol) {
    EXPECT_FALSE(cs.empty());
  }
  if (cs.empty()) return exact;
  EXPECT_NEAR(cs.front().distance, exact, tol);  // (a) the deepest first, exact
  for (const Contact& k : cs) {
    EXPECT_LE(k.distance, c.margin);
    EXPECT_GE(k.distance, exact - tol);  // (d)
    EXPECT_GE(k.distance, cs.front().distance);
    EXPECT_NEAR(k.normal.norm(), 1.0, 1e-12);
    EXPECT_LE(surfaceDistance(c.a, c.X_WA, k.pointA), tol);  // (b)
    EXPECT_LE(surfaceDistance(c.b, c.X_WB, k.pointB), tol);
    EXPECT_LE((k.pointB - k.pointA - k.distance * k.normal).norm(), tol);
  }
  if (c.faceOnFace) expectHullCoversOverlap(c, cs);
  return exact;
}

/// Half extents for a scale and a shape family: chunky, or very thin (a plate or a needle).
Vec halfExtentsFor(Sampler& s, double scale, int family) {
  Vec h = scale * s.halfExtents(0.2, 1.0);
  if (family == 1) h.z() = scale * s.uniform(1e-4, 1e-3);                      // plate
  if (family == 2) h.y() = scale * s.uniform(1e-3, 1e-2), h.z() = h.y();       // needle
  return h;
}

constexpr double kScales[] = {1e-4, 1.0, 1e4};

TEST(BoxBoxContacts, FaceOnFaceRestingWithTinyTilts) {
  Sampler s(11);
  for (double scale : kScales)
    for (int i = 0; i < cases(100); ++i) {
      const Vec hA = halfExtentsFor(s, scale, i % 2), hB = halfExtentsFor(s, scale, (i / 2) % 2);
      checkCase(faceOnFace(s, scale, hA, hB));
    }
}

TEST(BoxBoxContacts, FaceOnFaceGivesThePolygonCornersWithTheirOwnDepths) {
  // A unit cube tilted by 1e-3 about x on a wide slab, sunk 1e-3 at its lowest edge: four corners, two at −1e-3,
  // two at −1e-3 + 1e-3·sin(tilt)·2·0.5 higher, all with the slab's normal.
  const Box slab(Vec(2, 2, 0.5)), cube(Vec(0.5, 0.5, 0.5));
  const double tilt = 1e-3;
  const Eigen::Matrix3d R = Eigen::AngleAxisd(tilt, Vec::UnitX()).toRotationMatrix();
  const Vec lowest = R * Vec(0, -0.5, -0.5);  // the low edge's middle
  const Iso X_WB = fromParts(R, Vec(0, 0, 0.5 - 1e-3) - lowest);
  const auto cs = unidist::contact::boxBoxContacts(slab, Iso::Identity(), cube, X_WB, 0.01, 1e-12, 0);
  ASSERT_EQ(cs.size(), 4u);
  EXPECT_NEAR(cs[0].distance, -1e-3, 1e-12);
  EXPECT_NEAR(cs[1].distance, -1e-3, 1e-12);
  EXPECT_NEAR(cs[2].distance, -1e-3 + std::sin(tilt), 1e-12);
  EXPECT_NEAR(cs[3].distance, -1e-3 + std::sin(tilt), 1e-12);
  for (const Contact& c : cs) EXPECT_LE((c.normal - Vec::UnitZ()).norm(), 1e-12);
}

TEST(BoxBoxContacts, EdgeEdgeCrossingsGiveOneExactPair) {
  Sampler s(12);
  for (double scale : kScales)
    for (int i = 0; i < cases(100); ++i) {
      const Case c = edgeEdge(s, scale, halfExtentsFor(s, scale, 0), halfExtentsFor(s, scale, 0));
      checkCase(c);
      const auto cs = unidist::contact::boxBoxContacts(c.a, c.X_WA, c.b, c.X_WB, c.margin, 0, 0);
      ASSERT_FALSE(cs.empty());
      EXPECT_EQ(cs.size(), 1u) << "an edge crossing is one point";
    }
}

TEST(BoxBoxContacts, VertexInFace) {
  Sampler s(13);
  for (double scale : kScales)
    for (int i = 0; i < cases(100); ++i)
      checkCase(vertexInFace(s, scale, halfExtentsFor(s, scale, i % 3 == 1 ? 1 : 0), halfExtentsFor(s, scale, 0)));
}

TEST(BoxBoxContacts, AnyPoseWithinOrJustBeyondTheMargin) {
  Sampler s(14);
  int overlapping = 0, apartWithin = 0, beyond = 0;
  for (double scale : kScales)
    for (int i = 0; i < cases(150); ++i) {
      const Case c = anyPose(s, scale, halfExtentsFor(s, scale, i % 3), halfExtentsFor(s, scale, (i / 3) % 3));
      const double exact = checkCase(c);
      (exact < 0 ? overlapping : exact <= c.margin ? apartWithin : beyond) += 1;
    }
  // Every regime is exercised.
  EXPECT_GT(overlapping, cases(150));
  EXPECT_GT(apartWithin, cases(150));
  EXPECT_GT(beyond, cases(150) / 10);
}

TEST(BoxBoxContacts, IdenticalCoincidentBoxes) {
  Sampler s(15);
  for (double scale : kScales)
    for (int i = 0; i < cases(30); ++i) {
      const Case c = coincident(s, scale, halfExtentsFor(s, scale, i % 3));
      checkCase(c);
      const auto cs = unidist::contact::boxBoxContacts(c.a, c.X_WA, c.b, c.X_WB, c.margin, 0, 0);
      EXPECT_EQ(cs.size(), 4u) << "a whole face, pushed through the thinnest side";
    }
}

TEST(BoxBoxContacts, FarApartGivesNothing) {
  const Box a(Vec(1, 1, 1));
  const Iso X_WB = fromParts(Eigen::Matrix3d::Identity(), Vec(2.5, 0.3, 0));
  EXPECT_TRUE(unidist::contact::boxBoxContacts(a, Iso::Identity(), a, X_WB, 0.4, 0, 0).empty());
  EXPECT_EQ(unidist::contact::boxBoxContacts(a, Iso::Identity(), a, X_WB, 0.5, 0, 0).size(), 4u);
}

TEST(BoxBoxContacts, ReducedToMaxContactsKeepingTheDeepestAndTheSpread) {
  // An octagon: a square on a square turned 45°; six of the eight corners are kept, the deepest among them.
  const Box a(Vec(1, 1, 0.5)), b(Vec(1, 1, 0.5));
  const Eigen::Matrix3d R = Eigen::AngleAxisd(kPi / 4, Vec::UnitZ()).toRotationMatrix() *
                            Eigen::AngleAxisd(1e-4, Vec::UnitX()).toRotationMatrix();
  const Iso X_WB = fromParts(R, Vec(0, 0, 1 - 1e-3));
  const auto all = unidist::contact::boxBoxContacts(a, Iso::Identity(), b, X_WB, 0.01, 0, 0);
  ASSERT_EQ(all.size(), 8u);
  const auto four = unidist::contact::boxBoxContacts(a, Iso::Identity(), b, X_WB, 0.01, 0, 4);
  ASSERT_EQ(four.size(), 4u);
  EXPECT_EQ(four.front().distance, all.front().distance);
  double spread = kInf;
  for (std::size_t i = 0; i < four.size(); ++i)
    for (std::size_t j = i + 1; j < four.size(); ++j) spread = std::min(spread, (four[i].pointA - four[j].pointA).norm());
  EXPECT_GT(spread, 0.5) << "the four kept corners are spread over the octagon";
}

TEST(BoxBoxContacts, ManifoldContactsUsesTheRoutineInBothOrders) {
  Sampler s(16);
  for (int i = 0; i < cases(60); ++i) {
    const Case c = i % 2 ? faceOnFace(s, 1, halfExtentsFor(s, 1, 0), halfExtentsFor(s, 1, 0))
                         : anyPose(s, 1, halfExtentsFor(s, 1, 0), halfExtentsFor(s, 1, 0));
    unidist::ManifoldOptions o;
    o.margin = c.margin;
    o.maxContacts = 8;
    o.tolerance = 1e-12;
    const auto direct = unidist::contact::boxBoxContacts(c.a, c.X_WA, c.b, c.X_WB, c.margin, 1e-12, 8);
    const auto ab = unidist::manifoldContacts(c.a, c.X_WA, c.b, c.X_WB, o);
    const auto ba = unidist::manifoldContacts(c.b, c.X_WB, c.a, c.X_WA, o);
    ASSERT_EQ(ab.size(), direct.size()) << c.label;
    ASSERT_EQ(ba.empty(), direct.empty()) << c.label;
    for (std::size_t k = 0; k < ab.size(); ++k) {
      EXPECT_NEAR(ab[k].distance, direct[k].distance, 1e-12);
      EXPECT_LE((ab[k].pointA - direct[k].pointA).norm(), 1e-9);
    }
    if (!ab.empty()) {
      EXPECT_NEAR(ba.front().distance, ab.front().distance, 1e-9);
      for (const Contact& k : ba) {  // the roles exchanged: A's points on B now
        EXPECT_LE(surfaceDistance(c.b, c.X_WB, k.pointA), 1e-9);
        EXPECT_LE(surfaceDistance(c.a, c.X_WA, k.pointB), 1e-9);
        EXPECT_LE((k.pointB - k.pointA - k.distance * k.normal).norm(), 1e-9);
      }
    }
  }
}

}  // namespace
