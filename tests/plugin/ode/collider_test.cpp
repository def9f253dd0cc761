// The unidist collider against ODE's own: dCollide in both argument orders (mirrored normals, equal depths),
// against ODE's sphere–sphere, sphere–box, box–box and sphere–plane colliders on random overlapping poses, the
// caller's maximum and stride, rays (against ODE's own ray–sphere), ODE trimesh and convex geoms, capsules and
// cylinders, heightfields (no contacts, no crash), the AABB, and the per-pair cache's lifetime.
#include "ode_fixture.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/primitives.h"

#include <iostream>
#include <random>

namespace {

using odetest::collide;
using odetest::deepest;
using odetest::OdeTest;
using odetest::Vec;
using Iso = Eigen::Isometry3d;

Vec normalOf(const dContactGeom& c) { return Vec(c.normal[0], c.normal[1], c.normal[2]); }
Vec posOf(const dContactGeom& c) { return Vec(c.pos[0], c.pos[1], c.pos[2]); }

Iso randomPose(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-1, 1);
  Iso X = Iso::Identity();
  X.linear() = Eigen::Quaterniond(Eigen::Vector4d(u(rng), u(rng), u(rng), u(rng)).normalized()).toRotationMatrix();
  X.translation() = spread * Vec(u(rng), u(rng), u(rng));
  return X;
}

/// X_A moved along the pair's normal so that model a at X_A overlaps the geom `other` by about `depth`: the
/// resting-contact regime, where penetration depth has one meaning for every collider.
Iso shallowPose(const unidist::Model& a, Iso X_A, dGeomID other, double depth) {
  const auto b = unidist::modelFromOdeGeom(other);
  const unidist::DistanceResult d = unidist::distance(a, X_A, *b, unidist::odeGeomPose(other));
  X_A.translation() += (d.distance + depth) * d.normal;
  return X_A;
}

dGeomID unidistGeom(std::shared_ptr<const unidist::Model> m, double tol = 1e-10) {
  dGeomID g = unidist::ode::createGeom(nullptr, std::move(m));
  unidist::ode::setTolerance(g, tol);
  return g;
}

TEST_F(OdeTest, ArgumentOrderMirrorsNormalsAndKeepsDepth) {
  std::mt19937_64 rng(11);
  const auto block = std::make_shared<unidist::Box>(Vec(0.5, 0.2, 0.3));
  std::uniform_real_distribution<double> depth(0, 0.05);
  int compared = 0;
  for (int i = 0; i < 100; ++i) {
    // Fresh unidist geoms for each order: no warm start links the two answers.
    dGeomID box = dCreateBox(nullptr, 1.0, 0.6, 0.8);
    odetest::setPose(box, randomPose(rng, 0.3));
    const Iso X = shallowPose(*block, randomPose(rng, 0.8), box, depth(rng));
    dGeomID u1 = unidistGeom(block), u2 = unidistGeom(block);
    odetest::setPose(u1, X);
    odetest::setPose(u2, X);
    const auto ab = collide(u1, box), ba = collide(box, u2);
    ASSERT_EQ(ab.size(), ba.size()) << i;
    for (std::size_t k = 0; k < ab.size(); ++k) {
      EXPECT_EQ(ab[k].g1, u1);
      EXPECT_EQ(ab[k].g2, box);
      EXPECT_EQ(ba[k].g1, box);
      EXPECT_EQ(ba[k].g2, u2);
      EXPECT_EQ(ab[k].depth, ba[k].depth);
      EXPECT_GE(ab[k].depth, 0);
      EXPECT_EQ(posOf(ab[k]), posOf(ba[k]));
      EXPECT_EQ(normalOf(ab[k]), -normalOf(ba[k]));
      EXPECT_NEAR(normalOf(ab[k]).norm(), 1, 1e-12);
      ++compared;
    }
    for (dGeomID g : {u1, u2, box}) dGeomDestroy(g);
  }
  EXPECT_GT(compared, 80);
}

