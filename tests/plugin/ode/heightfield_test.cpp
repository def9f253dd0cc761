// ODE heightfields described with unidist::ode::describeHeightfield: ODE's frame and triangulation, both dCollide
// argument orders, bodies resting on a flat field, the contact normal on a slope, the depth against a bumpy field
// checked by brute force over the grid triangles, bad input, and undescribed / forgotten data (no contacts).
#include "ode_fixture.h"
#include "unidist/adapters/load.h"
#include "unidist/ode/heightfield.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <iostream>
#include <limits>
#include <random>
#include <string>

namespace {

using odetest::collide;
using odetest::deepest;
using odetest::OdeTest;
using odetest::OdeWorldTest;
using odetest::Vec;
using Iso = Eigen::Isometry3d;
using ModelPtr = std::shared_ptr<const unidist::Model>;

Vec normalOf(const dContactGeom& c) { return Vec(c.normal[0], c.normal[1], c.normal[2]); }

dGeomID unidistGeom(ModelPtr m, double tol = 1e-10) {
  dGeomID g = unidist::ode::createGeom(nullptr, std::move(m));
  unidist::ode::setTolerance(g, tol);
  return g;
}

/// ODE's heightfield is Y-up; this turns local y into world z (local z into world −y).
Eigen::Matrix3d yUpToZUp() {
  Eigen::Matrix3d R;
  R << 1, 0, 0, 0, 0, -1, 0, 1, 0;
  return R;
}

/// A heightfield built for ODE and described to unidist with the same numbers (thickness 1, scale 1, offset 0).
struct Field {
  std::vector<double> heights;
  int ws = 0, ds = 0;
  double width = 0, depth = 0;
  dHeightfieldDataID data = nullptr;
  dGeomID geom = nullptr;

  Field(std::vector<double> h, int widthSamples, int depthSamples, double w, double d, dSpaceID space = nullptr,
        bool placeable = true)
      : heights(std::move(h)), ws(widthSamples), ds(depthSamples), width(w), depth(d) {
    data = dGeomHeightfieldDataCreate();
    dGeomHeightfieldDataBuildDouble(data, heights.data(), 0, width, depth, ws, ds, 1, 0, 1, 0);
    unidist::ode::describeHeightfield(data, heights.data(), width, depth, ws, ds, 1, 0, 1, 0);
    geom = dCreateHeightfield(space, data, placeable ? 1 : 0);
    if (placeable) odetest::setRotation(geom, yUpToZUp());
  }
  ~Field() {
    dGeomDestroy(geom);
    unidist::ode::forgetHeightfield(data);
    dGeomHeightfieldDataDestroy(data);
  }
  Field(const Field&) = delete;
  Field& operator=(const Field&) = delete;

