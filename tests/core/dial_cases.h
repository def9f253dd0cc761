// The fixed inputs of the tolerance dial (tests/bench/dial_bench.cpp, tests/core/dial_monotone_test.cpp): for
// every pair of model kinds (primitive, mesh, point cloud, NURBS) a family of posed pairs whose true signed
// distance is known independently of the library:
//  * convex pairs apart: B's lowest point along n is placed at A's highest plus gap·n, so the distance is the gap;
//  * a capsule is a segment grown by its radius r, so a capsule whose segment is placed at gap g < r from a
//    convex solid penetrates it by exactly r − g (the Minkowski difference grows by the ball);
//  * a ball (centre c, radius R) against a convex solid S: sd_S(c) − R, apart or not; against a torus (core
//    circle C, tube a): dist(c, C) − a − R while a + R is below the torus's major radius;
//  * the meshes are a box split into a grid (its surface is the box itself) and a tessellated torus (truth
//    computed on the triangles themselves by brute force, tests/core/dial_oracles.h);
//  * the clouds are points of a sphere and a torus: brute force over every point.
// Poses come from fixed seeds; `perKind` poses are drawn for each kind of pair in a family.
#pragma once

#include "bench/nurbs_truth.h"
#include "core/dial_oracles.h"
#include "core/nurbs_fixtures.h"
#include "unidist/distance.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <functional>
#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace dial {

/// One model as the library sees it and as a peer library can rebuild it.
struct Geometry {
  enum class Kind { Primitive, Mesh, Cloud, Nurbs };
  Kind kind;
  std::string name;
  oracle::Shape shape;                          // Primitive (and the exact shape of the grid box mesh)
  Soup soup;                                    // Mesh: vertices and triangles; Cloud: vertices
  std::vector<unidist::NurbsSurface> surfaces;  // Nurbs: one closed surface (a solid)
  std::shared_ptr<const unidist::Model> model;
};
using GeometryPtr = std::shared_ptr<const Geometry>;

struct Case {
  std::string what;  // the kind of pair, e.g. "box-capsule"
  GeometryPtr a, b;
  Pose Xa, Xb;
  double truth;       // exact signed distance
  bool penetrating;   // truth < 0
  double size;        // the larger posed bounding-box diagonal (the library's default tolerance / 1e-9)
};

struct Family {
  std::string name;
  std::vector<Case> cases;
};

inline GeometryPtr primitive(const oracle::Shape& s) {
  auto g = std::make_shared<Geometry>();
  g->kind = Geometry::Kind::Primitive;
  g->name = s.kind;
  g->shape = s;
  if (s.kind == "sphere") g->model = std::make_shared<unidist::Sphere>(s.p0);
  if (s.kind == "box") g->model = std::make_shared<unidist::Box>(Vec(s.p0, s.p1, s.p2));
  if (s.kind == "capsule") g->model = std::make_shared<unidist::Capsule>(s.p0, s.p1);
  if (s.kind == "cylinder") g->model = std::make_shared<unidist::Cylinder>(s.p0, s.p1);
  if (s.kind == "cone") g->model = std::make_shared<unidist::Cone>(s.p0, s.p1);
  if (s.kind == "torus") g->model = std::make_shared<unidist::Torus>(s.p0, s.p1);
  return g;
}

inline GeometryPtr mesh(const std::string& name, Soup soup, const oracle::Shape& exact = {}) {
  auto g = std::make_shared<Geometry>();
  g->kind = Geometry::Kind::Mesh;
  g->name = name;
  g->shape = exact;
  g->model = std::make_shared<unidist::TriangleMesh>(soup.vertices, soup.triangles);
  g->soup = std::move(soup);
  return g;
}

inline GeometryPtr cloud(const std::string& name, std::vector<Vec> points) {
  auto g = std::make_shared<Geometry>();
  g->kind = Geometry::Kind::Cloud;
  g->name = name;
  g->model = std::make_shared<unidist::PointCloud>(points);
  g->soup.vertices = std::move(points);
  return g;
}

inline GeometryPtr nurbs(const std::string& name, const unidist::NurbsSurface& s) {
  auto g = std::make_shared<Geometry>();
  g->kind = Geometry::Kind::Nurbs;
  g->name = name;
  g->surfaces = {s};
  g->model = std::make_shared<unidist::NurbsModel>(g->surfaces, true);
  return g;
}

/// Every model the families use, built once.
struct Library {
  const double capsuleRadius = 0.2, sphereRadius = 0.5, smallRadius = 0.35, torusR = 0.8, torusA = 0.2;
  const oracle::Shape box{"box", 0.5, 0.35, 0.25}, box2{"box", 0.3, 0.4, 0.2}, cylinder{"cylinder", 0.4, 0.3},
      cone{"cone", 0.45, 0.4}, capsule{"capsule", 0.2, 0.45}, capsuleCore{"capsule", 0, 0.45},
      torus{"torus", 0.8, 0.2}, ball{"sphere", 0.3};
  GeometryPtr pBox = primitive(box), pCylinder = primitive(cylinder), pCone = primitive(cone),
              pCapsule = primitive(capsule), pTorus = primitive(torus), pBall = primitive(ball);
  GeometryPtr meshBox = mesh("grid box", meshfix::gridBox(Vec(box.p0, box.p1, box.p2), 4), box);
  GeometryPtr meshBox2 = mesh("grid box 2", meshfix::gridBox(Vec(box2.p0, box2.p1, box2.p2), 3), box2);
  GeometryPtr meshTorus = mesh("torus mesh", meshfix::torus(torusR, torusA, 32, 16));
  GeometryPtr cloudSphere = cloud("sphere cloud", spherePoints(0.5, 1000));
  GeometryPtr cloudTorus = cloud("torus cloud", torusPoints(torusR, torusA, 1000));
  GeometryPtr nurbsSphere = nurbs("NURBS sphere", nurbs_fixtures::sphereSurface(sphereRadius));
  GeometryPtr nurbsSmall = nurbs("NURBS sphere 0.35", nurbs_fixtures::sphereSurface(smallRadius));
  GeometryPtr nurbsTorus = nurbs("NURBS torus", nurbs_fixtures::torusSurface(torusR, torusA));
};