/// Random shallow overlaps of (unidist model, ODE geom) against (ODE twin, the same ODE geom): the deepest
/// contacts agree in depth (1e-6 of the size) and normal.
void compareWithNative(std::shared_ptr<const unidist::Model> model, dGeomID twin, dGeomID other, double spread,
                       bool otherPlaceable, unsigned seed) {
  std::mt19937_64 rng(seed);
  dGeomID u = unidistGeom(std::move(model));
  int compared = 0;
  std::uniform_real_distribution<double> depth(1e-3, 0.05);
  for (int i = 0; i < 200; ++i) {
    if (otherPlaceable) odetest::setPose(other, randomPose(rng, 0.2));
    const Iso X = shallowPose(*unidist::ode::geomModel(u), randomPose(rng, spread), other, depth(rng));
    odetest::setPose(u, X);
    odetest::setPose(twin, X);
    const auto ours = collide(u, other), theirs = collide(twin, other);
    if (theirs.empty()) continue;
    ASSERT_FALSE(ours.empty()) << i;
    const dContactGeom &a = deepest(ours), &b = deepest(theirs);
    EXPECT_NEAR(a.depth, b.depth, 1e-6) << i;
    EXPECT_GT(normalOf(a).dot(normalOf(b)), 1 - 1e-6) << i << " ours " << normalOf(a).transpose() << " ode "
                                                      << normalOf(b).transpose();
    ++compared;
  }
  EXPECT_GT(compared, 50);
  dGeomDestroy(u);
}

TEST_F(OdeTest, MatchesOdeSphereSphere) {
  dGeomID twin = dCreateSphere(nullptr, 0.5), other = dCreateSphere(nullptr, 0.7);
  compareWithNative(std::make_shared<unidist::Sphere>(0.5), twin, other, 0.8, true, 1);
  dGeomDestroy(twin);
  dGeomDestroy(other);
}

TEST_F(OdeTest, MatchesOdeSphereBox) {
  dGeomID twin = dCreateSphere(nullptr, 0.5), other = dCreateBox(nullptr, 1.2, 0.8, 1.0);
  compareWithNative(std::make_shared<unidist::Sphere>(0.5), twin, other, 0.8, true, 2);
  dGeomDestroy(twin);
  dGeomDestroy(other);
}

// ODE's box–box takes a face axis over an edge–edge axis unless the edge axis is 5% shallower (its "fudge
// factor"), and unidist's manifold reports the deepest *vertex* where vertices are inside: the two agree exactly
// where the penetration is along a face normal (a vertex or edge in a face: the usual resting case). Elsewhere
// both must bracket the certified penetration: ours never deeper, ODE's never shallower.
TEST_F(OdeTest, MatchesOdeBoxBox) {
  std::mt19937_64 rng(3);
  const auto block = std::make_shared<unidist::Box>(Vec(0.4, 0.3, 0.5));
  dGeomID u = unidistGeom(block), twin = dCreateBox(nullptr, 0.8, 0.6, 1.0), other = dCreateBox(nullptr, 1.2, 0.8, 1.0);
  std::uniform_real_distribution<double> depth(1e-3, 0.05);
  int faceCases = 0, edgeCases = 0;
  for (int i = 0; i < 200; ++i) {
    odetest::setPose(other, randomPose(rng, 0.2));
    const Iso X = shallowPose(*block, randomPose(rng, 0.9), other, depth(rng));
    odetest::setPose(u, X);
    odetest::setPose(twin, X);
    const auto ours = collide(u, other), theirs = collide(twin, other);
    ASSERT_FALSE(ours.empty()) << i;
    ASSERT_FALSE(theirs.empty()) << i;
    const Iso X_B = unidist::odeGeomPose(other);
    const unidist::DistanceResult truth = unidist::distance(*block, X, *unidist::modelFromOdeGeom(other), X_B);
    double alongFace = 0;
    for (int k = 0; k < 3; ++k)
      alongFace = std::max({alongFace, std::abs(truth.normal.dot(X.linear().col(k))),
                            std::abs(truth.normal.dot(X_B.linear().col(k)))});
    const dContactGeom &a = deepest(ours), &b = deepest(theirs);
    EXPECT_LE(a.depth, -truth.distance + 1e-9) << i;
    EXPECT_GE(b.depth, -truth.distance - 1e-9) << i;
    if (alongFace > 1 - 1e-9) {
      ++faceCases;
      EXPECT_NEAR(a.depth, b.depth, 1e-6) << i;
      EXPECT_GT(normalOf(a).dot(normalOf(b)), 1 - 1e-6) << i;
    } else {
      ++edgeCases;
    }
  }
  EXPECT_GT(faceCases, 100);
  std::cout << "box-box: " << faceCases << " face-normal overlaps matched ODE, " << edgeCases << " edge-edge bracketed\n";
  for (dGeomID g : {u, twin, other}) dGeomDestroy(g);
}

