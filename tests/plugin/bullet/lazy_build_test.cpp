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

namespace {

// A shape's own level of detail (ShapeOptions::detailA): its model's stand-in answers the contacts, the exact
// NURBS ball rests where the stand-in does (within the deviation), and a ball asked exactly builds no stand-in.
TEST(BulletLazyBuild, AShapesLevelOfDetailAnswersItsContacts) {
  bullet_test::TestWorld w;
  const auto floor = test_models::meshBox(Eigen::Vector3d(2, 2, 0.1));
  const auto coarse = test_models::nurbsSphere(0.2), exact = test_models::nurbsSphere(0.2);
  unidist::bullet::ShapeOptions o;
  o.detailA = 2e-3;
  w.add(unidist::bullet::makeShape(floor), 0, bullet_test::at(0, 0, -0.1));
  btRigidBody* a = w.add(unidist::bullet::makeShape(coarse, o), 1, bullet_test::at(0, 0, 0.5));
  btRigidBody* b = w.add(unidist::bullet::makeShape(exact), 1, bullet_test::at(1, 0, 0.5));
  w.run(1.5);

  EXPECT_TRUE(structureBuilt(*coarse, "level-of-detail"));
  EXPECT_FALSE(structureBuilt(*exact, "level-of-detail"));
  const double deviation = coarse->atDetail(2e-3).deviation;
  EXPECT_GT(deviation, 0);
  EXPECT_NEAR(double(a->getWorldTransform().getOrigin().z()), 0.2, deviation + 2e-3);
  EXPECT_NEAR(double(b->getWorldTransform().getOrigin().z()), 0.2, 2e-3);
}

}  // namespace
