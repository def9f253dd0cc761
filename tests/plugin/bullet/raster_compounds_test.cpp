// The opt-in image-space penetration depth for compound–compound pairs (unidist/bullet/raster_compounds.h):
// a cube in the notch of an L-shaped compound gets the union's minimum translation (0.1·√2 along the diagonal),
// where Bullet's own compound algorithm reports each child's 0.1; unsupported children fall back to Bullet.
#include "plugin/bullet/test_world.h"
#include "unidist/bullet/raster_compounds.h"

#include <BulletCollision/CollisionShapes/btCompoundShape.h>
#include <gtest/gtest.h>

#include <cmath>

namespace bullet_test {
namespace {

/// Compounds and the children they point to (btCompoundShape does not own its children).
struct Compounds {
  std::vector<std::unique_ptr<btCollisionShape>> children;

  /// The L block of tests/data/pieces/l_block.obj: [0,2]x[0,1]x[0,1] ∪ [0,1]x[0,2]x[0,1].
  std::unique_ptr<btCompoundShape> lBlock() {
    auto compound = std::make_unique<btCompoundShape>();
    children.push_back(std::make_unique<btBoxShape>(btVector3(1, btScalar(0.5), btScalar(0.5))));
    compound->addChildShape(at(1, 0.5, 0.5), children.back().get());
    children.push_back(std::make_unique<btBoxShape>(btVector3(btScalar(0.5), 1, btScalar(0.5))));
    compound->addChildShape(at(0.5, 1, 0.5), children.back().get());
    return compound;
  }

  std::unique_ptr<btCompoundShape> cube(double half, btCollisionShape* child = nullptr) {
    auto compound = std::make_unique<btCompoundShape>();
    if (!child) {
      children.push_back(std::make_unique<btBoxShape>(btVector3(btScalar(half), btScalar(half), btScalar(half))));
      child = children.back().get();
    }
    compound->addChildShape(btTransform::getIdentity(), child);
    return compound;
  }
};

/// The deepest point Bullet's contactPairTest reports for two objects.
struct Deepest : btCollisionWorld::ContactResultCallback {
  double depth = 1e300;
  btVector3 normalOnB;
  btScalar addSingleResult(btManifoldPoint& p, const btCollisionObjectWrapper*, int, int,
                           const btCollisionObjectWrapper*, int, int) override {
    if (p.getDistance() < depth) {
      depth = p.getDistance();
      normalOnB = p.m_normalWorldOnB;
    }
    return 0;
  }
};

Deepest pairTest(btCollisionWorld& world, btCollisionObject& a, btCollisionObject& b) {
  Deepest deepest;
  world.contactPairTest(&a, &b, deepest);
  return deepest;
}

class RasterCompoundsTest : public ::testing::Test {
 protected:
  void SetUp() override {
    l = shapes.lBlock();
    c = shapes.cube(0.25);
    block.setCollisionShape(l.get());
    cube.setCollisionShape(c.get());
    cube.setWorldTransform(at(1.15, 1.15, 0.5));
  }
  Compounds shapes;
  std::unique_ptr<btCompoundShape> l, c;
  btCollisionObject block, cube;
};

TEST_F(RasterCompoundsTest, CubeInTheNotchGetsTheUnionsTranslationNotAChildsDepth) {
  TestWorld w;
  const Deepest bullet = pairTest(*w.world, block, cube);
  EXPECT_NEAR(bullet.depth, -0.1, 1e-3);  // Bullet's own: one child's depth

  auto raster = unidist::bullet::registerRasterCompounds(&w.dispatcher, {64});
  const Deepest ours = pairTest(*w.world, block, cube);
  EXPECT_NEAR(ours.depth, -0.1 * std::sqrt(2.0), 5e-3);
  // Normal on B (the cube) pointing at A (the block): the cube leaves along +(1, 1, 0)/√2.
  EXPECT_NEAR(double(ours.normalOnB.x()), -std::sqrt(0.5), 0.05);
  EXPECT_NEAR(double(ours.normalOnB.y()), -std::sqrt(0.5), 0.05);
  EXPECT_NEAR(double(ours.normalOnB.z()), 0, 0.05);
  const unidist::bullet::RasterCompoundStats s = unidist::bullet::stats(*raster);
  EXPECT_GE(s.queries, 1);
  EXPECT_GE(s.penetrating, 1);
  EXPECT_EQ(s.fallbacks, 0);

  raster.reset();  // Bullet's own algorithm is back
  EXPECT_NEAR(pairTest(*w.world, block, cube).depth, -0.1, 1e-3);
}

TEST_F(RasterCompoundsTest, SeparatedCompoundsGetNoContactAndAChildThatIsNotConvexFallsBackToBullet) {
  TestWorld w;
  auto raster = unidist::bullet::registerRasterCompounds(&w.dispatcher, {32});
  cube.setWorldTransform(at(1.5, 1.5, 0.5));  // 0.25 off both arms' faces
  EXPECT_EQ(pairTest(*w.world, block, cube).depth, 1e300);

  btSphereShape ball(btScalar(0.25));
  auto ballCompound = shapes.cube(0, &ball);
  btCollisionObject sphere;
  sphere.setCollisionShape(ballCompound.get());
  sphere.setWorldTransform(at(1.15, 1.15, 0.5));
  const Deepest fallback = pairTest(*w.world, block, sphere);
  EXPECT_LT(fallback.depth, 0);  // Bullet's own answer, not none
  const unidist::bullet::RasterCompoundStats s = unidist::bullet::stats(*raster);
  EXPECT_GE(s.fallbacks, 1);
  EXPECT_NE(s.lastError.find("btSphereShape"), std::string::npos) << s.lastError;
}

TEST_F(RasterCompoundsTest, ACubeDroppedIntoTheNotchComesToRest) {
  TestWorld w;
  auto raster = unidist::bullet::registerRasterCompounds(&w.dispatcher, {32});
  w.add(shapes.lBlock(), 0, at(0, 0, 0));
  btRigidBody* falling = w.add(shapes.cube(0.25), 1, at(0.8, 0.8, 1.6));  // over both arms
  w.run(1.5);
  const btVector3 p = falling->getWorldTransform().getOrigin();
  for (int i = 0; i < 3; ++i) ASSERT_TRUE(std::isfinite(double(p[i])));
  EXPECT_NEAR(double(p.z()), 1.25, 0.02);  // on top of the block, not sunk into it
  EXPECT_LT(falling->getLinearVelocity().length(), 0.05);
  EXPECT_GT(unidist::bullet::stats(*raster).queries, 10);
}

TEST(RasterCompoundsOptions, BadResolutionAndNullDispatcherAreInputErrors) {
  TestWorld w;
  EXPECT_THROW(unidist::bullet::registerRasterCompounds(&w.dispatcher, {4}), unidist::InputError);
  EXPECT_THROW(unidist::bullet::registerRasterCompounds(nullptr), unidist::InputError);
}

}  // namespace
}  // namespace bullet_test