TEST_F(OdeTest, MatchesOdeSpherePlane) {
  dGeomID twin = dCreateSphere(nullptr, 0.5), plane = dCreatePlane(nullptr, 0.3, 0.2, 1, 0.1);
  compareWithNative(std::make_shared<unidist::Sphere>(0.5), twin, plane, 0.6, false, 4);
  dGeomDestroy(twin);
  dGeomDestroy(plane);
}

TEST_F(OdeTest, HonoursMaximumAndStride) {
  // A box resting face-on on a box, slightly sunk: four corner contacts.
  dGeomID top = unidistGeom(std::make_shared<unidist::Box>(Vec(0.5, 0.5, 0.5)));
  dGeomSetPosition(top, 0, 0, 0.999);
  dGeomID floor = dCreateBox(nullptr, 4, 4, 1);
  const auto all = collide(top, floor, 8);
  ASSERT_GE(all.size(), 4u);
  for (const auto& c : all) {
    EXPECT_NEAR(c.depth, 1e-3, 1e-9);
    EXPECT_NEAR((normalOf(c) - Vec(0, 0, 1)).norm(), 0, 1e-9);
  }
  EXPECT_EQ(collide(top, floor, 1).size(), 1u);
  EXPECT_EQ(collide(floor, top, 2).size(), 2u);

  // Stride: contacts in a larger record, padding and the records past the count untouched.
  struct Record {
    dContactGeom geom;
    double guard[3];
  };
  std::vector<Record> records(6);
  for (Record& r : records) r.guard[0] = r.guard[1] = r.guard[2] = 42, r.geom.depth = -7;
  const int n = dCollide(floor, top, 3, &records[0].geom, sizeof(Record));
  ASSERT_EQ(n, 3);
  for (int i = 0; i < 6; ++i) {
    for (double gval : records[static_cast<std::size_t>(i)].guard) EXPECT_EQ(gval, 42);
    if (i < n) {
      EXPECT_NEAR(records[static_cast<std::size_t>(i)].geom.depth, 1e-3, 1e-9);
      EXPECT_NEAR(normalOf(records[static_cast<std::size_t>(i)].geom).z(), -1, 1e-9);  // floor is g1 now
    } else {
      EXPECT_EQ(records[static_cast<std::size_t>(i)].geom.depth, -7);
    }
  }
  // Apart: nothing, and the array is left alone.
  dGeomSetPosition(top, 0, 0, 1.01);
  EXPECT_TRUE(collide(top, floor).empty());
  dGeomDestroy(top);
  dGeomDestroy(floor);
}

