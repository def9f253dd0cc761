// Exact rational NURBS test surfaces written from their definitions: sphere and torus (surfaces of revolution
// of a rational quadratic circle), a cylinder and a bicubic wavy patch with non-uniform weights.
#pragma once

#include "unidist/nurbs.h"

#include <cmath>
#include <vector>

namespace nurbs_fixtures {

using Net = std::vector<std::vector<Eigen::Vector4d>>;

struct Point2W {
  double a, b, w;
};

/// The unit circle as 9 rational quadratic control points (x, y, weight) over the knots below.
inline std::vector<Point2W> unitCircle() {
  const double h = std::sqrt(0.5);
  return {{1, 0, 1}, {1, 1, h}, {0, 1, 1}, {-1, 1, h}, {-1, 0, 1}, {-1, -1, h}, {0, -1, 1}, {1, -1, h}, {1, 0, 1}};
}
inline std::vector<double> circleKnots() { return {0, 0, 0, .25, .25, .5, .5, .75, .75, 1, 1, 1}; }

/// Revolves a profile (radius r, height z, weight) about the z axis: u = angle, v = profile parameter.
inline Net revolve(const std::vector<Point2W>& profile, double scale, const Eigen::Vector3d& centre) {
  Net net;
  for (const Point2W& c : unitCircle()) {
    net.emplace_back();
    for (const Point2W& p : profile)
      net.back().emplace_back(centre.x() + scale * c.a * p.a, centre.y() + scale * c.b * p.a, centre.z() + scale * p.b,
                              c.w * p.w);
  }
  return net;
}

inline unidist::NurbsSurface sphereSurface(double radius = 1, const Eigen::Vector3d& centre = Eigen::Vector3d::Zero()) {
  const double h = std::sqrt(0.5);
  const std::vector<Point2W> meridian = {{0, -1, 1}, {1, -1, h}, {1, 0, 1}, {1, 1, h}, {0, 1, 1}};
  return {2, 2, circleKnots(), {0, 0, 0, .5, .5, 1, 1, 1}, revolve(meridian, radius, centre)};
}

inline unidist::NurbsSurface torusSurface(double R = 1, double a = 0.25, double scale = 1) {
  std::vector<Point2W> tube;
  for (const Point2W& c : unitCircle()) tube.push_back({R + a * c.a, a * c.b, c.w});
  return {2, 2, circleKnots(), circleKnots(), revolve(tube, scale, Eigen::Vector3d::Zero())};
}

/// Open cylinder of radius r, z in [−h, h].
inline unidist::NurbsSurface cylinderSurface(double r = 0.5, double h = 1) {
  return {2, 1, circleKnots(), {0, 0, 1, 1}, revolve({{1, -h / r, 1}, {1, h / r, 1}}, r, Eigen::Vector3d::Zero())};
}

/// Bicubic 7x7 wavy patch over [−1,1]^2 with non-uniform knots and weights in [0.6, 1.6].
inline unidist::NurbsSurface wavySurface() {
  Net net(7);
  for (int i = 0; i < 7; ++i)
    for (int j = 0; j < 7; ++j) {
      const double x = -1 + i / 3.0, y = -1 + j / 3.0;
      net[static_cast<std::size_t>(i)].emplace_back(x, y, 0.35 * std::sin(3.1 * x) * std::cos(2.3 * y) + 0.1 * x * y,
                                                    1.1 + 0.5 * std::sin(1.7 * i + 0.9 * j));
    }
  const std::vector<double> k = {0, 0, 0, 0, 0.2, 0.45, 0.7, 1, 1, 1, 1};
  return {3, 3, k, k, net};
}

/// The box of half extents h as six bilinear patches, each with Su x Sv outward.
inline std::vector<unidist::NurbsSurface> boxPatches(const Eigen::Vector3d& h) {
  std::vector<unidist::NurbsSurface> faces;
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {1.0, -1.0}) {
      // (axis, b, c) cyclic: e_b x e_c = e_axis; the -axis face swaps u and v.
      const int b = (axis + 1) % 3, c = (axis + 2) % 3;
      const int u = side > 0 ? b : c, v = side > 0 ? c : b;
      Net net(2);
      for (int i = 0; i < 2; ++i)
        for (int j = 0; j < 2; ++j) {
          Eigen::Vector3d p = Eigen::Vector3d::Zero();
          p[axis] = side * h[axis];
          p[u] = (2 * i - 1) * h[u];
          p[v] = (2 * j - 1) * h[v];
          net[static_cast<std::size_t>(i)].emplace_back(p.x(), p.y(), p.z(), 1.0);
        }
      faces.emplace_back(1, 1, std::vector<double>{0, 0, 1, 1}, std::vector<double>{0, 0, 1, 1}, net);
    }
  return faces;
}

}  // namespace nurbs_fixtures
