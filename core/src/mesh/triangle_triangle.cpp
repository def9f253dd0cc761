#include "mesh/triangle_triangle.h"

#include "convex/segments.h"
#include "mesh/point_triangle.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace unidist::mesh {

bool segmentCrossesTriangle(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Eigen::Vector3d* t,
                            const Eigen::Vector3d& n, Eigen::Vector3d& x) {
  const double dp = n.dot(p - t[0]), dq = n.dot(q - t[0]);
  if ((dp > 0 && dq > 0) || (dp < 0 && dq < 0) || (dp == 0 && dq == 0)) return false;
  const double s = dp / (dp - dq);
  x = p + s * (q - p);
  for (int k = 0; k < 3; ++k) {
    const Eigen::Vector3d& u = t[k];
    const Eigen::Vector3d& v = t[(k + 1) % 3];
    if (n.dot((v - u).cross(x - u)) < 0) return false;
  }
  return true;
}

TriangleTriangleClosest closestTriangleTriangle(const Eigen::Vector3d* a, const Eigen::Vector3d& na,
                                                const Eigen::Vector3d* b, const Eigen::Vector3d& nb, double cutoff) {
  TriangleTriangleClosest r;
  // Separation along either normal bounds the distance from below (the gap between the projections).
  double sa[3], sb[3];  // a's vertices above b's plane, b's above a's
  for (int k = 0; k < 3; ++k) {
    sa[k] = nb.dot(a[k] - b[0]);
    sb[k] = na.dot(b[k] - a[0]);
  }
  {
    const double loA = std::min({sa[0], sa[1], sa[2]}), hiA = std::max({sa[0], sa[1], sa[2]});
    const double loB = std::min({sb[0], sb[1], sb[2]}), hiB = std::max({sb[0], sb[1], sb[2]});
    const double gap = std::max({loA, -hiA, loB, -hiB});
    if (gap >= cutoff) {
      r.distance = std::numeric_limits<double>::infinity();
      return r;
    }
  }
  // Crossing test: only when each triangle's vertices are not strictly on one side of the other's plane.
  auto straddles = [](const double* s) {
    bool pos = false, neg = false;
    for (int k = 0; k < 3; ++k) {
      pos = pos || s[k] >= 0;
      neg = neg || s[k] <= 0;
    }
    return pos && neg;
  };
  if (straddles(sa) && straddles(sb)) {
    Eigen::Vector3d x;
    for (int k = 0; k < 3; ++k) {
      if (segmentCrossesTriangle(a[k], a[(k + 1) % 3], b, nb, x) ||
          segmentCrossesTriangle(b[k], b[(k + 1) % 3], a, na, x)) {
        r.pointA = r.pointB = x;
        r.distance = 0;
        r.intersecting = true;
        return r;
      }
    }
  }
  // Features: a vertex–triangle distance is at least the vertex's height over the plane, an edge–edge one at
  // least the gap between the edges' boxes; either is skipped when that already reaches the best so far.
  double bestSq = std::numeric_limits<double>::infinity();
  const double cutoffSq = cutoff * cutoff;
  bool found = false;
  for (int k = 0; k < 3; ++k) {
    const double limit = std::min(bestSq, cutoffSq);
    if (sa[k] * sa[k] < limit) {
      const TriangleClosest ca = closestOnTriangle(a[k], b[0], b[1], b[2], nb);
      if (ca.squaredDistance < bestSq) {
        bestSq = ca.squaredDistance;
        r.pointA = a[k];
        r.pointB = ca.point;
        found = true;
      }
    }
    if (sb[k] * sb[k] < std::min(bestSq, cutoffSq)) {
      const TriangleClosest cb = closestOnTriangle(b[k], a[0], a[1], a[2], na);
      if (cb.squaredDistance < bestSq) {
        bestSq = cb.squaredDistance;
        r.pointA = cb.point;
        r.pointB = b[k];
        found = true;
      }
    }
  }
  double best = found ? std::sqrt(bestSq) : std::numeric_limits<double>::infinity();
  if (best > 0) {
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d &p1 = a[i], &q1 = a[(i + 1) % 3], &p2 = b[j], &q2 = b[(j + 1) % 3];
        const Eigen::Vector3d gap =
            (p2.cwiseMin(q2) - p1.cwiseMax(q1)).cwiseMax(p1.cwiseMin(q1) - p2.cwiseMax(q2)).cwiseMax(0.0);
        const double g2 = gap.squaredNorm();
        if (g2 >= best * best || g2 >= cutoffSq) continue;
        const detail::SegmentSegmentClosest s = detail::closestSegmentSegment(p1, q1, p2, q2);
        if (s.distance < best) {
          best = s.distance;
          r.pointA = s.point1;
          r.pointB = s.point2;
        }
      }
  }
  r.distance = best;
  return r;
}

}  // namespace unidist::mesh
