// An ODE world builds acceleration structures only for the pairs it actually queries (issue 8): a geom the
// space never pairs keeps none, and the geoms that touch build theirs once.
#include "core/query_helpers.h"
#include "plugin/models.h"
#include "ode_fixture.h"
#include "unidist/ode/geom.h"

#include <gtest/gtest.h>

namespace {

using query_test::structureBuilt;

using odetest::Vec;

class OdeLazyBuild : public odetest::OdeWorldTest {};

TEST_F(OdeLazyBuild, OnlyTheQueriedModelsBuildTheirStructures) {
  const auto floor = test_models::meshBox(Vec(2, 2, 0.1));
  const auto crate = test_models::meshBox(Vec(0.2, 0.2, 0.2));
  const auto farMesh = test_models::meshBox(Vec(0.3, 0.3, 0.3));
  const auto farCloud = test_models::cloudBox(Vec(0.3, 0.3, 0.3));
  dGeomID floorGeom = unidist::ode::createGeom(space, floor);
  dGeomSetPosition(floorGeom, 0, 0, -0.1);
  dMass m;
  dMassSetBox(&m, 1, 0.4, 0.4, 0.4);
  dBodyID falling = attachBody(unidist::ode::createGeom(space, crate), m, Vec(0, 0, 0.5));
  attachBody(unidist::ode::createGeom(space, farMesh), m, Vec(50, 0, 0.3));  // falls forever, alone
  dGeomSetPosition(unidist::ode::createGeom(space, farCloud), -50, 0, 0);     // static, alone
  run(1.0);

  EXPECT_NEAR(dBodyGetPosition(falling)[2], 0.2, 0.01);  // it did land on the floor
  EXPECT_TRUE(structureBuilt(*crate, "bvh") || structureBuilt(*floor, "bvh"));
  EXPECT_LE(static_cast<const unidist::TriangleMesh&>(*crate).bvhBuildCount(), 1);
  EXPECT_FALSE(structureBuilt(*farMesh, "bvh"));
  EXPECT_FALSE(structureBuilt(*farMesh, "winding"));
  EXPECT_FALSE(structureBuilt(*farCloud, "point-tree"));
}

}  // namespace

namespace {

class OdeLevelOfDetail : public odetest::OdeWorldTest {};

// A geom's own level of detail (setQueryOptions, detailA): its model's stand-in answers the contacts, the ball
// rests where the stand-in does (within the deviation), and a ball asked exactly builds no stand-in.
TEST_F(OdeLevelOfDetail, AGeomsLevelOfDetailAnswersItsContacts) {
  const auto floor = test_models::meshBox(Vec(2, 2, 0.1));
  const auto coarse = test_models::nurbsSphere(0.2), exact = test_models::nurbsSphere(0.2);
  dGeomSetPosition(unidist::ode::createGeom(space, floor), 0, 0, -0.1);
  dMass m;
  dMassSetSphere(&m, 1, 0.2);
  dGeomID coarseGeom = unidist::ode::createGeom(space, coarse);
  unidist::QueryOptions o;
  o.detailA = 2e-3;
  unidist::ode::setQueryOptions(coarseGeom, o);
  dBodyID a = attachBody(coarseGeom, m, Vec(0, 0, 0.5));
  dBodyID b = attachBody(unidist::ode::createGeom(space, exact), m, Vec(1, 0, 0.5));
  run(1.5);

  EXPECT_TRUE(structureBuilt(*coarse, "level-of-detail"));
  EXPECT_FALSE(structureBuilt(*exact, "level-of-detail"));
  const double deviation = coarse->atDetail(2e-3).deviation;
  EXPECT_GT(deviation, 0);
  EXPECT_NEAR(dBodyGetPosition(a)[2], 0.2, deviation + 2e-3);
  EXPECT_NEAR(dBodyGetPosition(b)[2], 0.2, 2e-3);
}

}  // namespace