inline Case makeCase(const std::string& what, const GeometryPtr& a, const Pose& Xa, const GeometryPtr& b,
                     const Pose& Xb, double truth) {
  const double size = unidist::defaultTolerance(*a->model, Xa, *b->model, Xb) / 1e-9;
  return {what, a, b, Xa, Xb, truth, truth < 0, size};
}

inline Pose rotation(std::mt19937_64& rng) {
  Pose X = oracle::randomPose(rng, 0);
  X.translation().setZero();
  return X;
}

inline Pose at(std::mt19937_64& rng, const Vec& t) {
  Pose X = rotation(rng);
  X.translation() = t;
  return X;
}

inline double uniform(std::mt19937_64& rng, double lo, double hi) {
  return std::uniform_real_distribution<double>(lo, hi)(rng);
}

/// B turned by Xb's rotation, moved so that its lowest point along n lies gap·n above A's highest.
inline void placeAtGap(const oracle::Shape& a, const Pose& Xa, const oracle::Shape& b, Pose& Xb, const Vec& n, double gap) {
  Xb.translation().setZero();
  Xb.translation() = oracle::worldSupport(a, Xa, n) + gap * n - oracle::worldSupport(b, Xb, -n);
}

/// Convex A and B apart by a gap log-uniform in [1e-3, 0.3] (truth: the gap).
inline Case apart(std::mt19937_64& rng, const GeometryPtr& a, const oracle::Shape& sa, const GeometryPtr& b,
                  const oracle::Shape& sb) {
  const Pose Xa = oracle::randomPose(rng, 0.5);
  Pose Xb = rotation(rng);
  const double gap = std::pow(10.0, uniform(rng, -3, std::log10(0.3)));
  placeAtGap(sa, Xa, sb, Xb, oracle::randomUnit(rng), gap);
  return makeCase(a->name + "-" + b->name, a, Xa, b, Xb, gap);
}

/// A convex solid and the capsule, its segment 0.02–0.15 from the solid: depth r − gap.
inline Case capsuleInto(std::mt19937_64& rng, const Library& L, const GeometryPtr& a, const oracle::Shape& sa) {
  const Pose Xa = oracle::randomPose(rng, 0.5);
  Pose Xb = rotation(rng);
  const double gap = uniform(rng, 0.02, 0.15);
  placeAtGap(sa, Xa, L.capsuleCore, Xb, oracle::randomUnit(rng), gap);
  return makeCase(a->name + "-capsule", a, Xa, L.pCapsule, Xb, gap - L.capsuleRadius);
}

/// A ball's centre t (in [lo, hi]) beyond a convex solid's support point along a random direction.
inline Vec beyond(std::mt19937_64& rng, const oracle::Shape& s, const Pose& X, double lo, double hi) {
  const Vec n = oracle::randomUnit(rng);
  return oracle::worldSupport(s, X, n) + uniform(rng, lo, hi) * n;
}

/// Draws random poses until one qualifies (a brute-force truth decides; at most 100 tries) and adds its case.
inline void drawOne(std::vector<Case>& out, const std::function<std::optional<Case>()>& draw) {
  for (int tries = 0; tries < 100; ++tries)
    if (std::optional<Case> c = draw()) {
      out.push_back(std::move(*c));
      return;
    }
}

/// A pose of random rotation whose translation is uniform in [-xy, xy]^2 x [-0.6, 0.6] (tori side by side).
inline Pose nearby(std::mt19937_64& rng, double xy) {
  return at(rng, Vec(uniform(rng, -xy, xy), uniform(rng, -xy, xy), uniform(rng, -0.6, 0.6)));
}

inline Circle torusCircle(const Library& L, const Pose& X) {
  return {X.translation(), X.linear().col(2), L.torusR};
}

/// A point about `rho` from the core circle of the torus posed at X (exactly rho unless it passes the axis).
inline Vec nearTorus(std::mt19937_64& rng, const Library& L, const Pose& X, double rho) {
  const double theta = uniform(rng, 0, 2 * M_PI), phi = uniform(rng, 0, 2 * M_PI);
  const double r = L.torusR + rho * std::cos(phi);
  return X * Vec(r * std::cos(theta), r * std::sin(theta), rho * std::sin(phi));
}

inline double cloudMin(const Soup& cloud, const Pose& X, const std::function<double(const Vec&)>& f) {
  double best = std::numeric_limits<double>::infinity();
  for (const Vec& p : cloud.vertices) best = std::min(best, f(X * p));
  return best;
}

}  // namespace dial
