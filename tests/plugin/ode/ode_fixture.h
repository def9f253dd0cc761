// ODE test worlds: ODE initialised and the unidist class registered for the fixture's lifetime (closed again at
// the end, so every test also exercises registration after dCloseODE), geoms and bodies created through helpers,
// and the ordinary user loop (dSpaceCollide → dCollide → dJointCreateContact → step).
#pragma once

#include "unidist/adapters/ode_geoms.h"
#include "unidist/ode/geom.h"

#include <gtest/gtest.h>
#include <ode/ode.h>

#include <algorithm>
#include <cmath>
#include <memory>
#include <vector>

namespace odetest {

using Vec = Eigen::Vector3d;

inline void setRotation(dGeomID g, const Eigen::Matrix3d& R) {
  dMatrix3 m;
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) m[4 * i + j] = R(i, j);
    m[4 * i + 3] = 0;
  }
  dGeomSetRotation(g, m);
}

inline void setPose(dGeomID g, const Eigen::Isometry3d& X) {
  dGeomSetPosition(g, X.translation().x(), X.translation().y(), X.translation().z());
  setRotation(g, X.linear());
}

inline Vec position(dBodyID b) {
  const dReal* p = dBodyGetPosition(b);
  return Vec(p[0], p[1], p[2]);
}

inline Vec linearVelocity(dBodyID b) {
  const dReal* v = dBodyGetLinearVel(b);
  return Vec(v[0], v[1], v[2]);
}

/// All contacts of dCollide(a, b), at most maxc.
inline std::vector<dContactGeom> collide(dGeomID a, dGeomID b, int maxc = 16) {
  std::vector<dContactGeom> c(static_cast<std::size_t>(maxc));
  const int n = dCollide(a, b, maxc, c.data(), sizeof(dContactGeom));
  c.resize(static_cast<std::size_t>(n));
  return c;
}

/// The deepest of a non-empty set of contacts.
inline const dContactGeom& deepest(const std::vector<dContactGeom>& cs) {
  return *std::max_element(cs.begin(), cs.end(),
                           [](const dContactGeom& x, const dContactGeom& y) { return x.depth < y.depth; });
}

/// ODE initialised for the test's lifetime.
class OdeTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dInitODE2(0);
    unidist::ode::init();
  }
  void TearDown() override { dCloseODE(); }
};

/// A world, a space and the usual contact loop, with the fixture's surface layer and soft CFM.
class OdeWorldTest : public OdeTest {
 protected:
  void SetUp() override {
    OdeTest::SetUp();
    world = dWorldCreate();
    space = dHashSpaceCreate(nullptr);
    group = dJointGroupCreate(0);
    dWorldSetGravity(world, 0, 0, -9.81);
    dWorldSetContactSurfaceLayer(world, layer);
  }
  void TearDown() override {
    dJointGroupDestroy(group);
    dSpaceDestroy(space);
    dWorldDestroy(world);
    OdeTest::TearDown();
  }

  /// A dynamic body holding geom g at its centre (mass from an ODE mass of the caller's choice).
  dBodyID attachBody(dGeomID g, const dMass& m, const Vec& at) {
    dBodyID b = dBodyCreate(world);
    dBodySetMass(b, &m);
    dBodySetPosition(b, at.x(), at.y(), at.z());
    dGeomSetBody(g, b);
    return b;
  }

  static void nearCallback(void* data, dGeomID o1, dGeomID o2) {
    auto* self = static_cast<OdeWorldTest*>(data);
    dBodyID b1 = dGeomGetBody(o1), b2 = dGeomGetBody(o2);
    if (!b1 && !b2) return;
    dContact c[8];
    const int n = dCollide(o1, o2, 8, &c[0].geom, sizeof(dContact));
    for (int i = 0; i < n; ++i) {
      c[i].surface.mode = dContactApprox1;
      c[i].surface.mu = self->mu;
      self->maxDepth = std::max(self->maxDepth, static_cast<double>(c[i].geom.depth));
      dJointAttach(dJointCreateContact(self->world, self->group, &c[i]), dGeomGetBody(c[i].geom.g1),
                   dGeomGetBody(c[i].geom.g2));
    }
    self->contactsSeen += n;
  }

  void step(bool quick = false) {
    dSpaceCollide(space, this, &nearCallback);
    if (quick)
      dWorldQuickStep(world, dt);
    else
      dWorldStep(world, dt);
    dJointGroupEmpty(group);
  }

  void run(double seconds, bool quick = false) {
    const int n = static_cast<int>(seconds / dt + 0.5);
    for (int i = 0; i < n; ++i) step(quick);
  }

  dWorldID world = nullptr;
  dSpaceID space = nullptr;
  dJointGroupID group = nullptr;
  double dt = 1.0 / 240;
  double layer = 1e-4;
  double mu = 0.6;
  double maxDepth = 0;
  long contactsSeen = 0;
};

}  // namespace odetest