  /// Local (Y-up) position of sample (i, j).
  Vec sample(int i, int j) const {
    return Vec(-0.5 * width + width * i / (ws - 1), heights[static_cast<std::size_t>(i + j * ws)],
               -0.5 * depth + depth * j / (ds - 1));
  }
};

/// 9 × 9 samples over 8 × 8 (spacing 1): flat at 0, or the slope h = x/4.
std::vector<double> gridHeights(bool slope) {
  std::vector<double> h;
  for (int j = 0; j < 9; ++j)
    for (int i = 0; i < 9; ++i) h.push_back(slope ? (-4 + i) / 4.0 : 0.0);
  return h;
}

// --- Independent reference: closest point on a triangle (Voronoi regions, written for this test). ---
Vec closestOnTriangle(const Vec& p, const Vec& a, const Vec& b, const Vec& c) {
  const Vec ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return a;
  const Vec bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return b;
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return a + d1 / (d1 - d3) * ab;
  const Vec cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return c;
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return a + d2 / (d2 - d6) * ac;
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
  const double denom = 1 / (va + vb + vc);
  return a + ab * (vb * denom) + ac * (vc * denom);
}

/// Distance from a local point to the field's triangulated surface (ODE's split: diagonal (i+1, j)–(i, j+1)),
/// by brute force over every grid triangle; `closest` receives the nearest surface point.
double surfaceDistance(const Field& f, const Vec& q, Vec* closest) {
  double best = std::numeric_limits<double>::infinity();
  for (int j = 0; j + 1 < f.ds; ++j)
    for (int i = 0; i + 1 < f.ws; ++i) {
      const Vec a = f.sample(i, j), b = f.sample(i + 1, j), c = f.sample(i, j + 1), d = f.sample(i + 1, j + 1);
      for (const Vec& p : {closestOnTriangle(q, a, b, c), closestOnTriangle(q, d, b, c)})
        if ((p - q).norm() < best) best = (p - q).norm(), *closest = p;
    }
  return best;
}

TEST_F(OdeTest, HeightfieldMeshFollowsOdesFrameAndTriangulation) {
  // The same asymmetric 3 × 2 field as the probe of ODE's own ray collider (docs/ode.md): the model's surface
  // heights must equal ODE's at sample points and inside both triangles of a cell.
  const std::vector<double> h = {0, 1, 2, 3, 7, 5};
  Field f(h, 3, 2, 2, 1);
  const auto mesh = unidist::ode::heightfieldModel(f.data);
  ASSERT_TRUE(mesh);
  EXPECT_TRUE(mesh->isSolid());
  EXPECT_GT(mesh->stats().signedVolume, 0);
  dGeomID ray = dCreateRay(nullptr, 100);
  odetest::setRotation(f.geom, Eigen::Matrix3d::Identity());  // local = world for the probe
  std::mt19937_64 rng(3);
  std::uniform_real_distribution<double> ux(-0.99, 0.99), uz(-0.49, 0.49);
  double worst = 0;
  for (int k = 0; k < 200; ++k) {
    const double x = ux(rng), z = uz(rng);
    dGeomRaySet(ray, x, 50, z, 0, -1, 0);
    dContactGeom c;
    ASSERT_EQ(dCollide(ray, f.geom, 1, &c, sizeof c), 1);
    const Vec odeHit(c.pos[0], c.pos[1], c.pos[2]);
    worst = std::max(worst, std::abs(mesh->closestPoint(odeHit).signedDistance));
  }
  // ODE's ray hits lie on the model's surface (ODE's ray–heightfield is not exact: a few 1e-4 at most).
  EXPECT_LT(worst, 2e-3);
  std::cout << "ODE ray hits vs model surface: worst distance " << worst << "\n";
  // Exact check of the split: the cell centre (−0.5, 0) lies on the diagonal from sample (1, 0) (height 1) to
  // (0, 1) (height 3), height 2, not on the other diagonal's (0 + 7)/2; the point above the other triangle's
  // centroid too.
  EXPECT_NEAR(mesh->closestPoint(Vec(-0.5, 2, 0)).signedDistance, 0, 1e-12);
  EXPECT_NEAR(mesh->closestPoint(Vec(-1.0 / 3, (1 + 3 + 7) / 3.0, 1.0 / 6)).signedDistance, 0, 1e-12);
  EXPECT_NEAR(mesh->closestPoint(Vec(-2.0 / 3, (0 + 1 + 3) / 3.0, -1.0 / 6)).signedDistance, 0, 1e-12);
  dGeomDestroy(ray);
}

void expectMirrored(dGeomID u, dGeomID field, double depthTol) {
  const auto ab = collide(u, field), ba = collide(field, u);
  ASSERT_FALSE(ab.empty());
  ASSERT_EQ(ab.size(), ba.size());
  for (std::size_t i = 0; i < ab.size(); ++i) {
    EXPECT_NEAR(ab[i].depth, ba[i].depth, depthTol);
    EXPECT_LT((normalOf(ab[i]) + normalOf(ba[i])).norm(), 1e-12);
    EXPECT_EQ(ab[i].g1, u);
    EXPECT_EQ(ba[i].g1, field);
  }
}

TEST_F(OdeTest, HeightfieldArgumentOrdersMirrorNormalsAndKeepDepths) {
  for (bool slope : {false, true}) {
    Field f(gridHeights(slope), 9, 9, 8, 8);
    std::mt19937_64 rng(slope ? 5 : 4);
    std::uniform_real_distribution<double> u(-2.5, 2.5), dip(0.001, 0.05);
    const ModelPtr sphere = std::make_shared<unidist::Sphere>(0.5);
    const ModelPtr box = std::make_shared<unidist::Box>(Vec(0.3, 0.4, 0.2));
    for (const ModelPtr& m : {sphere, box}) {
      dGeomID g = unidistGeom(m);
      for (int k = 0; k < 10; ++k) {
        const double x = u(rng), y = u(rng);
        const double ground = slope ? x / 4 : 0;  // world: local x = world x, local y = world z
        const double reach = m->type() == unidist::ModelType::Sphere ? 0.5 : 0.2;
        // Upright, dipping `dip` into the ground (vertical dip; on the slope the penetration is smaller).
        dGeomSetPosition(g, x, y, ground + reach - dip(rng));
        SCOPED_TRACE(std::string(slope ? "slope " : "flat ") + std::to_string(k));
        expectMirrored(g, f.geom, 1e-12);
        if (!slope) {
          const auto cs = collide(g, f.geom);
          EXPECT_LT((normalOf(deepest(cs)) - Vec(0, 0, 1)).norm(), 1e-9);  // from the field into the body
          const double z = dGeomGetPosition(g)[2];
          EXPECT_NEAR(deepest(cs).depth, reach - z, 1e-9);
        }
      }
      dGeomDestroy(g);
    }
  }
}

TEST_F(OdeTest, HeightfieldSlopeNormal) {
  Field f(gridHeights(true), 9, 9, 8, 8);
  const Vec n = Vec(-0.25, 0, 1).normalized();  // world normal of z = x/4
  dGeomID ball = unidistGeom(std::make_shared<unidist::Sphere>(0.5));
  for (double x : {-2.3, -0.7, 0.4, 1.9}) {
    const Vec onSlope(x, 0.3 * x, x / 4);
    const Vec c = onSlope + (0.5 - 0.01) * n;
    dGeomSetPosition(ball, c.x(), c.y(), c.z());
    const auto cs = collide(ball, f.geom);
    ASSERT_FALSE(cs.empty());
    EXPECT_LT((normalOf(deepest(cs)) - n).norm(), 1e-6) << x;
    EXPECT_NEAR(deepest(cs).depth, 0.01, 1e-8) << x;
    const auto rev = collide(f.geom, ball);
    ASSERT_FALSE(rev.empty());
    EXPECT_LT((normalOf(deepest(rev)) + n).norm(), 1e-6) << x;
  }
  dGeomDestroy(ball);
}

TEST_F(OdeTest, HeightfieldBumpyDepthMatchesBruteForce) {
  std::mt19937_64 rng(17);
  std::uniform_real_distribution<double> uh(0, 0.6);
  std::vector<double> h;
  for (int k = 0; k < 6 * 5; ++k) h.push_back(uh(rng));
  Field f(h, 6, 5, 5, 4);
  // Any pose: the depth does not depend on it.
  Iso X = Iso::Identity();
  X.linear() = Eigen::AngleAxisd(0.7, Vec(1, 2, 3).normalized()).toRotationMatrix();
  X.translation() = Vec(1, -2, 0.5);
  odetest::setPose(f.geom, X);
  std::uniform_real_distribution<double> ux(-1.4, 1.4), uz(-0.9, 0.9), above(0.15, 0.4), dip(0.001, 0.05);
  double worst = 0;
  int checked = 0;
  for (int k = 0; k < 40; ++k) {
    const double x = ux(rng), z = uz(rng);
    Vec top;
    surfaceDistance(f, Vec(x, 10, z), &top);  // some surface point near (x, z)
    const Vec c(x, 0.8 + above(rng), z);     // above every sample (max 0.6)
    Vec p;
    const double d = surfaceDistance(f, c, &p);
    const double r = d + dip(rng);
    if (std::abs(c.x()) + r > 2.5 || std::abs(c.z()) + r > 2) continue;  // keep the walls out of reach
    dGeomID ball = unidistGeom(std::make_shared<unidist::Sphere>(r));
    const Vec cw = X * c;
    dGeomSetPosition(ball, cw.x(), cw.y(), cw.z());
    const auto cs = collide(ball, f.geom);
    ASSERT_FALSE(cs.empty()) << k;
    const double err = std::abs(deepest(cs).depth - (r - d));
    worst = std::max(worst, err);
    EXPECT_LT(err, 1e-9) << k;
    // The normal is first-order in the closest points' error (the depth second-order): 1e-4 here.
    EXPECT_LT((normalOf(deepest(cs)) - X.linear() * (c - p).normalized()).norm(), 1e-4) << k;
    dGeomDestroy(ball);
    ++checked;
  }
  EXPECT_GT(checked, 20);
  std::cout << "bumpy heightfield: " << checked << " spheres, worst depth error " << worst << "\n";
}

TEST_F(OdeTest, HeightfieldRejectsBadInput) {
  using unidist::InputError;
  using unidist::ode::describeHeightfield;
  dHeightfieldDataID d = dGeomHeightfieldDataCreate();
  std::vector<double> h(9, 0.0);
  EXPECT_THROW(describeHeightfield(nullptr, h.data(), 1, 1, 3, 3, 1, 0, 1, 0), InputError);
  EXPECT_THROW(describeHeightfield(d, nullptr, 1, 1, 3, 3, 1, 0, 1, 0), InputError);
  EXPECT_THROW(describeHeightfield(d, h.data(), 1, 1, 1, 3, 1, 0, 1, 0), InputError);
  EXPECT_THROW(describeHeightfield(d, h.data(), 1, 1, 3, 1, 1, 0, 1, 0), InputError);
  EXPECT_THROW(describeHeightfield(d, h.data(), 0, 1, 3, 3, 1, 0, 1, 0), InputError);
  EXPECT_THROW(describeHeightfield(d, h.data(), 1, -1, 3, 3, 1, 0, 1, 0), InputError);
  EXPECT_THROW(describeHeightfield(d, h.data(), 1, 1, 3, 3, 1, 0, 0, 0), InputError);
  EXPECT_THROW(describeHeightfield(d, h.data(), 1, 1, 3, 3, NAN, 0, 1, 0), InputError);
  EXPECT_THROW(describeHeightfield(d, h.data(), 1, 1, 3, 3, 1, INFINITY, 1, 0), InputError);
  try {
    describeHeightfield(d, h.data(), 1, 1, 3, 3, 1, 0, 1, 1);
    ADD_FAILURE() << "wrap accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("not supported"), std::string::npos) << e.what();
  }
  h[4] = NAN;
  try {
    describeHeightfield(d, h.data(), 1, 1, 3, 3, 1, 0, 1, 0);
    ADD_FAILURE() << "NaN accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("sample 4"), std::string::npos) << e.what();
  }
  EXPECT_EQ(unidist::ode::heightfieldModel(d), nullptr);  // nothing registered by a failed call
  dGeomHeightfieldDataDestroy(d);
}

TEST_F(OdeTest, UndescribedOrForgottenHeightfieldGivesNoContacts) {
  std::vector<double> h(9, 0.0);
  dHeightfieldDataID d = dGeomHeightfieldDataCreate();
  dGeomHeightfieldDataBuildDouble(d, h.data(), 0, 2, 2, 3, 3, 1, 0, 1, 0);
  dGeomID field = dCreateHeightfield(nullptr, d, 0);  // non-placeable: local frame = world (Y up)
  dGeomID ball = unidistGeom(std::make_shared<unidist::Sphere>(0.5));
  dGeomSetPosition(ball, 0.1, 0.45, 0.2);
  EXPECT_TRUE(collide(ball, field).empty());
  EXPECT_TRUE(collide(field, ball).empty());
  EXPECT_THROW(unidist::modelFromOdeGeom(field), unidist::InputError);
  const std::size_t before = unidist::ode::heightfieldCount();
  unidist::ode::describeHeightfield(d, h.data(), 2, 2, 3, 3, 1, 0, 1, 0);
  EXPECT_EQ(unidist::ode::heightfieldCount(), before + 1);
  auto cs = collide(ball, field);
  ASSERT_FALSE(cs.empty());
  EXPECT_NEAR(deepest(cs).depth, 0.05, 1e-9);
  EXPECT_LT((normalOf(deepest(cs)) - Vec(0, 1, 0)).norm(), 1e-9);
  // Re-described with another offset (same data id, same bounds shape): the new model is used at once.
  unidist::ode::describeHeightfield(d, h.data(), 2, 2, 3, 3, 1, 0.02, 1, 0);
  cs = collide(ball, field);
  ASSERT_FALSE(cs.empty());
  EXPECT_NEAR(deepest(cs).depth, 0.07, 1e-9);
  unidist::ode::forgetHeightfield(d);
  EXPECT_EQ(unidist::ode::heightfieldCount(), before);
  EXPECT_TRUE(collide(ball, field).empty());
  EXPECT_TRUE(unidist::ode::lastError().empty() || unidist::ode::lastError().find("heightfield") == std::string::npos);
  dGeomDestroy(ball);
  dGeomDestroy(field);
  dGeomHeightfieldDataDestroy(d);
}

/// Drops on a flat 9 × 9 field (world z = 0 at the top, 8 × 8 wide) rest at the analytic height.
class OdeHeightfieldDrop : public OdeWorldTest {
 protected:
  void dropOn(const char* name, ModelPtr model, const dMass& mass, double rest, double size) {
    Field f(gridHeights(false), 9, 9, 8, 8, space);
    dGeomID g = unidist::ode::createGeom(space, std::move(model));
    dBodyID b = attachBody(g, mass, Vec(0.01, -0.02, rest + 0.2));
    run(5);
    const Vec at5 = odetest::position(b);
    run(5);
    const Vec at10 = odetest::position(b);
    EXPECT_NEAR(at10.z(), rest - layer, layer + 1e-3 * size) << name;
    EXPECT_LT((at10 - at5).norm(), 1e-4) << name;
    EXPECT_LT((at10.head<2>() - Eigen::Vector2d(0.01, -0.02)).norm(), 1e-3) << name;
    EXPECT_LT(odetest::linearVelocity(b).norm(), 1e-3) << name;
    std::cout << name << " on heightfield: rest z = " << at10.z() << " (analytic " << rest << ", layer " << layer
              << "), drift 5-10 s " << (at10 - at5).norm() << ", max depth " << maxDepth << "\n";
    dGeomDestroy(g);
    dBodyDestroy(b);
  }
};

TEST_F(OdeHeightfieldDrop, BoxRestsOnFlatField) {
  dMass m;
  dMassSetBoxTotal(&m, 1, 0.8, 0.8, 0.8);
  dropOn("box", std::make_shared<unidist::Box>(Vec(0.4, 0.4, 0.4)), m, 0.4, 0.8);
}

TEST_F(OdeHeightfieldDrop, NurbsSphereRestsOnFlatField) {
  dMass m;
  dMassSetSphereTotal(&m, 1, 1);
  const std::string path = std::string(UNIDIST_SHARED_DIR) + "/acceptance/models/sphere_nurbs.unurbs.json";
  dropOn("NURBS sphere", unidist::loadModel(path), m, 1.0, 2.0);
}

}  // namespace
