// unidist geoms in ordinary ODE worlds (the user's own loop, dWorldStep): a primitive sphere, the NURBS sphere,
// a mesh box, a point-cloud box and a torus dropped on dCreatePlane, on a static dCreateBox and on other unidist
// geoms rest at the analytic height (within the surface layer + 1e-3 of their size) and do not drift; a stack of
// mixed bodies stays standing; a sphere settles at the bottom of an open mesh bowl and of an open NURBS bowl;
// ODE's ray sensors see unidist geoms. Masses come from ODE's own dMass helpers, as an ODE user would set them.
#include "plugin/models.h"
#include "ode_fixture.h"
#include "unidist/adapters/load.h"
#include "unidist/mesh.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <chrono>
#include <iostream>
#include <string>

namespace {

using odetest::OdeWorldTest;
using odetest::Vec;
using ModelPtr = std::shared_ptr<const unidist::Model>;

/// A box [-h, h]^3 as a 12-triangle mesh and as the lattice of its faces (a point cloud).
ModelPtr meshBox(double h) { return test_models::meshBox(Vec(h, h, h), 1); }
ModelPtr cloudBox(double h) { return test_models::cloudBox(Vec(h, h, h), 5); }

ModelPtr nurbsSphere() {
  static const ModelPtr m = unidist::loadModel(std::string(UNIDIST_SHARED_DIR) + "/acceptance/models/sphere_nurbs.unurbs.json");
  return m;
}

/// The open bowl z = x² + y² over [-1, 1]² tessellated on an n x n grid (an open mesh: no inside).
ModelPtr meshBowl(int n) {
  std::vector<Vec> v;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) {
      const double x = -1 + 2.0 * i / n, y = -1 + 2.0 * j / n;
      v.emplace_back(x, y, x * x + y * y);
    }
  std::vector<unidist::TriangleMesh::Triangle> t;
  const auto at = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.push_back({at(i, j), at(i + 1, j), at(i + 1, j + 1)});
      t.push_back({at(i, j), at(i + 1, j + 1), at(i, j + 1)});
    }
  return std::make_shared<unidist::TriangleMesh>(v, t);
}

struct Drop {
  const char* name;
  ModelPtr model;
  double restAboveSupport;  // analytic height of the model origin above the support's top
  double size;              // bounding diagonal scale for the tolerance
  dMass mass;
};

dMass boxMass(double m, double h) {
  dMass mass;
  dMassSetBoxTotal(&mass, m, 2 * h, 2 * h, 2 * h);
  return mass;
}
dMass sphereMass(double m, double r) {
  dMass mass;
  dMassSetSphereTotal(&mass, m, r);
  return mass;
}
dMass cylinderMass(double m, double r, double h) {
  dMass mass;
  dMassSetCylinderTotal(&mass, m, 3, r, 2 * h);
  return mass;
}
dMass torusMass(double m, double R, double r) {
  dMass mass;
  const double ixx = m * (0.5 * R * R + 0.625 * r * r), izz = m * (R * R + 0.75 * r * r);
  dMassSetParameters(&mass, m, 0, 0, 0, ixx, ixx, izz, 0, 0, 0);
  return mass;
}

std::vector<Drop> drops() {
  return {
      {"sphere", std::make_shared<unidist::Sphere>(0.5), 0.5, 1.0, sphereMass(1, 0.5)},
      {"nurbs sphere", nurbsSphere(), 1.0, 2.0, sphereMass(1, 1.0)},
      {"mesh box", meshBox(0.4), 0.4, 0.8, boxMass(1, 0.4)},
      {"cloud box", cloudBox(0.3), 0.3, 0.6, boxMass(1, 0.3)},
      {"torus", std::make_shared<unidist::Torus>(1.0, 0.25), 0.25, 2.5, torusMass(1, 1.0, 0.25)},
  };
}

/// Drops a model from 0.2 above its rest on a support whose top is at `top`, runs 10 s, checks the rest height
/// at 10 s and the drift since 5 s.
class OdeDrop : public OdeWorldTest {
 protected:
  void dropOn(double top, const Drop& d) {
    dGeomID g = unidist::ode::createGeom(space, d.model);
    dBodyID b = attachBody(g, d.mass, Vec(0.01, -0.02, top + d.restAboveSupport + 0.2));
    run(5);
    const Vec at5 = odetest::position(b);
    run(5);
    const Vec at10 = odetest::position(b);
    const double expect = top + d.restAboveSupport;
    SCOPED_TRACE(d.name);
    EXPECT_NEAR(at10.z(), expect - layer, layer + 1e-3 * d.size) << d.name;
    EXPECT_LT((at10 - at5).norm(), 1e-4) << d.name;                      // no drift
    EXPECT_LT((at10.head<2>() - Eigen::Vector2d(0.01, -0.02)).norm(), 1e-3) << d.name;
    EXPECT_LT(odetest::linearVelocity(b).norm(), 1e-3) << d.name;
    std::cout << d.name << ": rest z = " << at10.z() << " (analytic " << expect << ", layer " << layer << ")\n";
    dGeomDestroy(g);
    dBodyDestroy(b);
  }
};

TEST_F(OdeDrop, OnOdePlane) {
  dCreatePlane(space, 0, 0, 1, 0);
  for (const Drop& d : drops()) dropOn(0, d);
}

TEST_F(OdeDrop, OnStaticOdeBox) {
  dGeomID box = dCreateBox(space, 6, 6, 1);
  dGeomSetPosition(box, 0, 0, 0.5);
  for (const Drop& d : drops()) dropOn(1, d);
}

