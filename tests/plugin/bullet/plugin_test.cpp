// The Bullet plugin's conventions against Bullet itself: contactPairTest on unidist sphere/box primitives gives
// Bullet's own sphere–sphere and box–box answers (distance, normal, points) in both argument orders; a unidist
// shape meets every Bullet shape type a scene can hold without reaching the SDF path; Bullet's ray test sees
// unidist shapes; the shapes reject local scaling and half-spaces; the warm start does the resting work.
#include "adapters/bullet_reference.h"
#include "plugin/models.h"
#include "plugin/bullet/test_world.h"

#include <BulletCollision/CollisionShapes/btHeightfieldTerrainShape.h>
#include <BulletCollision/Gimpact/btGImpactCollisionAlgorithm.h>
#include <BulletCollision/Gimpact/btGImpactShape.h>
#include <gtest/gtest.h>

#include <random>

namespace {

using bullet_test::at;
using test_models::Vec;
using unidist::bullet::makeShape;

/// Every contact point reported, with the normal turned to point from B to A in the caller's order.
struct Recorder : btCollisionWorld::ContactResultCallback {
  const btCollisionObject* a = nullptr;
  struct Hit {
    double distance;
    btVector3 normalBtoA, onA, onB;
  };
  std::vector<Hit> hits;
  btScalar addSingleResult(btManifoldPoint& cp, const btCollisionObjectWrapper* w0, int, int,
                           const btCollisionObjectWrapper*, int, int) override {
    const bool aFirst = w0->getCollisionObject() == a;
    hits.push_back({double(cp.getDistance()), aFirst ? cp.m_normalWorldOnB : -cp.m_normalWorldOnB,
                    aFirst ? cp.getPositionWorldOnA() : cp.getPositionWorldOnB(),
                    aFirst ? cp.getPositionWorldOnB() : cp.getPositionWorldOnA()});
    return 0;
  }
  const Hit& deepest() const {
    return *std::min_element(hits.begin(), hits.end(), [](const Hit& x, const Hit& y) { return x.distance < y.distance; });
  }
};

class PairWorld {
 public:
  PairWorld() { plugin = unidist::bullet::registerAlgorithms(&dispatcher); }
  ~PairWorld() {
    objects.clear();
    world.reset();
    plugin.reset();
  }
  btCollisionObject* add(btCollisionShape* shape, const btTransform& pose) {
    objects.push_back(std::make_unique<btCollisionObject>());
    objects.back()->setCollisionShape(shape);
    objects.back()->setWorldTransform(pose);
    world->addCollisionObject(objects.back().get());
    return objects.back().get();
  }
  Recorder query(btCollisionObject* a, btCollisionObject* b, double threshold = 1.0) {
    Recorder r;
    r.a = a;
    r.m_closestDistanceThreshold = btScalar(threshold);
    world->contactPairTest(a, b, r);
    return r;
  }

  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher{&config};
  btDbvtBroadphase broadphase;
  std::unique_ptr<unidist::bullet::Registration> plugin;
  std::unique_ptr<btCollisionWorld> world = std::make_unique<btCollisionWorld>(&dispatcher, &broadphase, &config);
  std::vector<std::unique_ptr<btCollisionObject>> objects;
};

btTransform randomPose(std::mt19937_64& rng, double spread) {
  std::uniform_real_distribution<double> u(-spread, spread), q(-1, 1);
  btQuaternion rot(btScalar(q(rng)), btScalar(q(rng)), btScalar(q(rng)), btScalar(q(rng)));
  rot.normalize();
  return at(u(rng), u(rng), u(rng), rot);
}

/// Exact minimum translation depth of two overlapping boxes: the least overlap over the 15 separating axes.
double satDepth(const btBoxShape& a, const btTransform& XA, const btBoxShape& b, const btTransform& XB) {
  const btVector3 ha = a.getHalfExtentsWithMargin(), hb = b.getHalfExtentsWithMargin();
  std::vector<btVector3> axes;
  for (int i = 0; i < 3; ++i) {
    axes.push_back(XA.getBasis().getColumn(i));
    axes.push_back(XB.getBasis().getColumn(i));
    for (int j = 0; j < 3; ++j) axes.push_back(XA.getBasis().getColumn(i).cross(XB.getBasis().getColumn(j)));
  }
  double depth = 1e300;
  for (btVector3 L : axes) {
    if (L.length() < 1e-6) continue;
    L.normalize();
    double ra = 0, rb = 0;
    for (int i = 0; i < 3; ++i) {
      ra += double(ha[i]) * std::abs(double(XA.getBasis().getColumn(i).dot(L)));
      rb += double(hb[i]) * std::abs(double(XB.getBasis().getColumn(i).dot(L)));
    }
    depth = std::min(depth, ra + rb - std::abs(double((XB.getOrigin() - XA.getOrigin()).dot(L))));
  }
  return depth;
}

/// For random poses, the plugin's pair (unidist A, native B) in both orders against Bullet: the native pair's
/// deepest contact for overlaps up to deepLimit (deeper ones: Bullet's box–box reports its clipped points'
/// depths, which can be shallower than the minimum translation, so only "ours is at least as deep"), and
/// Bullet's GJK on margin-free copies (exactA/B; a box's margin rounds its corners) for separated pairs (its
/// box–box measures separation along a face normal, an upper bound). Both orders, mirrored normals.
void compareWithNative(btConvexShape& nativeA, btCollisionShape& unidistA, btConvexShape& nativeB, double spread,
                       double tol, bool comparePoints, double deepLimit, const btConvexShape& exactA,
                       const btConvexShape& exactB, double (*exactDepth)(const btTransform&, const btTransform&)) {
  std::mt19937_64 rng(7);
  int overlapping = 0, separated = 0, deeper = 0;
  for (int i = 0; i < 300; ++i) {
    const btTransform XA = randomPose(rng, spread), XB = randomPose(rng, spread);
    PairWorld native, plugin;
    Recorder truth = native.query(native.add(&nativeA, XA), native.add(&nativeB, XB));
    btCollisionObject* ua = plugin.add(&unidistA, XA);
    btCollisionObject* nb = plugin.add(&nativeB, XB);
    Recorder ab = plugin.query(ua, nb), ba = plugin.query(nb, ua);
    const double gjk = bullet_reference::bulletConvexDistance(exactA, XA, exactB, XB);
    if (gjk > 0.05) {  // apart: both orders report the exact distance (threshold 1) or nothing beyond it
      if (gjk > 0.9) continue;
      ++separated;
      ASSERT_FALSE(ab.hits.empty()) << "pose " << i;
      ASSERT_FALSE(ba.hits.empty()) << "pose " << i;
      EXPECT_NEAR(ab.deepest().distance, gjk, tol) << "pose " << i;
      EXPECT_NEAR(ba.deepest().distance, gjk, tol) << "pose " << i;
      continue;
    }
    if (gjk > 0) continue;  // GJK's own margin band: not a reference either way
    ASSERT_FALSE(truth.hits.empty()) << "pose " << i;
    ASSERT_FALSE(ab.hits.empty()) << "pose " << i;
    ASSERT_FALSE(ba.hits.empty()) << "pose " << i;
    ++overlapping;
    const Recorder::Hit &t = truth.deepest(), &x = ab.deepest(), &y = ba.deepest();
    if (t.distance < -deepLimit || x.distance < t.distance - tol) {
      // Ours is the exact minimum translation; Bullet's box–box reports its clipped points' depths, which can
      // be shallower (deep overlaps, edge–edge crossings): ours is never the shallower one.
      ++deeper;
      EXPECT_LE(x.distance, t.distance + tol) << "pose " << i;
      if (exactDepth) {
        EXPECT_NEAR(x.distance, -exactDepth(XA, XB), tol) << "pose " << i;
      }
      EXPECT_NEAR(y.distance, x.distance, tol) << "pose " << i;
      continue;
    }
    EXPECT_NEAR(x.distance, t.distance, tol) << "pose " << i;
    EXPECT_NEAR(y.distance, t.distance, tol) << "pose " << i;
    EXPECT_GT(double(x.normalBtoA.dot(t.normalBtoA)), 1 - 1e-3) << "pose " << i;
    EXPECT_GT(double(-y.normalBtoA.dot(t.normalBtoA)), 1 - 1e-3) << "pose " << i << " (reversed order)";
    if (comparePoints) {
      EXPECT_LT(double((x.onA - t.onA).length()), 10 * tol) << "pose " << i;
    }
  }
  EXPECT_GT(overlapping, 30);
  if (!exactDepth) {
    EXPECT_EQ(deeper, 0) << "only Bullet's box–box clips its points";
  }
  EXPECT_GT(separated, 30);
}

TEST(BulletPlugin, SphereSphereMatchesBullet) {
  btSphereShape nativeA(0.5), nativeB(0.7);
  auto unidistA = makeShape(std::make_shared<unidist::Sphere>(0.5));
  compareWithNative(nativeA, *unidistA, nativeB, 0.8, 2e-5, true, 1e9, nativeA, nativeB, nullptr);
}

TEST(BulletPlugin, BoxBoxMatchesBullet) {
  btBoxShape nativeA(btVector3(0.5, 0.3, 0.2)), nativeB(btVector3(0.4, 0.6, 0.3));
  auto unidistA = makeShape(std::make_shared<unidist::Box>(Vec(0.5, 0.3, 0.2)));
  // Bullet's deepest box–box point is a corner of its clipped face; ours is the minimum-translation witness.
  btBoxShape exactA(btVector3(0.5, 0.3, 0.2)), exactB(btVector3(0.4, 0.6, 0.3));
  exactA.setMargin(0);
  exactB.setMargin(0);
  compareWithNative(nativeA, *unidistA, nativeB, 0.8, 2e-4, false, 0.03, exactA, exactB,
                    [](const btTransform& XA, const btTransform& XB) {
                      return satDepth(btBoxShape(btVector3(0.5, 0.3, 0.2)), XA, btBoxShape(btVector3(0.4, 0.6, 0.3)), XB);
                    });
}

TEST(BulletPlugin, SpherePlaneMatchesBullet) {
  btSphereShape nativeA(0.5);
  btStaticPlaneShape plane(btVector3(0, 0, 1), 0);
  auto unidistA = makeShape(std::make_shared<unidist::Sphere>(0.5));
  PairWorld native, plugin;
  for (double z : {0.7, 0.5, 0.3}) {
    Recorder truth = native.query(native.add(&nativeA, at(0, 0, z)), native.add(&plane, at(0, 0, 0)));
    Recorder mine = plugin.query(plugin.add(unidistA.get(), at(0, 0, z)), plugin.add(&plane, at(0, 0, 0)));
    ASSERT_FALSE(truth.hits.empty());
    ASSERT_FALSE(mine.hits.empty());
    EXPECT_NEAR(mine.deepest().distance, truth.deepest().distance, 1e-6);
    EXPECT_NEAR(double(mine.deepest().normalBtoA.z()), 1.0, 1e-6);
  }
}

/// A unidist mesh box (concave type = Bullet's SDF type) and a unidist sphere overlapping each Bullet shape
/// type: contacts come back, finite and penetrating, and nothing crashes.
TEST(BulletPlugin, MeetsEveryBulletShapeType) {
  btSphereShape sphere(0.5);
  btBoxShape box(btVector3(0.5, 0.5, 0.5));
  btCapsuleShapeZ capsule(0.3, 0.6);
  btCylinderShapeZ cylinder(btVector3(0.4, 0.4, 0.5));
  btConeShapeZ cone(0.5, 1.0);
  btStaticPlaneShape plane(btVector3(0, 0, 1), 0);
  btConvexHullShape hull;
  for (int i = 0; i < 8; ++i) hull.addPoint(btVector3(i & 1 ? 0.5 : -0.5, i & 2 ? 0.5 : -0.5, i & 4 ? 0.5 : -0.5));
  btTriangleMesh triangles;
  triangles.addTriangle(btVector3(-2, -2, 0.4), btVector3(2, -2, 0.4), btVector3(2, 2, 0.4));
  triangles.addTriangle(btVector3(-2, -2, 0.4), btVector3(2, 2, 0.4), btVector3(-2, 2, 0.4));
  btBvhTriangleMeshShape bvhMesh(&triangles, true);
  btGImpactMeshShape gimpact(&triangles);
  gimpact.updateBound();
  std::vector<float> heights(16 * 16, 0.9f);  // Bullet centres the height range [0, 1]: the surface is at z 0.4
  btHeightfieldTerrainShape terrain(16, 16, heights.data(), 1, 0, 1, 2, PHY_FLOAT, false);
  btCompoundShape compound;
  compound.addChildShape(at(0.2, 0, 0), &box);
  std::vector<std::pair<const char*, btCollisionShape*>> natives = {
      {"sphere", &sphere}, {"box", &box},    {"capsule", &capsule},   {"cylinder", &cylinder},
      {"cone", &cone},     {"plane", &plane}, {"convex hull", &hull}, {"bvh mesh", &bvhMesh},
      {"gimpact", &gimpact}, {"heightfield", &terrain}, {"compound", &compound}};
  auto meshBox = makeShape(test_models::meshBox(Vec(0.5, 0.5, 0.5)));
  auto ball = makeShape(std::make_shared<unidist::Sphere>(0.5));
  for (btCollisionShape* mine : {meshBox.get(), ball.get()}) {
    for (const auto& [name, native] : natives) {
      for (bool unidistFirst : {true, false}) {
        PairWorld w;
        w.plugin.reset();  // a registration restores the defaults when it goes: the old one first
        btGImpactCollisionAlgorithm::registerAlgorithm(&w.dispatcher);
        w.plugin = unidist::bullet::registerAlgorithms(&w.dispatcher);  // after GImpact's, which overwrites its row
        btCollisionObject* u = nullptr;
        btCollisionObject* n = nullptr;
        if (unidistFirst) u = w.add(mine, at(0, 0, 0.7));
        n = w.add(native, at(0, 0, native == &plane ? 0.4 : 0));
        if (!unidistFirst) u = w.add(mine, at(0, 0, 0.7));
        const Recorder r = w.query(u, n, 0.0);
        SCOPED_TRACE(std::string(name) + (unidistFirst ? " (unidist first)" : " (native first)") + (mine == ball.get() ? ", unidist sphere" : ", unidist mesh box"));
        ASSERT_FALSE(r.hits.empty());
        EXPECT_LT(r.deepest().distance, 0);
        EXPECT_TRUE(std::isfinite(r.deepest().distance));
        EXPECT_GT(double(r.deepest().normalBtoA.z()), 0.5) << "A is above: pushed up";
      }
    }
  }
}

TEST(BulletPlugin, RayTestSeesUnidistShapes) {
  auto ball = makeShape(std::make_shared<unidist::Sphere>(0.5));
  auto mesh = makeShape(test_models::meshBox(Vec(0.5, 0.5, 0.5)));
  for (btCollisionShape* s : {ball.get(), mesh.get()}) {
    PairWorld w;
    w.add(s, at(0, 0, 1));
    btCollisionWorld::ClosestRayResultCallback ray(btVector3(0.1, 0, 5), btVector3(0.1, 0, -5));
    w.world->rayTest(btVector3(0.1, 0, 5), btVector3(0.1, 0, -5), ray);
    ASSERT_TRUE(ray.hasHit());
    const double expected = s == ball.get() ? 1 + std::sqrt(0.25 - 0.01) : 1.5;
    EXPECT_NEAR(double(ray.m_hitPointWorld.z()), expected, 1e-4);
  }
}

TEST(BulletPlugin, ShapesRejectScalingAndHalfSpaces) {
  auto ball = makeShape(std::make_shared<unidist::Sphere>(0.5));
  EXPECT_THROW(ball->setLocalScaling(btVector3(2, 2, 2)), unidist::InputError);
  ball->setLocalScaling(btVector3(1, 1, 1));  // the identity is fine
  auto mesh = makeShape(test_models::meshBox(Vec(0.5, 0.5, 0.5)));
  EXPECT_THROW(mesh->setLocalScaling(btVector3(1, 2, 1)), unidist::InputError);
  EXPECT_THROW(makeShape(std::make_shared<unidist::Plane>(Vec(0, 0, 1), 0)), unidist::InputError);
  EXPECT_THROW(makeShape(nullptr), unidist::InputError);
}

TEST(BulletPlugin, ShapeTypesAndExactAabb) {
  auto ball = makeShape(std::make_shared<unidist::Sphere>(0.5));
  auto torus = makeShape(std::make_shared<unidist::Torus>(1, 0.25));
  EXPECT_EQ(ball->getShapeType(), CUSTOM_CONVEX_SHAPE_TYPE);
  EXPECT_EQ(torus->getShapeType(), CUSTOM_CONCAVE_SHAPE_TYPE);
  btVector3 mn, mx;
  ball->getAabb(at(1, 2, 3), mn, mx);
  EXPECT_NEAR(double(mn.x()), 0.5, 1e-6);
  EXPECT_NEAR(double(mx.z()), 3.5, 1e-6);
}

TEST(BulletPlugin, RestingContactsAreWarmStarted) {
  bullet_test::TestWorld w;
  w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, at(0, 0, 0));
  w.add(makeShape(std::make_shared<unidist::Torus>(0.6, 0.15)), 1, at(0, 0, 0.2));
  w.run(2.0);
  const unidist::bullet::PluginStats s = unidist::bullet::stats(*w.plugin);
  EXPECT_GT(s.localUpdates, 2 * s.globalSearches) << s.localUpdates << " local, " << s.globalSearches << " global";
}

}  // namespace
