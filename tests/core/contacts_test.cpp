// Contact points (unidist/contacts.h): mesh–mesh local minima against the brute-force oracle of
// core/contact_oracle.h at random poses (every minimum within the margin found, nothing else reported), and
// analytic cases with known contacts: a box resting on a box (the four corners), two parallel tessellated
// cylinders (the ends of the touching generator lines), a sphere mesh over a plane (its lowest vertex),
// penetrating pairs (negative distance, the normal B must move along), the scales 1e-4 and 1e4, flat contacts
// (corners only), the reduction to maxContacts, cloud points tied with the nearest, and bad options.
#include "core/contact_oracle.h"
#include "core/mesh_fixtures.h"
#include "unidist/contacts.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

namespace {

using meshfix::Soup;
using meshfix::Vec;
using unidist::Contact;
using unidist::ContactOptions;
using Iso = Eigen::Isometry3d;

Iso pose(const Vec& t, const Eigen::Quaterniond& q = Eigen::Quaterniond::Identity()) {
  Iso X = Iso::Identity();
  X.linear() = q.normalized().toRotationMatrix();
  X.translation() = t;
  return X;
}

Soup posed(Soup s, const Iso& X) {
  for (Vec& v : s.vertices) v = X * v;
  return s;
}

/// The contract's invariants on every contact: unit normal, pointB − pointA = distance · normal.
void expectConsistent(const std::vector<Contact>& cs, double size) {
  for (const Contact& c : cs) {
    EXPECT_NEAR(c.normal.norm(), 1.0, 1e-12);
    EXPECT_LE((c.pointB - c.pointA - c.distance * c.normal).norm(), 1e-8 * size);
  }
}

/// Whether some contact has these points (within eps).
bool hasContact(const std::vector<Contact>& cs, const Vec& pA, const Vec& pB, double eps) {
  for (const Contact& c : cs)
    if ((c.pointA - pA).norm() <= eps && (c.pointB - pB).norm() <= eps) return true;
  return false;
}

void compareWithOracle(const Soup& sa, const Iso& XA, const Soup& sb, const Iso& XB, double margin, int& total) {
  const unidist::TriangleMesh a = meshfix::makeMesh(sa), b = meshfix::makeMesh(sb);
  ContactOptions o;
  o.margin = margin;
  const std::vector<Contact> got = unidist::contacts(a, XA, b, XB, o);
  const double size = 4;
  const contactoracle::Oracle oracle(posed(sa, XA), posed(sb, XB), a.isSolid(), b.isSolid(), size);
  const std::vector<contactoracle::Minimum> truth = oracle.minima(margin + 1e-6);
  expectConsistent(got, size);
  for (const auto& m : truth) {
    if (m.distance > margin - 1e-6) continue;  // too close to the cut-off to insist either way
    EXPECT_TRUE(hasContact(got, m.pA, m.pB, 1e-7 * size))
        << "missed minimum at distance " << m.distance << " pA " << m.pA.transpose() << " pB " << m.pB.transpose();
  }
  for (const Contact& c : got) {
    EXPECT_LE(c.distance, margin + 1e-8);
    bool matched = false;
    for (const auto& m : truth)
      matched = matched || ((c.pointA - m.pA).norm() <= 1e-7 * size && (c.pointB - m.pB).norm() <= 1e-7 * size);
    EXPECT_TRUE(matched) << "spurious contact at distance " << c.distance << " pA " << c.pointA.transpose();
  }
  total += static_cast<int>(truth.size());
}

TEST(Contacts, MeshMeshMatchesBruteForceAtRandomPoses) {
  std::mt19937_64 rng(2024);
  std::uniform_real_distribution<double> u(-1, 1);
  const Soup shapes[] = {meshfix::icosphere(1.0, 1), meshfix::torus(1.0, 0.35, 12, 8), meshfix::wavySheet(6)};
  int total = 0;
  for (int trial = 0; trial < 24; ++trial) {
    const Soup& sa = shapes[trial % 3];
    const Soup& sb = shapes[(trial / 3) % 3];
    const Eigen::Quaterniond qa(u(rng), u(rng), u(rng), u(rng)), qb(u(rng), u(rng), u(rng), u(rng));
    const Iso XA = pose(Vec(u(rng), u(rng), u(rng)) * 0.2, qa);
    const Vec dir = Vec(u(rng), u(rng), u(rng)).normalized();
    // Start B along dir, then slide it until the global distance is a random gap well inside the margin.
    Iso XB = pose(XA.translation() + 2.6 * dir, qb);
    const unidist::TriangleMesh ma = meshfix::makeMesh(sa), mb = meshfix::makeMesh(sb);
    const double target = 0.05 + 0.2 * (u(rng) + 1) / 2;
    for (int step = 0; step < 8; ++step)
      XB.translation() += (target - unidist::distance(ma, XA, mb, XB).distance) * dir;
    ASSERT_GT(unidist::distance(ma, XA, mb, XB).distance, 0.02);
    SCOPED_TRACE(trial);
    compareWithOracle(sa, XA, sb, XB, 0.45, total);
  }
  EXPECT_GT(total, 24);  // the cases do have minima within the margin
}

TEST(Contacts, BoxRestingOnBoxGivesFourCorners) {
  const unidist::Box big(Vec(1, 1, 1)), small(Vec(0.5, 0.5, 0.5));
  const Eigen::Quaterniond turn(Eigen::AngleAxisd(0.4, Vec::UnitZ()));
  for (double gap : {0.0, 1e-3}) {
    const Iso XB = pose(Vec(0.2, -0.1, 1.5 + gap), turn);
    ContactOptions o;
    o.margin = gap > 0 ? 0.01 : 0.0;
    const std::vector<Contact> cs = unidist::contacts(big, Iso::Identity(), small, XB, o);
    ASSERT_EQ(cs.size(), 4u) << "gap " << gap;
    expectConsistent(cs, 3);
    for (const Contact& c : cs) {
      EXPECT_NEAR(c.distance, gap, 1e-12);
      EXPECT_NEAR(c.normal.z(), 1.0, 1e-9);
      const Vec local = XB.inverse() * c.pointB;  // a bottom corner of the small box
      EXPECT_NEAR(std::abs(local.x()), 0.5, 1e-12);
      EXPECT_NEAR(std::abs(local.y()), 0.5, 1e-12);
      EXPECT_NEAR(local.z(), -0.5, 1e-12);
    }
  }
}

TEST(Contacts, BoxSunkIntoBoxGivesFourCornersWithDepth) {
  const unidist::Box big(Vec(1, 1, 1)), small(Vec(0.5, 0.5, 0.5));
  const Iso XB = pose(Vec(0.1, 0.2, 1.5 - 1e-3), Eigen::Quaterniond(Eigen::AngleAxisd(0.3, Vec::UnitZ())));
  const std::vector<Contact> cs = unidist::contacts(big, Iso::Identity(), small, XB);
  ASSERT_EQ(cs.size(), 4u);
  expectConsistent(cs, 3);
  for (const Contact& c : cs) {
    EXPECT_NEAR(c.distance, -1e-3, 1e-12);
    EXPECT_NEAR(c.normal.z(), 1.0, 1e-9);  // B (the small box) must move up
    EXPECT_NEAR(c.pointA.z(), 1.0, 1e-12);
  }
}

TEST(Contacts, BoxOnPlaneGivesFourCorners) {
  const unidist::Box box(Vec(0.3, 0.2, 0.1));
  const unidist::Plane floor(Vec(0, 0, 1), 0);
  const std::vector<Contact> cs = unidist::contacts(box, pose(Vec(1, 2, 0.1)), floor, Iso::Identity());
  ASSERT_EQ(cs.size(), 4u);
  expectConsistent(cs, 1);
  for (const Contact& c : cs) {
    EXPECT_NEAR(c.distance, 0, 1e-12);
    EXPECT_NEAR(c.normal.z(), -1.0, 1e-9);  // from the box toward the floor
    EXPECT_NEAR(std::abs(c.pointA.x() - 1), 0.3, 1e-12);
  }
}

/// Closed cylinder along x: n sides (a vertex line at angle 0, i.e. at +y), radius r, half-length h.
Soup cylinder(int n, double r, double h) {
  Soup s;
  for (int end = 0; end < 2; ++end)
    for (int k = 0; k < n; ++k) {
      const double t = 2 * M_PI * k / n;
      s.vertices.emplace_back(end ? h : -h, r * std::cos(t), r * std::sin(t));
    }
  s.vertices.emplace_back(-h, 0, 0);
  s.vertices.emplace_back(h, 0, 0);
  const auto N = static_cast<std::uint32_t>(n);
  for (std::uint32_t k = 0; k < N; ++k) {
    const std::uint32_t k1 = (k + 1) % N;
    s.triangles.push_back({k, k1, N + k1});
    s.triangles.push_back({k, N + k1, N + k});
    s.triangles.push_back({2 * N, k1, k});
    s.triangles.push_back({2 * N + 1, N + k, N + k1});
  }
  return s;
}

TEST(Contacts, ParallelCylindersTouchAtTheEndsOfTheirLines) {
  const Soup cyl = cylinder(16, 0.5, 1.0);
  const unidist::TriangleMesh a = meshfix::makeMesh(cyl), b = meshfix::makeMesh(cyl);
  ASSERT_TRUE(a.isSolid());
  const double gap = 0.01;
  ContactOptions o;
  o.margin = 2 * gap;
  for (double shift : {0.0, 0.5}) {
    const Iso XB = pose(Vec(shift, 1.0 + gap, 0));
    const std::vector<Contact> cs = unidist::contacts(a, Iso::Identity(), b, XB, o);
    ASSERT_EQ(cs.size(), 2u) << "shift " << shift;
    expectConsistent(cs, 4);
    EXPECT_TRUE(hasContact(cs, Vec(-1 + shift, 0.5, 0), Vec(-1 + shift, 0.5 + gap, 0), 1e-12));
    EXPECT_TRUE(hasContact(cs, Vec(1, 0.5, 0), Vec(1, 0.5 + gap, 0), 1e-12));
    for (const Contact& c : cs) EXPECT_NEAR(c.normal.y(), 1.0, 1e-12);
  }
}

/// An icosphere turned so that one vertex is its single lowest point.
Soup sphereWithLowestVertex() {
  Soup s = meshfix::icosphere(1.0, 2);
  const Eigen::Quaterniond q = Eigen::Quaterniond::FromTwoVectors(s.vertices[0].normalized(), -Vec::UnitZ());
  for (Vec& v : s.vertices) v = q * v;
  return s;
}

TEST(Contacts, SphereMeshOverPlaneGivesItsLowestVertex) {
  const unidist::TriangleMesh ball = meshfix::makeMesh(sphereWithLowestVertex());
  const unidist::Plane floor(Vec(0, 0, 1), 0);
  for (double height : {1.05, 0.99}) {
    ContactOptions o;
    o.margin = 0.1;
    const std::vector<Contact> cs = unidist::contacts(ball, pose(Vec(0.3, 0.4, height)), floor, Iso::Identity(), o);
    ASSERT_EQ(cs.size(), 1u);
    expectConsistent(cs, 2);
    EXPECT_NEAR(cs[0].distance, height - 1, 1e-12);
    EXPECT_NEAR(cs[0].normal.z(), -1, 1e-12);  // toward the floor, or (penetrating) the way the floor moves away
    EXPECT_LE((cs[0].pointA - Vec(0.3, 0.4, height - 1)).norm(), 1e-12);
  }
}

TEST(Contacts, SphereMeshSunkIntoBoxMeshGivesDeepestVertex) {
  const unidist::TriangleMesh ball = meshfix::makeMesh(sphereWithLowestVertex());
  const unidist::TriangleMesh block = meshfix::makeMesh(meshfix::gridBox(Vec(2, 2, 1), 3));
  const std::vector<Contact> cs = unidist::contacts(ball, pose(Vec(0.1, 0.2, 1.98)), block, Iso::Identity());
  ASSERT_EQ(cs.size(), 1u);
  expectConsistent(cs, 4);
  EXPECT_NEAR(cs[0].distance, -0.02, 1e-12);
  EXPECT_NEAR(cs[0].normal.z(), -1, 1e-12);  // the block must move down
  // Reversed roles: the normal flips, the points swap.
  const std::vector<Contact> rs = unidist::contacts(block, Iso::Identity(), ball, pose(Vec(0.1, 0.2, 1.98)));
  ASSERT_EQ(rs.size(), 1u);
  EXPECT_NEAR(rs[0].distance, -0.02, 1e-12);
  EXPECT_NEAR(rs[0].normal.z(), 1, 1e-12);
  EXPECT_LE((rs[0].pointA - cs[0].pointB).norm(), 1e-12);
}

TEST(Contacts, ContainedMeshGivesTheGlobalDepth) {
  // Surfaces far apart, one solid inside the other: the global penetration. A unit cube at x in [0, 1] inside
  // the box [-2, 2]³ leaves it soonest along +x, by 2 (−x: 3, ±y, ±z: 2.5).
  const unidist::TriangleMesh inner = meshfix::makeMesh(meshfix::gridBox(Vec(0.5, 0.5, 0.5), 1));
  const unidist::TriangleMesh outer = meshfix::makeMesh(meshfix::gridBox(Vec(2, 2, 2), 2));
  const std::vector<Contact> cs = unidist::contacts(outer, Iso::Identity(), inner, pose(Vec(0.5, 0, 0)));
  ASSERT_EQ(cs.size(), 1u);
  expectConsistent(cs, 8);
  EXPECT_NEAR(cs[0].distance, -2, 1e-9);
  EXPECT_NEAR(cs[0].normal.x(), 1, 1e-9);
}

TEST(Contacts, ScaleInvariant) {
  for (double k : {1e-4, 1.0, 1e4}) {
    const unidist::Box big(Vec(k, k, k)), small(Vec(0.5 * k, 0.5 * k, 0.5 * k));
    const Iso XB =
        pose(Vec(0.2 * k, 0.1 * k, 1.5 * k + 1e-3 * k), Eigen::Quaterniond(Eigen::AngleAxisd(0.7, Vec::UnitZ())));
    ContactOptions o;
    o.margin = 0.01 * k;
    const std::vector<Contact> cs = unidist::contacts(big, Iso::Identity(), small, XB, o);
    ASSERT_EQ(cs.size(), 4u) << "scale " << k;
    expectConsistent(cs, 3 * k);
    for (const Contact& c : cs) EXPECT_NEAR(c.distance, 1e-3 * k, 1e-12 * k);
    const unidist::TriangleMesh ball = meshfix::makeMesh(meshfix::scaled(sphereWithLowestVertex(), k));
    const std::vector<Contact> sp =
        unidist::contacts(ball, pose(Vec(0, 0, 0.98 * k)), unidist::Plane(Vec(0, 0, 1), 0), Iso::Identity());
    ASSERT_EQ(sp.size(), 1u) << "scale " << k;
    EXPECT_NEAR(sp[0].distance, -0.02 * k, 1e-12 * k);
  }
}

TEST(Contacts, FlatContactKeepsOnlyTheCorners) {
  // A plate tessellated 4 × 4 on a box: the contact polygon's corners, not its inner or side vertices.
  const unidist::TriangleMesh plate = meshfix::makeMesh(meshfix::gridBox(Vec(0.5, 0.5, 0.1), 4));
  const std::vector<Contact> cs =
      unidist::contacts(plate, pose(Vec(0, 0, 1.1)), unidist::Box(Vec(2, 2, 1)), Iso::Identity());
  ASSERT_EQ(cs.size(), 4u);
  for (const Contact& c : cs) {
    EXPECT_NEAR(c.pointA.z(), 1.0, 1e-12);
    EXPECT_NEAR(std::abs(c.pointA.x()), 0.5, 1e-12);
    EXPECT_NEAR(std::abs(c.pointA.y()), 0.5, 1e-12);
  }
}

TEST(Contacts, ReductionSpreadsOverTheContactRegion) {
  // A 16-sided cylinder standing on its cap on a plane: every rim vertex; reduced to 4, four spread ones.
  const unidist::TriangleMesh cyl = meshfix::makeMesh(cylinder(16, 0.5, 1.0));
  const unidist::Plane floor(Vec(1, 0, 0), -1);  // the solid x <= -1
  const std::vector<Contact> all = unidist::contacts(cyl, Iso::Identity(), floor, Iso::Identity());
  ASSERT_EQ(all.size(), 16u);
  for (const Contact& c : all) EXPECT_NEAR(Eigen::Vector2d(c.pointA.y(), c.pointA.z()).norm(), 0.5, 1e-12);
  ContactOptions o;
  o.maxContacts = 4;
  const std::vector<Contact> four = unidist::contacts(cyl, Iso::Identity(), floor, Iso::Identity(), o);
  ASSERT_EQ(four.size(), 4u);
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j)
      EXPECT_GE((four[i].pointA - four[j].pointA).norm(), 0.5 * std::sqrt(2.0) - 1e-9);
}

