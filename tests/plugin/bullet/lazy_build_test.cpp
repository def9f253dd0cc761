// A Bullet world builds acceleration structures only for the pairs it actually queries (issue 8): a body the
// broadphase never pairs keeps none, and the bodies that touch build theirs once.
#include "plugin/bullet/test_world.h"
#include "core/query_helpers.h"
#include "plugin/models.h"

#include <gtest/gtest.h>

namespace {

using query_test::structureBuilt;

TEST(BulletLazyBuild, OnlyTheQueriedModelsBuildTheirStructures) {
  bullet_test::TestWorld w;
  const auto floor = test_models::meshBox(Eigen::Vector3d(2, 2, 0.1));
  const auto crate = test_models::meshBox(Eigen::Vector3d(0.2, 0.2, 0.2));
  const auto farMesh = test_models::meshBox(Eigen::Vector3d(0.3, 0.3, 0.3));
  const auto farCloud = test_models::cloudBox(Eigen::Vector3d(0.3, 0.3, 0.3));
  w.add(unidist::bullet::makeShape(floor), 0, bullet_test::at(0, 0, -0.1));
  btRigidBody* falling = w.add(unidist::bullet::makeShape(crate), 1, bullet_test::at(0, 0, 0.5));
  w.add(unidist::bullet::makeShape(farMesh), 1, bullet_test::at(50, 0, 0.3));   // falls forever, alone
  w.add(unidist::bullet::makeShape(farCloud), 0, bullet_test::at(-50, 0, 0));  // static, alone
  w.run(1.0);

  EXPECT_NEAR(double(falling->getWorldTransform().getOrigin().z()), 0.2, 0.01);  // it did land on the floor
  EXPECT_TRUE(structureBuilt(*crate, "bvh") || structureBuilt(*floor, "bvh"));
  const auto& crateMesh = static_cast<const unidist::TriangleMesh&>(*crate);
  EXPECT_LE(crateMesh.bvhBuildCount(), 1);
  EXPECT_FALSE(structureBuilt(*farMesh, "bvh"));
  EXPECT_FALSE(structureBuilt(*farMesh, "winding"));
  EXPECT_FALSE(structureBuilt(*farCloud, "point-tree"));
}

}  // namespace