TEST_F(OdeTest, RayMatchesOdeRaySphere) {
  std::mt19937_64 rng(5);
  dGeomID u = unidistGeom(std::make_shared<unidist::Sphere>(0.6), 1e-9);
  dGeomID twin = dCreateSphere(nullptr, 0.6);
  dGeomID ray = dCreateRay(nullptr, 5);
  int hits = 0;
  for (int i = 0; i < 200; ++i) {
    const Iso X = randomPose(rng, 0.5);
    odetest::setPose(u, X);
    odetest::setPose(twin, X);
    std::normal_distribution<double> n;
    const Vec start = 2 * Vec(n(rng), n(rng), n(rng)).normalized() * (i % 10 == 0 ? 0.1 : 1.0);
    const Vec dir = (X.translation() + 0.7 * Vec(n(rng), n(rng), n(rng)).normalized() - start).normalized();
    dGeomRaySet(ray, start.x(), start.y(), start.z(), dir.x(), dir.y(), dir.z());
    const auto theirs = collide(ray, twin, 1);
    const auto ours = collide(ray, u, 1);
    if (theirs.size() == 1 && ours.empty()) {  // a grazing ray: allowed only within the tolerance
      const Vec c = X.translation();
      EXPECT_GT((c - start).cross(dir).norm(), 0.6 - 1e-6) << i;
      continue;
    }
    ASSERT_EQ(ours.size(), theirs.size()) << i;
    if (ours.empty()) continue;
    ++hits;
    EXPECT_EQ(ours[0].g1, ray);
    EXPECT_NEAR(ours[0].depth, theirs[0].depth, 1e-7) << i;
    EXPECT_NEAR((posOf(ours[0]) - posOf(theirs[0])).norm(), 0, 1e-7) << i;
    EXPECT_GT(normalOf(ours[0]).dot(normalOf(theirs[0])), 1 - 1e-6) << i;
    const auto reversed = collide(u, ray, 1);
    ASSERT_EQ(reversed.size(), 1u);
    EXPECT_NEAR((normalOf(reversed[0]) + normalOf(ours[0])).norm(), 0, 1e-12);
  }
  EXPECT_GT(hits, 60);
  // Backface culling: from inside the sphere, the exit is not reported.
  odetest::setPose(u, Iso::Identity());
  dGeomRaySet(ray, 0, 0, 0, 1, 0, 0);
  EXPECT_EQ(collide(ray, u, 1).size(), 1u);
  dGeomRaySetBackfaceCull(ray, 1);
  EXPECT_TRUE(collide(ray, u, 1).empty());
  dGeomDestroy(u);
  dGeomDestroy(twin);
  dGeomDestroy(ray);
}

/// A unit cube (two triangles per face) as ODE trimesh data; the arrays must outlive the data.
struct CubeData {
  std::vector<dReal> vertices;
  std::vector<dTriIndex> indices;
  dTriMeshDataID data = nullptr;
  explicit CubeData(double h) {
    for (int i = 0; i < 8; ++i)
      for (int k = 0; k < 3; ++k) vertices.push_back(((i >> k) & 1) ? h : -h);
    const int quads[6][4] = {{0, 2, 3, 1}, {4, 5, 7, 6}, {0, 1, 5, 4}, {2, 6, 7, 3}, {0, 4, 6, 2}, {1, 3, 7, 5}};
    for (const auto& q : quads)
      for (int t : {q[0], q[1], q[2], q[0], q[2], q[3]}) indices.push_back(static_cast<dTriIndex>(t));
    data = dGeomTriMeshDataCreate();
    dGeomTriMeshDataBuildDouble(data, vertices.data(), 3 * sizeof(dReal), 8, indices.data(),
                                static_cast<int>(indices.size()), 3 * sizeof(dTriIndex));
  }
  ~CubeData() { dGeomTriMeshDataDestroy(data); }
};

int messages = 0;
void countMessage(int, const char*, va_list) { ++messages; }

