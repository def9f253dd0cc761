// Bad input through Bullet (docs/reliability.md, "Bad input through the engines"). The policy: a model that cannot
// be a shape (a primitive of zero size, no triangles, no points, null, a half-space) is refused with InputError when
// it is made; a shape whose pose or velocity goes non-finite while the world runs is skipped — its pairs get no
// contacts, stats().skippedPairs counts them, nothing is thrown through stepSimulation — and the others simulate on.
#include "plugin/bullet/test_world.h"
#include "plugin/models.h"
#include "unidist/adapters/scene.h"
#include "unidist/adapters/spec.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <string>

namespace {

using bullet_test::at;
using bullet_test::TestWorld;
using test_models::Vec;
using unidist::InputError;
using unidist::bullet::makeShape;

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

bool finite(const btRigidBody& b) {
  const btTransform& X = b.getWorldTransform();
  for (int i = 0; i < 3; ++i)
    if (!std::isfinite(double(X.getOrigin()[i])) || !std::isfinite(double(X.getBasis()[i].length2()))) return false;
  return std::isfinite(double(b.getLinearVelocity().length2())) &&
         std::isfinite(double(b.getAngularVelocity().length2()));
}

TEST(BulletBadInput, ZeroSizeAndEmptyModelsAreRefusedWhenMade) {
  EXPECT_THROW(unidist::parsePrimitiveSpec("sphere:r=0"), InputError);
  EXPECT_THROW(unidist::parsePrimitiveSpec("box:hx=1,hy=0,hz=1"), InputError);
  EXPECT_THROW(unidist::parsePrimitiveSpec("cylinder:r=1,h=nan"), InputError);
  EXPECT_THROW(unidist::Sphere(0.0), InputError);
  EXPECT_THROW(unidist::Box(Vec(1, 0, 1)), InputError);
  EXPECT_THROW(unidist::TriangleMesh({Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0)}, {}), InputError) << "no triangles";
  EXPECT_THROW(unidist::TriangleMesh({Vec(0, 0, 0), Vec(1, 0, 0), Vec(2, 0, 0)}, {{0, 1, 2}}), InputError)
      << "only a zero-area triangle";
  EXPECT_THROW(unidist::PointCloud(std::vector<Vec>{}), InputError);
  EXPECT_THROW(makeShape(nullptr), InputError);
  EXPECT_THROW(makeShape(std::make_shared<unidist::Plane>(Vec(0, 0, 1), 0)), InputError) << "use btStaticPlaneShape";
  EXPECT_THROW(unidist::parseScene(R"({"bodies": [{"name": "b", "model": "sphere:r=0", "mass": 1}]})", ".", "scene"),
               InputError);
}

/// A box resting on the floor with a ball resting on it; the ball then goes bad. Returns the box.
struct BadBallOnBox {
  TestWorld w;
  btRigidBody* box;
  btRigidBody* ball;
  BadBallOnBox() {
    w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, at(0, 0, 0));
    box = w.add(makeShape(std::make_shared<unidist::Box>(Vec(0.5, 0.5, 0.25))), 2, at(0, 0, 0.25));
    ball = w.add(makeShape(test_models::nurbsSphere(0.2)), 1, at(0, 0, 0.7));
    box->setActivationState(DISABLE_DEACTIVATION);
    w.run(1.0);  // settled: the ball–box pair has its algorithm and manifold
  }
  void expectBoxUndisturbed() {
    EXPECT_TRUE(finite(*box));
    EXPECT_NEAR(double(box->getWorldTransform().getOrigin().z()), 0.25, 1e-3);
    EXPECT_LT(double(box->getLinearVelocity().length()), 1e-2);
  }
};

TEST(BulletBadInput, NanPoseIsSkippedAndTheRestSimulates) {
  BadBallOnBox s;
  const long skippedBefore = unidist::bullet::stats(*s.w.plugin).skippedPairs;
  btTransform bad = s.ball->getWorldTransform();
  bad.setOrigin(btVector3(btScalar(kNaN), 0, btScalar(0.7)));
  s.ball->setWorldTransform(bad);
  EXPECT_NO_THROW(s.w.run(1.0));
  EXPECT_GT(unidist::bullet::stats(*s.w.plugin).skippedPairs, skippedBefore);
  s.expectBoxUndisturbed();
}

TEST(BulletBadInput, NanAndInfiniteVelocitiesAreSkippedAndTheRestSimulates) {
  for (const bool angular : {false, true})
    for (const double v : {kNaN, kInf}) {
      SCOPED_TRACE(std::string(angular ? "angular " : "linear ") + std::to_string(v));
      BadBallOnBox s;
      if (angular)
        s.ball->setAngularVelocity(btVector3(btScalar(v), 0, 0));
      else
        s.ball->setLinearVelocity(btVector3(0, btScalar(v), 0));
      EXPECT_NO_THROW(s.w.run(1.0));
      EXPECT_GT(unidist::bullet::stats(*s.w.plugin).skippedPairs, 0);
      s.expectBoxUndisturbed();
    }
}

TEST(BulletBadInput, ClosestPointQueryWithANanPoseReportsNothing) {
  TestWorld w;
  btRigidBody* a = w.add(makeShape(std::make_shared<unidist::Sphere>(0.5)), 0, at(0, 0, 0));
  btRigidBody* b = w.add(makeShape(test_models::meshBox(Vec(0.5, 0.5, 0.5))), 0, at(0.9, 0, 0));
  struct Count : btCollisionWorld::ContactResultCallback {
    int n = 0;
    btScalar addSingleResult(btManifoldPoint&, const btCollisionObjectWrapper*, int, int,
                             const btCollisionObjectWrapper*, int, int) override {
      ++n;
      return 0;
    }
  } touching, afterNan;
  w.world->contactPairTest(a, b, touching);
  EXPECT_GT(touching.n, 0) << "the pair overlaps";
  btTransform bad = b->getWorldTransform();
  bad.setOrigin(btVector3(btScalar(kNaN), 0, 0));
  b->setWorldTransform(bad);
  EXPECT_NO_THROW(w.world->contactPairTest(a, b, afterNan));
  EXPECT_EQ(afterNan.n, 0);
}

TEST(BulletBadInput, SinglePointCloudDoesNotUpsetTheWorld) {
  // A point cloud of one point is a model of zero size, yet a valid one: it lands on the box like a grain of sand
  // (a point contact), and the box keeps resting.
  TestWorld w;
  w.add(std::make_unique<btStaticPlaneShape>(btVector3(0, 0, 1), 0), 0, at(0, 0, 0));
  btRigidBody* box = w.add(makeShape(std::make_shared<unidist::Box>(Vec(0.5, 0.5, 0.25))), 2, at(0, 0, 0.25));
  btRigidBody* dot = w.add(makeShape(std::make_shared<unidist::PointCloud>(std::vector<Vec>{Vec::Zero()})), 1,
                           at(0.2, 0.1, 0.8));
  EXPECT_NO_THROW(w.run(2.0));
  EXPECT_TRUE(finite(*dot));
  EXPECT_NEAR(double(dot->getWorldTransform().getOrigin().z()), 0.5, 1e-3) << "on the box top";
  EXPECT_EQ(unidist::bullet::stats(*w.plugin).skippedPairs, 0);
  EXPECT_TRUE(finite(*box));
  EXPECT_NEAR(double(box->getWorldTransform().getOrigin().z()), 0.25, 1e-3);
}

}  // namespace
