// The extremes suite's models: ideal shapes and degenerate inputs in the four representations (built here; their
// support maps, signed distances and the pair oracle are in extremes_oracles.cpp).
#include "core/extremes_models.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <map>

namespace extremes {
namespace {

using nurbs_fixtures::boxPatches;
using nurbs_fixtures::Net;
using unidist::NurbsModel;
using unidist::NurbsSurface;

std::shared_ptr<const unidist::Model> nurbsModel(std::vector<NurbsSurface> surfaces, bool solid) {
  return std::make_shared<NurbsModel>(std::move(surfaces), solid);
}

/// Points spread over the sphere of radius r (Fibonacci lattice).
std::vector<Vec> spherePoints(double r, int n) {
  std::vector<Vec> out;
  for (const Vec& u : oracle::sphereDirections(n)) out.push_back(r * u);
  return out;
}

/// The NURBS sphere of radius r: the meridian revolved about z by a rational quadratic circle (9 control points of
/// nurbs_fixtures::unitCircle(), or that circle reparametrised), over the u knots given.
NurbsSurface sphereOfCircle(double r, const std::vector<nurbs_fixtures::Point2W>& circle, std::vector<double> uKnots) {
  const double h = std::sqrt(0.5);
  const std::vector<nurbs_fixtures::Point2W> meridian = {{0, -1, 1}, {1, -1, h}, {1, 0, 1}, {1, 1, h}, {0, 1, 1}};
  Net net;
  for (const auto& c : circle) {
    net.emplace_back();
    for (const auto& p : meridian) net.back().emplace_back(r * c.a * p.a, r * c.b * p.a, r * p.b, c.w * p.w);
  }
  return {2, 2, std::move(uKnots), {0, 0, 0, .5, .5, 1, 1, 1}, net};
}

Body nurbsBall(double r, NurbsSurface s, std::string label) {
  Body b;
  b.family = Family::Nurbs;
  b.kind = Kind::Ball;
  b.radius = r;
  b.model = nurbsModel({std::move(s)}, true);
  b.label = std::move(label);
  return b;
}

/// Flat square [-s, s]^2 at z = 0, n x n quads, two triangles each (open).
meshfix::Soup flatSheet(double s, int n) {
  return meshfix::heightSheet(s, n, [](double, double) { return 0.0; });
}

/// Biquadratic flat square with uneven weights (the image is still the whole square: its boundary curves have
/// collinear control points and positive weights).
NurbsSurface flatNurbsSheet(double s) {
  Net net(3);
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      net[static_cast<std::size_t>(i)].emplace_back(s * (i - 1), s * (j - 1), 0.0, 0.5 + 0.4 * i + 0.3 * j * j);
  return {2, 2, {0, 0, 0, 1, 1, 1}, {0, 0, 0, 1, 1, 1}, net};
}

}  // namespace


void setMesh(Body& b, meshfix::Soup s) {
  b.points = s.vertices;
  b.model = std::make_shared<unidist::TriangleMesh>(s.vertices, s.triangles);
  b.soup = std::move(s);
}

void setCloud(Body& b, std::vector<Vec> points) {
  b.model = std::make_shared<unidist::PointCloud>(points);
  b.points = std::move(points);
}

const char* familyName(Family f) {
  switch (f) {
    case Family::Prim: return "prim";
    case Family::Mesh: return "mesh";
    case Family::Cloud: return "cloud";
    case Family::Nurbs: return "nurbs";
  }
  return "?";
}

std::string pairName(Family a, Family b) {
  if (static_cast<int>(a) > static_cast<int>(b)) std::swap(a, b);
  return std::string(familyName(a)) + "-" + familyName(b);
}

Body ball(Family f, double r) {
  Body b;
  b.family = f;
  b.kind = Kind::Ball;
  b.radius = r;
  switch (f) {
    case Family::Prim:
      b.model = std::make_shared<unidist::Sphere>(r);
      b.label = "sphere";
      break;
    case Family::Mesh:
      setMesh(b, meshfix::icosphere(r, 2));
      b.label = "icosphere(320)";
      break;
    case Family::Cloud:
      setCloud(b, spherePoints(r, 200));
      b.label = "sphere cloud(200)";
      break;
    case Family::Nurbs:
      b.model = nurbsModel({nurbs_fixtures::sphereSurface(r)}, true);
      b.label = "nurbs sphere";
      break;
  }
  return b;
}

Body box(Family f, const Vec& half) {
  Body b;
  b.family = f;
  b.kind = Kind::Box;
  b.half = half;
  switch (f) {
    case Family::Prim:
      b.model = std::make_shared<unidist::Box>(half);
      b.label = "box";
      break;
    case Family::Mesh:
      setMesh(b, meshfix::gridBox(half, 3));
      b.label = "grid box(108)";
      break;
    case Family::Cloud:
      setCloud(b, meshfix::gridBox(half, 6).vertices);
      b.label = "box lattice cloud";
      break;
    case Family::Nurbs:
      b.model = nurbsModel(boxPatches(half), true);
      b.label = "nurbs box(6 bilinear)";
      break;
  }
  return b;
}

Body sheet(Family f, double s) {
  Body b;
  b.family = f;
  b.kind = Kind::Sheet;
  b.radius = s;
  switch (f) {
    case Family::Prim:
      b.model = std::make_shared<unidist::Plane>(Vec::UnitZ(), 0.0);
      b.label = "half-space";
      break;
    case Family::Mesh:
      setMesh(b, flatSheet(s, 4));
      b.label = "flat mesh sheet";
      break;
    case Family::Cloud:
      setCloud(b, flatSheet(s, 10).vertices);
      b.label = "flat cloud grid";
      break;
    case Family::Nurbs:
      b.model = nurbsModel({flatNurbsSheet(s)}, false);
      b.label = "flat nurbs sheet";
      break;
  }
  return b;
}

Body thinBox(double halfSide, double halfThickness) {
  Body b = box(Family::Prim, Vec(halfSide, halfSide, halfThickness));
  b.label = "plate box(t=" + unidist::testing::sci(2 * halfThickness) + ")";
  return b;
}

Body needleCapsule(double radius, double halfLength) {
  Body b;
  b.family = Family::Prim;
  b.kind = Kind::Capsule;
  b.radius = radius;
  b.half = Vec(0, 0, halfLength);
  b.model = std::make_shared<unidist::Capsule>(radius, halfLength);
  b.label = "needle capsule";
  return b;
}

Body needleBox(const Vec& h) {
  // Every face is a fan from its centre over its boundary loop; every edge carries an extra vertex 1e-9 of the
  // edge from one end (the same vertex for both faces), so the fan has needle triangles 1e9 times longer than wide.
  meshfix::Soup s;
  auto corner = [&](int i, int j, int k) { return Vec(i ? h.x() : -h.x(), j ? h.y() : -h.y(), k ? h.z() : -h.z()); };
  std::map<std::pair<int, int>, std::uint32_t> edgePoint;
  auto cornerId = [](int i, int j, int k) { return i + 2 * j + 4 * k; };
  for (int c = 0; c < 8; ++c) s.vertices.push_back(corner(c & 1, (c >> 1) & 1, (c >> 2) & 1));
  auto needle = [&](int a, int b) {
    const auto key = std::minmax(a, b);
    auto it = edgePoint.find(key);
    if (it != edgePoint.end()) return it->second;
    const Vec p = s.vertices[static_cast<std::size_t>(key.first)], q = s.vertices[static_cast<std::size_t>(key.second)];
    s.vertices.push_back(p + 1e-9 * (q - p));
    return edgePoint[key] = static_cast<std::uint32_t>(s.vertices.size() - 1);
  };
  for (int axis = 0; axis < 3; ++axis)
    for (int side = 0; side < 2; ++side) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      // Corners counter-clockwise in (u, v), which faces +axis; reversed for the -axis face.
      std::vector<int> loop;
      for (auto [a, b] : {std::pair{0, 0}, {1, 0}, {1, 1}, {0, 1}}) {
        int idx[3];
        idx[axis] = side;
        idx[u] = a;
        idx[v] = b;
        loop.push_back(cornerId(idx[0], idx[1], idx[2]));
      }
      if (side == 0) std::reverse(loop.begin(), loop.end());
      std::vector<std::uint32_t> ring;
      for (std::size_t k = 0; k < 4; ++k) {
        ring.push_back(static_cast<std::uint32_t>(loop[k]));
        ring.push_back(needle(loop[k], loop[(k + 1) % 4]));
      }
      Vec centre = Vec::Zero();
      centre[axis] = side ? h[axis] : -h[axis];
      s.vertices.push_back(centre);
      const auto c = static_cast<std::uint32_t>(s.vertices.size() - 1);
      for (std::size_t k = 0; k < ring.size(); ++k) s.triangles.push_back({c, ring[k], ring[(k + 1) % ring.size()]});
    }
  // Degenerate triangles the mesh must drop: a repeated index, three exactly collinear points, a duplicate.
  s.vertices.push_back(Vec(0, -h.y(), -h.z()));  // midpoint of an x edge: exactly collinear with its ends
  const auto mid = static_cast<std::uint32_t>(s.vertices.size() - 1);
  s.triangles.push_back({0, 0, 1});
  s.triangles.push_back({0, mid, 1});
  s.triangles.push_back(s.triangles.front());
  Body b;
  b.family = Family::Mesh;
  b.kind = Kind::Box;
  b.half = h;
  b.label = "needle box mesh(" + std::to_string(s.triangles.size()) + ")";
  setMesh(b, std::move(s));
  return b;
}

