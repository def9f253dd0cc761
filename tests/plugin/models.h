// The bodies of the Bullet (and scene) tests: a NURBS sphere, a mesh box, a box-shaped point cloud, a NURBS
// bowl, a mesh block with a square through-hole, a tessellated floor, and the unidist primitives.
#pragma once

#include "core/mesh_fixtures.h"
#include "core/nurbs_fixtures.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <memory>

namespace test_models {

using Vec = Eigen::Vector3d;

inline std::shared_ptr<const unidist::Model> nurbsSphere(double r) {
  return std::make_shared<unidist::NurbsModel>(std::vector<unidist::NurbsSurface>{nurbs_fixtures::sphereSurface(r)}, true);
}

/// The lower half of a sphere of radius r about the origin, open (a bowl, inside up), as a rational NURBS.
inline std::shared_ptr<const unidist::Model> nurbsBowl(double r) {
  const double h = std::sqrt(0.5);
  const std::vector<nurbs_fixtures::Point2W> quarter = {{0, -1, 1}, {1, -1, h}, {1, 0, 1}};
  return std::make_shared<unidist::NurbsModel>(
      std::vector<unidist::NurbsSurface>{
          {2, 2, nurbs_fixtures::circleKnots(), {0, 0, 0, 1, 1, 1}, nurbs_fixtures::revolve(quarter, r, Vec::Zero())}},
      false);
}

/// The square x = 0, |y|, |z| <= half as an open bilinear NURBS patch (a wall of zero thickness).
inline std::shared_ptr<const unidist::Model> nurbsWall(double half) {
  nurbs_fixtures::Net net = {{{0, -half, -half, 1}, {0, -half, half, 1}}, {{0, half, -half, 1}, {0, half, half, 1}}};
  return std::make_shared<unidist::NurbsModel>(std::vector<unidist::NurbsSurface>{{1, 1, {0, 0, 1, 1}, {0, 0, 1, 1}, net}},
                                               false);
}

inline std::shared_ptr<const unidist::Model> meshBox(const Vec& h, int n = 2) {
  const meshfix::Soup s = meshfix::gridBox(h, n);
  return std::make_shared<unidist::TriangleMesh>(s.vertices, s.triangles);
}

/// Two boxes of half extents h, centres ±offset along x, as one mesh of two closed components (a dumbbell
/// without a bar: a non-convex model touching a floor in two separate places).
inline std::shared_ptr<const unidist::Model> twoBoxes(const Vec& h, double offset) {
  meshfix::Soup s = meshfix::gridBox(h, 1);
  const std::size_t n = s.vertices.size(), t = s.triangles.size();
  for (std::size_t i = 0; i < n; ++i) s.vertices.push_back(s.vertices[i] + Vec(offset, 0, 0));
  for (std::size_t i = 0; i < n; ++i) s.vertices[i] -= Vec(offset, 0, 0);
  for (std::size_t k = 0; k < t; ++k) {
    auto tri = s.triangles[k];
    for (auto& v : tri) v += static_cast<std::uint32_t>(n);
    s.triangles.push_back(tri);
  }
  return std::make_shared<unidist::TriangleMesh>(s.vertices, s.triangles);
}

/// The lattice points of a box's faces (an n × n grid per face): a cloud with flat sides.
inline std::shared_ptr<const unidist::Model> cloudBox(const Vec& h, int n = 4) {
  return std::make_shared<unidist::PointCloud>(meshfix::gridBox(h, n).vertices);
}

/// Open flat floor z = 0 over [-half, half]², n × n quads (two triangles each, facing up).
inline std::shared_ptr<const unidist::Model> tessellatedFloor(double half, int n) {
  std::vector<Vec> v;
  std::vector<unidist::TriangleMesh::Triangle> t;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; j <= n; ++j) v.emplace_back(-half + 2 * half * i / n, -half + 2 * half * j / n, 0);
  auto id = [n](int i, int j) { return static_cast<std::uint32_t>(i * (n + 1) + j); };
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) {
      t.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
    }
  return std::make_shared<unidist::TriangleMesh>(v, t);
}

/// A block [-outer, outer]² × [0, height] with a square through-hole [-inner, inner]² (a closed genus-1 solid).
inline std::shared_ptr<const unidist::Model> blockWithHole(double outer, double inner, double height) {
  std::vector<Vec> v;
  const double sx[4] = {-1, 1, 1, -1}, sy[4] = {-1, -1, 1, 1};  // counter-clockwise seen from +z
  for (double z : {0.0, height})
    for (double size : {outer, inner})
      for (int k = 0; k < 4; ++k) v.emplace_back(size * sx[k], size * sy[k], z);
  // index: 8·(z top) + 4·(inner) + corner
  auto o = [](int top, int k) { return static_cast<std::uint32_t>(8 * top + (k % 4)); };
  auto i = [](int top, int k) { return static_cast<std::uint32_t>(8 * top + 4 + (k % 4)); };
  std::vector<unidist::TriangleMesh::Triangle> t;
  for (int k = 0; k < 4; ++k) {
    // top ring faces +z, bottom ring −z
    t.push_back({o(1, k), o(1, k + 1), i(1, k + 1)});
    t.push_back({o(1, k), i(1, k + 1), i(1, k)});
    t.push_back({o(0, k), i(0, k + 1), o(0, k + 1)});
    t.push_back({o(0, k), i(0, k), i(0, k + 1)});
    // outer wall faces out, inner wall faces the hole
    t.push_back({o(0, k), o(0, k + 1), o(1, k + 1)});
    t.push_back({o(0, k), o(1, k + 1), o(1, k)});
    t.push_back({i(0, k), i(1, k + 1), i(0, k + 1)});
    t.push_back({i(0, k), i(1, k), i(1, k + 1)});
  }
  return std::make_shared<unidist::TriangleMesh>(v, t);
}

}  // namespace test_models
