// Unions of convex pieces whose boundary distances are known by construction, and an independent CPU oracle:
// the "ray version" of Kim et al.'s algorithm (algorithms.md §5.2) — clip rays from O against every piece, walk
// the sorted intervals to the first uncovered gap — over many directions, then polished by a pattern search.
#pragma once

#include "unidist/raster/convex_union.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace raster_test {

using unidist::raster::ConvexPolytope;
using unidist::raster::ConvexUnion;
using Vec = Eigen::Vector3d;

inline ConvexPolytope box(const Vec& lo, const Vec& hi) {
  std::vector<Vec> corners;
  for (int c = 0; c < 8; ++c)
    corners.emplace_back((c & 1) ? hi.x() : lo.x(), (c & 2) ? hi.y() : lo.y(), (c & 4) ? hi.z() : lo.z());
  return unidist::raster::convexHull(corners);
}

/// The unit cube [0,1]³ cut into six tetrahedra around its main diagonal (every piece shares faces).
inline ConvexUnion cubeOfTetrahedra(const Vec& origin, double size) {
  const int paths[6][3] = {{0, 1, 2}, {0, 2, 1}, {1, 0, 2}, {1, 2, 0}, {2, 0, 1}, {2, 1, 0}};
  ConvexUnion pieces;
  for (const auto& path : paths) {
    std::vector<Vec> corners{origin};
    Vec p = Vec::Zero();
    for (int axis : path) {
      p[axis] = 1;
      corners.push_back(origin + size * p);
    }
    pieces.push_back(unidist::raster::convexHull(corners));
  }
  return pieces;
}

/// A polyhedral torus about z (centre radius R, tube radius r: the tube polygon's vertices lie on the circle)
/// as `segments` convex ring segments, each the hull of two consecutive tube cross-sections of `sides` sides.
inline ConvexUnion torusPieces(double R, double r, int segments, int sides, const Eigen::Isometry3d& X) {
  ConvexUnion pieces;
  auto section = [&](int s, std::vector<Vec>& out) {
    const double theta = 2 * M_PI * s / segments;
    for (int k = 0; k < sides; ++k) {
      const double phi = 2 * M_PI * (k + 0.5) / sides;
      const double rho = R + r * std::cos(phi);
      out.push_back(X * Vec(rho * std::cos(theta), rho * std::sin(theta), r * std::sin(phi)));
    }
  };
  for (int s = 0; s < segments; ++s) {
    std::vector<Vec> points;
    section(s, points);
    section(s + 1, points);
    pieces.push_back(unidist::raster::convexHull(points));
  }
  return pieces;
}

/// Exit distance of the ray O + t·u (u unit) from the union: intervals clipped from each piece's planes,
/// sorted, walked from 0 to the first gap. Overlapping or touching intervals (within `join`) merge.
inline double rayExit(const ConvexUnion& pieces, const Vec& O, const Vec& u, double join = 1e-12) {
  std::vector<std::pair<double, double>> intervals;
  for (const auto& piece : pieces) {
    double in = -std::numeric_limits<double>::infinity(), out = std::numeric_limits<double>::infinity();
    for (const auto& plane : piece.planes) {
      const double slope = plane.head<3>().dot(u), value = plane.head<3>().dot(O) + plane.w();
      if (slope > 0) out = std::min(out, -value / slope);
      else if (slope < 0) in = std::max(in, -value / slope);
      else if (value > 0) in = std::numeric_limits<double>::infinity();
    }
    if (in <= out && out > 0) intervals.emplace_back(in, out);
  }
  std::sort(intervals.begin(), intervals.end());
  double reach = 0;
  for (const auto& [in, out] : intervals) {
    if (in > reach + join) break;
    reach = std::max(reach, out);
  }
  return reach;
}

/// The oracle: the smallest exit over a cube map of `n`² directions per face, then a compass search on the
/// sphere around the best direction (`directions` per step) down to `finest` radians or `budget` rays. An upper
/// estimate of the true distance, exact up to the search's convergence (slow along a crease's valley, where it
/// zigzags unless a search direction lies along the valley: more directions help).
inline double oracleDistance(const ConvexUnion& pieces, const Vec& O, int n = 64, double finest = 1e-10,
                             Vec* bestDirection = nullptr, int budget = 4000, int directions = 8) {
  double best = std::numeric_limits<double>::infinity();
  Vec bestU = Vec::UnitX();
  for (int axis = 0; axis < 3; ++axis)
    for (int sign = -1; sign <= 1; sign += 2)
      for (int i = 0; i < n; ++i)
        for (int j = 0; j < n; ++j) {
          Vec u = Vec::Zero();
          u[axis] = sign;
          u[(axis + 1) % 3] = (2.0 * i + 1) / n - 1;
          u[(axis + 2) % 3] = (2.0 * j + 1) / n - 1;
          u.normalize();
          const double t = rayExit(pieces, O, u);
          if (t < best) best = t, bestU = u;
        }
  // Compass search in the tangent plane, eight directions, halving the step.
  Vec e1 = bestU.unitOrthogonal(), e2 = bestU.cross(e1);
  for (double step = 2.0 / n; step > finest && budget > 0;) {
    bool moved = false;
    for (int k = 0; k < directions; ++k, --budget) {
      const double angle = 2 * M_PI * k / directions;
      const Vec u = (bestU + step * (std::cos(angle) * e1 + std::sin(angle) * e2)).normalized();
      const double t = rayExit(pieces, O, u);
      if (t < best) {
        best = t, bestU = u, moved = true;
        e1 = bestU.unitOrthogonal(), e2 = bestU.cross(e1);
        break;
      }
    }
    if (!moved) step *= 0.5;
  }
  if (bestDirection) *bestDirection = bestU;
  return best;
}

}  // namespace raster_test