Body duplicatePointBall(double r) {
  Body b = ball(Family::Cloud, r);
  std::vector<Vec> pts;
  for (const Vec& p : b.points) pts.insert(pts.end(), {p, p, p});
  for (int k = 0; k < 50; ++k) pts.push_back(b.points[17]);
  b.label = "sphere cloud with duplicates(" + std::to_string(pts.size()) + ")";
  setCloud(b, std::move(pts));
  return b;
}

Body fullMultiplicityBall(double r) {
  // The circle with its knot 0.5 at multiplicity 3 (= degree + 1): the point (-1, 0) is given twice, once
  // ending the first half and once starting the second; the two halves only meet there.
  std::vector<nurbs_fixtures::Point2W> circle = nurbs_fixtures::unitCircle();
  circle.insert(circle.begin() + 4, circle[4]);
  return nurbsBall(r, sphereOfCircle(r, circle, {0, 0, 0, .25, .25, .5, .5, .5, .75, .75, 1, 1, 1}),
                   "nurbs sphere, knot multiplicity p+1");
}

Body extremeWeightBall(double r, double span) {
  // A quadratic arc is unchanged when its end weights change and the middle weight keeps w1^2 / (w0 w2): the
  // quarter circles get end weights alternating span and 1/span (middle weights stay sqrt(1/2)).
  std::vector<nurbs_fixtures::Point2W> circle = nurbs_fixtures::unitCircle();
  for (std::size_t k = 0; k < circle.size(); k += 2) circle[k].w = (k / 2) % 2 == 0 ? span : 1 / span;
  return nurbsBall(r, sphereOfCircle(r, circle, nurbs_fixtures::circleKnots()),
                   "nurbs sphere, weights " + unidist::testing::sci(1 / span) + ".." + unidist::testing::sci(span));
}

Body singlePointCloud(const Vec& p) {
  Body b;
  b.family = Family::Cloud;
  b.kind = Kind::Point;
  b.label = "one-point cloud";
  setCloud(b, {p});
  return b;
}

Pose rotation(const Vec& axis, double angle) {
  Pose X = Pose::Identity();
  X.linear() = Eigen::AngleAxisd(angle, axis.normalized()).toRotationMatrix();
  return X;
}

Pose randomRotation(std::mt19937_64& rng) {
  std::normal_distribution<double> n01;
  Pose X = Pose::Identity();
  X.linear() = Eigen::Quaterniond(n01(rng), n01(rng), n01(rng), n01(rng)).normalized().toRotationMatrix();
  return X;
}

Case makeCase(const std::string& extreme, const Body& a, const Pose& XA, const Body& b, const Pose& XB, Truth truth) {
  Case c;
  c.family = pairName(a.family, b.family);
  c.extreme = extreme;
  c.what = a.label + " vs " + b.label;
  c.a = a.model;
  c.b = b.model;
  c.XA = XA;
  c.XB = XB;
  c.truth = truth;
  return c;
}

}  // namespace extremes