TEST_F(OdeTest, TriMeshPairsWithoutOdeWarnings) {
  messages = 0;
  dSetMessageHandler(&countMessage);
  CubeData cube(0.5);
  dGeomID mesh = dCreateTriMesh(nullptr, cube.data, nullptr, nullptr, nullptr);
  // ODE's cube is a closed solid once converted.
  const auto model = std::dynamic_pointer_cast<const unidist::TriangleMesh>(unidist::modelFromOdeGeom(mesh));
  ASSERT_TRUE(model);
  EXPECT_TRUE(model->isSolid());
  EXPECT_TRUE(model->isConvex());
  EXPECT_EQ(unidist::modelFromOdeGeom(mesh), model);  // converted once per data

  // A unidist sphere sunk 0.01 into the top face.
  dGeomID ball = unidistGeom(std::make_shared<unidist::Sphere>(0.3));
  dGeomSetPosition(ball, 0.1, 0.05, 0.79);
  auto cs = collide(ball, mesh);
  ASSERT_FALSE(cs.empty());
  EXPECT_NEAR(deepest(cs).depth, 0.01, 1e-8);
  EXPECT_NEAR(normalOf(deepest(cs)).z(), 1, 1e-8);
  const int tri = deepest(cs).side2;
  ASSERT_GE(tri, 0);
  dVector3 v0, v1, v2;
  dGeomTriMeshGetTriangle(mesh, tri, &v0, &v1, &v2);
  EXPECT_NEAR(v0[2], 0.5, 1e-12);  // ODE's own index of a top-face triangle
  EXPECT_NEAR(v1[2], 0.5, 1e-12);
  EXPECT_NEAR(v2[2], 0.5, 1e-12);

  // The trimesh pair: a unidist mesh box (half size 0.3, rotated 30° about z) sunk 0.02 into ODE's trimesh cube.
  CubeData small(0.3);
  dGeomID smallMesh = dCreateTriMesh(nullptr, small.data, nullptr, nullptr, nullptr);
  dGeomID block = unidistGeom(unidist::modelFromOdeGeom(smallMesh), 1e-9);
  dGeomDestroy(smallMesh);
  Iso X = Iso::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 6, Vec::UnitZ()).toRotationMatrix();
  X.translation() = Vec(0, 0, 0.78);
  odetest::setPose(block, X);
  cs = collide(block, mesh);
  ASSERT_GE(cs.size(), 3u);
  for (const auto& c : cs) {  // ODE hands out trimesh vertices rounded to float (0.3 → 0.30000001192...)
    EXPECT_NEAR(c.depth, 0.02, 1e-7);
    EXPECT_NEAR(normalOf(c).z(), 1, 1e-8);
  }
  cs = collide(mesh, block);
  ASSERT_GE(cs.size(), 3u);
  EXPECT_NEAR(normalOf(cs[0]).z(), -1, 1e-8);
  EXPECT_EQ(messages, 0);
  dSetMessageHandler(nullptr);
  dGeomDestroy(ball);
  dGeomDestroy(block);
  dGeomDestroy(mesh);
}

TEST_F(OdeTest, ConvexCapsuleAndCylinderGeoms) {
  // ODE convex: a unit cube given by its planes, points and quads.
  static const dReal planes[] = {1, 0, 0, 0.5, -1, 0, 0, 0.5, 0, 1, 0, 0.5, 0, -1, 0, 0.5, 0, 0, 1, 0.5, 0, 0, -1, 0.5};
  static const dReal points[] = {0.5,  0.5,  0.5, -0.5, 0.5,  0.5, -0.5, -0.5, 0.5,  0.5,  -0.5, 0.5,
                                 0.5,  0.5,  -0.5, -0.5, 0.5, -0.5, -0.5, -0.5, -0.5, 0.5, -0.5, -0.5};
  static const unsigned polygons[] = {4, 0, 3, 7, 4, 4, 1, 5, 6, 2, 4, 0, 4, 5, 1, 4, 3, 2, 6, 7, 4, 0, 1, 2, 3, 4, 4, 7, 6, 5};
  dGeomID convex = dCreateConvex(nullptr, planes, 6, points, 8, polygons);
  dGeomSetPosition(convex, 3, 0, 0);
  const auto model = unidist::modelFromOdeGeom(convex);
  EXPECT_TRUE(model->isSolid() && model->isConvex());
  EXPECT_NEAR(model->localBounds().max.z(), 0.5, 1e-15);

  dGeomID ball = unidistGeom(std::make_shared<unidist::Sphere>(0.25));
  dGeomSetPosition(ball, 3.2, 0.1, 0.73);
  auto cs = collide(ball, convex);
  ASSERT_FALSE(cs.empty());
  EXPECT_NEAR(deepest(cs).depth, 0.02, 1e-8);
  EXPECT_NEAR(normalOf(deepest(cs)).z(), 1, 1e-8);

  // Capsule (ODE axis z, length without the caps) and cylinder.
  dGeomID capsule = dCreateCapsule(nullptr, 0.2, 1.0);
  dGeomSetPosition(ball, 0, 0, 0.5 + 0.2 + 0.25 - 0.03);
  cs = collide(ball, capsule);
  ASSERT_FALSE(cs.empty());
  EXPECT_NEAR(deepest(cs).depth, 0.03, 1e-8);
  dGeomID cylinder = dCreateCylinder(nullptr, 0.2, 1.0);
  dGeomSetPosition(ball, 0.2 + 0.25 - 0.04, 0, 0.1);
  cs = collide(ball, cylinder);
  ASSERT_FALSE(cs.empty());
  EXPECT_NEAR(deepest(cs).depth, 0.04, 1e-8);
  EXPECT_NEAR(normalOf(deepest(cs)).x(), 1, 1e-8);
  for (dGeomID g : {ball, convex, capsule, cylinder}) dGeomDestroy(g);
}