TEST_F(OdeDrop, OnEachOther) {
  // A primitive sphere and a cloud box on a static unidist mesh box (top at z = 1).
  dGeomID table = unidist::ode::createGeom(space, meshBox(0.5));
  dGeomSetPosition(table, 0, 0, 0.5);
  const std::vector<Drop> d = drops();
  dropOn(1, d[0]);
  dropOn(1, d[3]);
  dGeomDestroy(table);
  // The torus on a static unidist box primitive (top at z = 0.5). (A ball resting in the torus's hole, touching
  // the tube along a circle, needs the core's sphere-inside-torus penetration search every step, which takes
  // tens of milliseconds per query today: docs/ode.md.)
  dGeomID ring = unidist::ode::createGeom(space, std::make_shared<unidist::Box>(Vec(3, 3, 0.5)));
  dropOn(0.5, d[4]);
  dGeomDestroy(ring);
}

TEST_F(OdeWorldTest, MixedStackStaysStanding) {
  dCreatePlane(space, 0, 0, 1, 0);
  struct Level {
    ModelPtr model;
    dMass mass;
    double z;
  };
  const std::vector<Level> levels = {
      {meshBox(0.5), boxMass(2, 0.5), 0.5},
      {cloudBox(0.3), boxMass(1, 0.3), 1.3},
      {std::make_shared<unidist::Box>(Vec(0.4, 0.4, 0.4)), boxMass(1.5, 0.4), 2.0},
      {std::make_shared<unidist::Cylinder>(0.25, 0.15), cylinderMass(0.5, 0.25, 0.15), 2.55},
  };
  std::vector<dBodyID> bodies;
  for (const Level& l : levels) bodies.push_back(attachBody(unidist::ode::createGeom(space, l.model), l.mass, Vec(0, 0, l.z)));
  run(5);
  for (std::size_t i = 0; i < levels.size(); ++i) {
    const Vec p = odetest::position(bodies[i]);
    EXPECT_NEAR(p.z(), levels[i].z, 4 * layer + 1e-3) << i;
    EXPECT_LT(p.head<2>().norm(), 1e-3) << i;
  }
}

// The same kind of bowl as an open mesh paraboloid (grid vertex at the bottom); the NURBS bowl of issue 6 follows.
TEST_F(OdeWorldTest, SphereSettlesInBowl) {
  dGeomID bowl = unidist::ode::createGeom(space, meshBowl(40));
  (void)bowl;
  dWorldSetDamping(world, 0.02, 0.02);  // ODE has no rolling resistance: damping lets the ball settle
  dBodyID ball = attachBody(unidist::ode::createGeom(space, std::make_shared<unidist::Sphere>(0.2)), sphereMass(0.3, 0.2),
                            Vec(0.4, 0.2, 0.5));
  run(12);
  const Vec p = odetest::position(ball);
  // The bowl's curvature radius at the bottom is 0.5 > 0.2: the ball touches near the single lowest point
  // (the facets around the bottom vertex sit at most 0.05² · 2 below the paraboloid).
  EXPECT_LT(p.head<2>().norm(), 0.02);
  EXPECT_NEAR(p.z(), 0.2 - layer, layer + 2e-3);
  EXPECT_LT(odetest::linearVelocity(ball).norm(), 0.02);
}

// Issue 6: the open NURBS bowl of the Bullet plugin's test (a hemisphere of radius 2, bottom at z = 0).
TEST_F(OdeWorldTest, SphereSettlesAtTheBottomOfANurbsBowl) {
  dGeomID bowl = unidist::ode::createGeom(space, test_models::nurbsBowl(2));
  dGeomSetPosition(bowl, 0, 0, 2);
  dBodyID ball = attachBody(unidist::ode::createGeom(space, std::make_shared<unidist::Sphere>(0.5)), sphereMass(1, 0.5),
                            Vec(0.6, 0.2, 1.2));
  dBodySetLinearDamping(ball, 0.02);
  dBodySetAngularDamping(ball, 0.02);
  const auto t0 = std::chrono::steady_clock::now();
  run(12);
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const Vec p = odetest::position(ball);
  EXPECT_NEAR(p.z(), 0.5 - layer, layer + 5e-3);
  EXPECT_LT(p.head<2>().norm(), 0.05);
  EXPECT_LT(odetest::linearVelocity(ball).norm(), 0.02);
  std::cout << "ball in NURBS bowl after 12 s: " << p.transpose() << ", |v| " << odetest::linearVelocity(ball).norm()
            << ", " << wall << " s wall clock\n";
}

// A genus-1 mesh block must not be hulled: the peg drops through its square hole onto the floor.
TEST_F(OdeWorldTest, PegDropsThroughTheHoleOfAMeshBlock) {
  dCreatePlane(space, 0, 0, 1, 0);
  dGeomID block = unidist::ode::createGeom(space, test_models::blockWithHole(1, 0.3, 1));
  (void)block;  // static: no body, at the origin
  dBodyID peg = attachBody(unidist::ode::createGeom(space, std::make_shared<unidist::Box>(Vec(0.2, 0.2, 0.6))),
                           boxMass(1, 0.2), Vec(0.02, 0, 1.9));
  run(3);
  const Vec p = odetest::position(peg);
  EXPECT_NEAR(p.z(), 0.6 - layer, layer + 3e-3) << "the peg stands on the floor inside the hole, not on a hull";
  EXPECT_LT(std::abs(p.x()), 0.1);
}

TEST_F(OdeWorldTest, QuickStepAlsoRests) {
  dCreatePlane(space, 0, 0, 1, 0);
  dBodyID b = attachBody(unidist::ode::createGeom(space, nurbsSphere()), sphereMass(1, 1), Vec(0, 0, 1.3));
  run(5, true);
  EXPECT_NEAR(odetest::position(b).z(), 1 - layer, layer + 2e-3);
}

}  // namespace