TEST(Contacts, OtherFamiliesGiveTheGlobalMinimum) {
  const unidist::Sphere s(1.0);
  const unidist::Capsule cap(0.5, 1.0);
  ContactOptions o;
  o.margin = 0.5;
  const std::vector<Contact> cs = unidist::contacts(s, Iso::Identity(), cap, pose(Vec(1.8, 0, 0)), o);
  ASSERT_EQ(cs.size(), 1u);
  EXPECT_NEAR(cs[0].distance, 0.3, 1e-9);
  EXPECT_NEAR(cs[0].normal.x(), 1, 1e-9);
  o.margin = 0.2;
  EXPECT_TRUE(unidist::contacts(s, Iso::Identity(), cap, pose(Vec(1.8, 0, 0)), o).empty());
  // A cloud against a solid: the nearest point of each nearby hierarchy leaf.
  const unidist::PointCloud cloud({Vec(0, 0, 1.05), Vec(3, 0, 1.05), Vec(0, 0, 9)});
  o.margin = 0.1;
  const std::vector<Contact> cc =
      unidist::contacts(cloud, Iso::Identity(), unidist::Box(Vec(5, 5, 1)), Iso::Identity(), o);
  ASSERT_GE(cc.size(), 1u);
  for (const Contact& c : cc) EXPECT_NEAR(c.distance, 0.05, 1e-12);
}