TEST_F(OdeTest, HeightfieldsGiveNoContactsAndAdaptersSayWhy) {
  dHeightfieldDataID data = dGeomHeightfieldDataCreate();
  static const double heights[4] = {0, 0, 0, 0};
  dGeomHeightfieldDataBuildDouble(data, heights, 0, 2, 2, 2, 2, 1, 0, 0.1, 0);
  dGeomID field = dCreateHeightfield(nullptr, data, 1);
  dGeomID ball = unidistGeom(std::make_shared<unidist::Sphere>(0.5));
  EXPECT_TRUE(collide(ball, field).empty());
  EXPECT_THROW(unidist::modelFromOdeGeom(field), unidist::InputError);
  dGeomDestroy(ball);
  dGeomDestroy(field);
  dGeomHeightfieldDataDestroy(data);
}

TEST_F(OdeTest, AabbFollowsThePose) {
  dGeomID g = unidistGeom(std::make_shared<unidist::Box>(Vec(1, 2, 3)));
  Iso X = Iso::Identity();
  X.linear() = Eigen::AngleAxisd(M_PI / 2, Vec::UnitZ()).toRotationMatrix();
  X.translation() = Vec(10, 20, 30);
  odetest::setPose(g, X);
  dReal b[6];
  dGeomGetAABB(g, b);
  const double expect[6] = {8, 12, 19, 21, 27, 33};
  for (int i = 0; i < 6; ++i) EXPECT_NEAR(b[i], expect[i], 1e-12);
  dGeomDestroy(g);
  dGeomID half = unidistGeom(std::make_shared<unidist::Plane>(Vec(0, 0, 1), 0));
  dGeomGetAABB(half, b);
  EXPECT_EQ(b[0], -dInfinity);
  EXPECT_EQ(b[5], dInfinity);
  dGeomDestroy(half);
}

TEST_F(OdeTest, PairCachesLiveAsLongAsTheGeom) {
  const std::size_t before = unidist::ode::pairCacheCount();
  dGeomID a = unidistGeom(std::make_shared<unidist::Sphere>(0.5));
  dGeomID b = unidistGeom(std::make_shared<unidist::Sphere>(0.5));
  dGeomID box = dCreateBox(nullptr, 1, 1, 1);
  dGeomSetPosition(b, 0.9, 0, 0);
  collide(a, b);
  collide(a, box);
  EXPECT_EQ(unidist::ode::pairCacheCount(), before + 2);
  EXPECT_EQ(unidist::ode::geomModel(box), nullptr);
  EXPECT_EQ(unidist::ode::geomModel(a)->type(), unidist::ModelType::Sphere);
  dGeomDestroy(b);
  EXPECT_EQ(unidist::ode::pairCacheCount(), before + 1);
  dGeomDestroy(a);
  EXPECT_EQ(unidist::ode::pairCacheCount(), before);
  dGeomDestroy(box);
}

TEST_F(OdeTest, RejectsBadArguments) {
  EXPECT_THROW(unidist::ode::createGeom(nullptr, nullptr), unidist::InputError);
  dGeomID box = dCreateBox(nullptr, 1, 1, 1);
  EXPECT_THROW(unidist::ode::setTolerance(box, 1e-3), unidist::InputError);
  dGeomID g = unidistGeom(std::make_shared<unidist::Sphere>(1));
  EXPECT_THROW(unidist::ode::setTolerance(g, 0), unidist::InputError);
  EXPECT_THROW(unidist::ode::setTolerance(g, NAN), unidist::InputError);
  unidist::ode::setTolerance(g, -1);
  EXPECT_EQ(unidist::ode::tolerance(g), -1);
  dGeomDestroy(g);
  dGeomDestroy(box);
}

}  // namespace
