#include "generic/direction_cones.h"

#include <algorithm>
#include <cmath>

namespace unidist::detail {

Eigen::Vector3d cubeMapDirection(int face, double u, double v) {
  const int axis = face / 2;
  const double sign = face % 2 == 0 ? 1.0 : -1.0;
  Eigen::Vector3d d;
  d[axis] = sign;
  d[(axis + 1) % 3] = u;
  d[(axis + 2) % 3] = v;
  return d.normalized();
}

DirectionCone makeCone(int face, double u0, double u1, double v0, double v1, int level) {
  DirectionCone c{face, u0, u1, v0, v1, level, cubeMapDirection(face, 0.5 * (u0 + u1), 0.5 * (v0 + v1)), 0};
  // The gnomonic image of a square is a convex spherical polygon, so its farthest point from any inner
  // direction is a corner. The angle is taken from the chord (stable for tiny cells) and padded for rounding.
  double chord = 0;
  for (double u : {u0, u1})
    for (double v : {v0, v1}) chord = std::max(chord, (cubeMapDirection(face, u, v) - c.axis).norm());
  c.halfAngle = 2 * std::asin(std::min(1.0, 0.5 * chord)) * (1 + 1e-12) + 1e-15;
  return c;
}

std::vector<DirectionCone> cubeMapCones(int n) {
  std::vector<DirectionCone> cones;
  const double h = 2.0 / n;
  for (int face = 0; face < 6; ++face)
    for (int i = 0; i < n; ++i)
      for (int j = 0; j < n; ++j) cones.push_back(makeCone(face, -1 + i * h, -1 + (i + 1) * h, -1 + j * h, -1 + (j + 1) * h, 0));
  return cones;
}

std::array<DirectionCone, 4> splitCone(const DirectionCone& c) {
  const double um = 0.5 * (c.u0 + c.u1), vm = 0.5 * (c.v0 + c.v1);
  const int l = c.level + 1;
  return {makeCone(c.face, c.u0, um, c.v0, vm, l), makeCone(c.face, um, c.u1, c.v0, vm, l),
          makeCone(c.face, c.u0, um, vm, c.v1, l), makeCone(c.face, um, c.u1, vm, c.v1, l)};
}

}  // namespace unidist::detail
