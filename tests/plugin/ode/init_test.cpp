// Registration: init() is idempotent, registers again after dCloseODE + dInitODE2 (ODE forgets user classes),
// takes whatever class id ODE hands out when another library registered first, and geoms created after a
// re-initialisation collide. No fixture here: these tests drive ODE's initialisation themselves.
#include "unidist/ode/geom.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>
#include <ode/ode.h>

namespace {

/// Contacts of a unidist sphere sunk 0.1 into a native box, in a fresh pair of geoms (0 when the class is not
/// registered: ODE then has no collider for the pair).
int sphereOnBoxContacts() {
  dGeomID ball = unidist::ode::createGeom(nullptr, std::make_shared<unidist::Sphere>(0.5));
  dGeomID box = dCreateBox(nullptr, 2, 2, 1);
  dGeomSetPosition(ball, 0, 0, 0.9);
  dContactGeom c[4];
  const int n = dCollide(ball, box, 4, c, sizeof(dContactGeom));
  dGeomDestroy(ball);
  dGeomDestroy(box);
  return n;
}

void noAabb(dGeomID, dReal aabb[6]) {
  for (int i = 0; i < 6; ++i) aabb[i] = 0;
}
dColliderFn* noCollider(int) { return nullptr; }

TEST(OdeInit, IdempotentAndAgainAfterCloseOde) {
  dInitODE2(0);
  unidist::ode::init();
  const int first = unidist::ode::geomClass();
  EXPECT_GE(first, dFirstUserClass);
  unidist::ode::init();
  unidist::ode::init();
  EXPECT_EQ(unidist::ode::geomClass(), first);  // no second class taken
  EXPECT_GT(sphereOnBoxContacts(), 0);
  dCloseODE();

  // Several re-initialisations in one process: more than ODE's 4 user classes if each took a new slot.
  for (int round = 0; round < 6; ++round) {
    dInitODE2(0);
    unidist::ode::init();
    EXPECT_EQ(unidist::ode::geomClass(), dFirstUserClass) << round;  // ODE's table starts empty again
    EXPECT_GT(sphereOnBoxContacts(), 0) << round;
    dCloseODE();
  }
}

TEST(OdeInit, TakesTheIdOdeHandsOut) {
  dInitODE2(0);
  dGeomClass other{};
  other.bytes = 8;
  other.collider = &noCollider;
  other.aabb = &noAabb;
  const int theirs = dCreateGeomClass(&other);  // another library registered first
  unidist::ode::init();
  EXPECT_EQ(unidist::ode::geomClass(), theirs + 1);
  EXPECT_GT(sphereOnBoxContacts(), 0);
  dCloseODE();
}

TEST(OdeInit, NestedInitialisationKeepsTheClass) {
  dInitODE2(0);
  unidist::ode::init();
  const int id = unidist::ode::geomClass();
  dInitODE2(0);  // a second user of ODE in the same process
  unidist::ode::init();
  EXPECT_EQ(unidist::ode::geomClass(), id);
  dCloseODE();  // still initialised once
  unidist::ode::init();
  EXPECT_EQ(unidist::ode::geomClass(), id);
  EXPECT_GT(sphereOnBoxContacts(), 0);
  dCloseODE();
}

}  // namespace
