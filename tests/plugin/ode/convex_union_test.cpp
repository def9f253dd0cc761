// Convex-union geoms (unidist/ode/convex_union.h): two such geoms collide through the image-space penetration
// depth — a cube in the notch of an L-shaped union gets one contact at the union's minimum translation (0.1·√2
// along the diagonal), where any single piece says 0.1 — and a cube dropped on the union comes to rest.
#include "plugin/ode/ode_fixture.h"
#include "unidist/ode/convex_union.h"

namespace odetest {
namespace {

std::vector<Vec> boxCorners(const Vec& lo, const Vec& hi) {
  std::vector<Vec> corners;
  for (int c = 0; c < 8; ++c)
    corners.emplace_back((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
  return corners;
}

/// The L block of tests/data/pieces/l_block.obj.
std::vector<std::vector<Vec>> lBlock() { return {boxCorners({0, 0, 0}, {2, 1, 1}), boxCorners({0, 0, 0}, {1, 2, 1})}; }

std::vector<std::vector<Vec>> cube(double half) { return {boxCorners(Vec::Constant(-half), Vec::Constant(half))}; }

using ConvexUnionGeomTest = OdeTest;

TEST_F(ConvexUnionGeomTest, CubeInTheNotchGetsOneContactAtTheUnionsTranslation) {
  dGeomID block = unidist::ode::createConvexUnionGeom(nullptr, lBlock(), 64);
  dGeomID box = unidist::ode::createConvexUnionGeom(nullptr, cube(0.25), 64);
  dGeomSetPosition(box, 1.15, 1.15, 0.5);
  const std::vector<dContactGeom> cs = collide(block, box);
  ASSERT_EQ(cs.size(), 1u) << unidist::ode::lastError();
  EXPECT_NEAR(cs[0].depth, 0.1 * std::sqrt(2.0), 5e-3);
  // From g2 into g1: moving the block (g1) along it separates, i.e. away from the cube: −(1, 1, 0)/√2.
  EXPECT_NEAR(cs[0].normal[0], -std::sqrt(0.5), 0.05);
  EXPECT_NEAR(cs[0].normal[1], -std::sqrt(0.5), 0.05);
  EXPECT_NEAR(cs[0].normal[2], 0, 0.05);

  const std::vector<dContactGeom> swapped = collide(box, block);  // ODE swaps and negates itself
  ASSERT_EQ(swapped.size(), 1u);
  EXPECT_NEAR(swapped[0].normal[0], std::sqrt(0.5), 0.05);

  dGeomSetPosition(box, 1.5, 1.5, 0.5);  // 0.25 off both arms: nothing
  EXPECT_TRUE(collide(block, box).empty());
  dGeomDestroy(block);
  dGeomDestroy(box);
}

TEST_F(ConvexUnionGeomTest, BadPiecesAndResolutionsAreInputErrors) {
  EXPECT_THROW(unidist::ode::createConvexUnionGeom(nullptr, {}), unidist::InputError);
  EXPECT_THROW(unidist::ode::createConvexUnionGeom(nullptr, cube(1), 4), unidist::InputError);
  EXPECT_THROW(unidist::ode::createConvexUnionGeom(nullptr, {{Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0), Vec(1, 1, 0)}}),
               unidist::InputError);  // flat
  EXPECT_THROW(unidist::ode::createConvexUnionGeom(nullptr, {{Vec(0, 0, 0), Vec(1, 0, 0), Vec(0, 1, 0),
                                                              Vec(0, 0, std::nan(""))}}),
               unidist::InputError);
}

using ConvexUnionWorldTest = OdeWorldTest;

TEST_F(ConvexUnionWorldTest, ACubeDroppedOnTheUnionComesToRest) {
  unidist::ode::createConvexUnionGeom(space, lBlock(), 32);
  dGeomID box = unidist::ode::createConvexUnionGeom(space, cube(0.25), 32);
  dMass m;
  dMassSetBoxTotal(&m, 1, 0.5, 0.5, 0.5);
  dBodyID body = attachBody(box, m, Vec(0.8, 0.8, 1.6));  // over both arms
  run(1.5);
  const Vec p = position(body);
  ASSERT_TRUE(p.allFinite());
  EXPECT_NEAR(p.z(), 1.25, 0.02);
  EXPECT_LT(linearVelocity(body).norm(), 0.05);
  EXPECT_LT(maxDepth, 0.02);
  EXPECT_TRUE(unidist::ode::lastError().empty()) << unidist::ode::lastError();
}

}  // namespace
}  // namespace odetest