TEST(Contacts, CloudPointsAsNearAsTheNearestAreAllKept) {
  // The long-run stack's cloud slab (tests/longrun/slab.xyz: the face lattice of a 360 x 360 x 60 slab, 60 apart
  // across, 30 through) with a ball cradled between four lattice points of its top face: all four are contacts,
  // at one distance. Keeping one point per hierarchy leaf gave two of them, on a diagonal, which the ball rocked
  // about in Bullet (docs/reliability.md, "Long runs").
  std::vector<Vec> points;
  for (int x = -180; x <= 180; x += 60)
    for (int y = -180; y <= 180; y += 60)
      for (int z = -30; z <= 30; z += 30)
        if (z != 0 || std::abs(x) == 180 || std::abs(y) == 180) points.push_back(Vec(x, y, z));
  ASSERT_EQ(points.size(), 122u);
  const unidist::PointCloud cloud(points);
  const unidist::Sphere ball(150.0);
  const double rest = 30 + std::sqrt(150.0 * 150.0 - 2 * 30.0 * 30.0);  // centre height touching the four
  ContactOptions o;
  o.margin = 1.0;
  for (const Vec& offset : {Vec(0, 0, 0.05), Vec(0, 0, -0.02), Vec(1e-7, -3e-8, 0.05), Vec(-2e-9, 5e-9, -0.02)}) {
    const Vec centre = Vec(30, 30, rest) + offset;
    std::vector<Contact> cs = unidist::contacts(cloud, Iso::Identity(), ball, pose(centre), o);
    ASSERT_EQ(cs.size(), 4u) << "ball at " << centre.transpose();
    std::sort(cs.begin(), cs.end(), [](const Contact& a, const Contact& b) {
      return a.pointA.x() + 1e3 * a.pointA.y() < b.pointA.x() + 1e3 * b.pointA.y();
    });
    const Vec expected[4] = {Vec(0, 0, 30), Vec(60, 0, 30), Vec(0, 60, 30), Vec(60, 60, 30)};
    for (int i = 0; i < 4; ++i) {
      EXPECT_EQ(cs[i].pointA, expected[i]);
      EXPECT_NEAR(cs[i].distance, (expected[i] - centre).norm() - 150.0, 1e-9);
      EXPECT_NEAR(cs[i].distance, cs[0].distance, 1e-6);
    }
  }
}

TEST(Contacts, ConcurrentQueriesOnSharedModelsAgree) {
  // The models (and their lazily built hierarchies) are shared; each query keeps its own scratch data.
  const unidist::TriangleMesh a = meshfix::makeMesh(meshfix::torus(1.0, 0.35, 24, 12));
  const unidist::TriangleMesh b = meshfix::makeMesh(meshfix::icosphere(0.5, 2));
  const Iso XB = pose(Vec(1.0, 0.0, 0.86));
  ContactOptions o;
  o.margin = 0.1;
  std::vector<Contact> results[4];
  std::vector<std::thread> threads;
  for (auto& r : results) threads.emplace_back([&] { r = unidist::contacts(a, Iso::Identity(), b, XB, o); });
  for (std::thread& t : threads) t.join();
  ASSERT_FALSE(results[0].empty());
  for (const auto& r : results) {
    ASSERT_EQ(r.size(), results[0].size());
    for (std::size_t i = 0; i < r.size(); ++i) EXPECT_EQ(r[i].pointA, results[0][i].pointA);
  }
}

TEST(Contacts, BadOptionsThrow) {
  const unidist::Sphere s(1.0);
  ContactOptions o;
  o.margin = -1;
  EXPECT_THROW(unidist::contacts(s, Iso::Identity(), s, Iso::Identity(), o), unidist::InputError);
  o.margin = std::nan("");
  EXPECT_THROW(unidist::contacts(s, Iso::Identity(), s, Iso::Identity(), o), unidist::InputError);
  o = {};
  o.maxContacts = -2;
  EXPECT_THROW(unidist::contacts(s, Iso::Identity(), s, Iso::Identity(), o), unidist::InputError);
  const unidist::Plane p(Vec(0, 0, 1), 0);
  EXPECT_THROW(unidist::contacts(p, Iso::Identity(), p, Iso::Identity()), unidist::InputError);
}

}  // namespace
