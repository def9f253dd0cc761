#include "mesh/triangle_triangle.h"

#include "mesh/point_triangle.h"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::mesh {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

// Whether the lines of [p1, q1] and [p2, q2] are provably at least sqrt(limitSq) apart: |r·m| / |m| with
// m = d1 × d2, each side widened by a bound on its rounding error (so near-parallel edges are never skipped
// on a garbage direction). No square root: both sides are compared squared.
bool linesApart(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                const Eigen::Vector3d& q2, double limitSq) {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2, r = p2 - p1;
  const Eigen::Vector3d m = d1.cross(d2);
  const double k = d1.lpNorm<1>() * d2.lpNorm<1>();  // bounds |m| and each |m_i|'s scale
  const double num = std::abs(r.dot(m)) - 32 * kEps * r.lpNorm<1>() * k;
  if (!(num > 0)) return false;
  const double e = 16 * kEps * k;
  const double den2 = m.squaredNorm() + 2 * e * k + e * e;  // ≥ (|m| + e)², as |m| ≤ k
  return num * num >= limitSq * den2 * (1 + 8 * kEps);
}

// False only when the closest points of the edges' lines provably (rounding allowed for) fall outside an
// edge, so that interiorEdgeEdge would find nothing: the normal equations' numerators against their
// determinant, without a division or a square root. d1, d2: the edges' vectors; a = d1·d1 and e = d2·d2;
// n1, n2: their 1-norms; r = p1 − p2. With b = d1·d2, c = d1·r, f = d2·r and D = ae − b², the line points are
// at s = (bf − ce)/D on edge 1 and t = (af − bc)/D on edge 2; every product is bounded by n1 n2² |r|₁ or
// n1² n2 |r|₁ (D by n1² n2²), so a margin of 64ε of those covers the rounding of the dot products and of the
// numerators. Parallel or degenerate edges (D within its margin of 0) always pass.
bool mayBeInterior(const Eigen::Vector3d& d1, double a, double n1, const Eigen::Vector3d& d2, double e, double n2,
                   const Eigen::Vector3d& r) {
  const double b = d1.dot(d2), c = d1.dot(r), f = d2.dot(r);
  const double D = a * e - b * b;
  const double q = n1 * n2, rr = r.lpNorm<1>();
  const double mD = 64 * kEps * q * q;
  if (!(D > mD)) return true;
  const double ms = 64 * kEps * q * n2 * rr + mD, mt = 64 * kEps * q * n1 * rr + mD;
  const double s = b * f - c * e, t = a * f - b * c;
  return s >= -ms && s <= D + ms && t >= -mt && t <= D + mt;
}

// Closest points of the edges' lines when they lie inside both edges (x1 on [p1, q1], x2 on [p2, q2]); false
// for parallel or degenerate edges and when either falls outside, where an endpoint is a closest point. The
// critical point is found by Gram–Schmidt against the longer edge, which stays accurate for near-parallel ones.
bool interiorEdgeEdge(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1, const Eigen::Vector3d& p2,
                      const Eigen::Vector3d& q2, Eigen::Vector3d& x1, Eigen::Vector3d& x2) {
  const Eigen::Vector3d d1 = q1 - p1, d2 = q2 - p2;
  const double n1 = d1.squaredNorm(), n2 = d2.squaredNorm();
  if (!(n1 > 0 && n2 > 0)) return false;
  const bool firstLonger = n1 >= n2;
  const Eigen::Vector3d& pL = firstLonger ? p1 : p2;
  const Eigen::Vector3d& pS = firstLonger ? p2 : p1;
  const Eigen::Vector3d& dL = firstLonger ? d1 : d2;
  const Eigen::Vector3d& dS = firstLonger ? d2 : d1;
  const double nL = firstLonger ? n1 : n2;
  const Eigen::Vector3d u = dL / std::sqrt(nL);
  Eigen::Vector3d w = dS - dS.dot(u) * u;
  w -= w.dot(u) * u;
  const double ww = w.squaredNorm();
  if (!(ww > 0)) return false;
  const Eigen::Vector3d rr = pS - pL;
  const double t = -(rr - rr.dot(u) * u).dot(w) / ww;  // on the shorter edge
  if (!(t >= 0 && t <= 1)) return false;
  const double s = (rr + t * dS).dot(dL) / nL;  // on the longer edge
  if (!(s >= 0 && s <= 1)) return false;
  const Eigen::Vector3d xL = pL + s * dL, xS = pS + t * dS;
  x1 = firstLonger ? xL : xS;
  x2 = firstLonger ? xS : xL;
  return true;
}

}  // namespace

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
  // A vertex is also at least as far from the other triangle as from that triangle's box.
  const Eigen::Vector3d boxLoA = a[0].cwiseMin(a[1]).cwiseMin(a[2]), boxHiA = a[0].cwiseMax(a[1]).cwiseMax(a[2]);
  const Eigen::Vector3d boxLoB = b[0].cwiseMin(b[1]).cwiseMin(b[2]), boxHiB = b[0].cwiseMax(b[1]).cwiseMax(b[2]);
  const auto boxSq = [](const Eigen::Vector3d& q, const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
    return (lo - q).cwiseMax(q - hi).cwiseMax(0.0).squaredNorm();
  };
  for (int k = 0; k < 3; ++k) {
    const double limit = std::min(bestSq, cutoffSq);
    if (sa[k] * sa[k] < limit && boxSq(a[k], boxLoB, boxHiB) < limit) {
      const TriangleClosest ca = closestOnTriangle(a[k], b[0], b[1], b[2], nb);
      if (ca.squaredDistance < bestSq) {
        bestSq = ca.squaredDistance;
        r.pointA = a[k];
        r.pointB = ca.point;
        found = true;
      }
    }
    const double limitB = std::min(bestSq, cutoffSq);
    if (sb[k] * sb[k] < limitB && boxSq(b[k], boxLoA, boxHiA) < limitB) {
      const TriangleClosest cb = closestOnTriangle(b[k], a[0], a[1], a[2], na);
      if (cb.squaredDistance < bestSq) {
        bestSq = cb.squaredDistance;
        r.pointA = cb.point;
        r.pointB = b[k];
        found = true;
      }
    }
  }
  // Edges: a closest pair with an endpoint is a vertex–triangle pair measured above (or skipped for being no
  // nearer), so only interior edge–edge critical points remain. Each is filtered by the gap of the edges'
  // boxes, then by the distance between the edges' lines with its rounding error allowed for.
  if (!(bestSq > 0)) {
    r.distance = found ? std::sqrt(bestSq) : std::numeric_limits<double>::infinity();
    return r;
  }
  // Per edge: its vector, box and 1-norm, once (each takes part in three pairs).
  Eigen::Vector3d dA[3], dB[3], loA[3], hiA[3], loB[3], hiB[3];
  double nA1[3], nB1[3], aa[3], bb[3];
  for (int i = 0; i < 3; ++i) {
    const Eigen::Vector3d &pa = a[i], &qa = a[(i + 1) % 3], &pb = b[i], &qb = b[(i + 1) % 3];
    dA[i] = qa - pa;
    dB[i] = qb - pb;
    loA[i] = pa.cwiseMin(qa);
    hiA[i] = pa.cwiseMax(qa);
    loB[i] = pb.cwiseMin(qb);
    hiB[i] = pb.cwiseMax(qb);
    nA1[i] = dA[i].lpNorm<1>();
    nB1[i] = dB[i].lpNorm<1>();
    aa[i] = dA[i].squaredNorm();
    bb[i] = dB[i].squaredNorm();
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Eigen::Vector3d &p1 = a[i], &q1 = a[(i + 1) % 3], &p2 = b[j], &q2 = b[(j + 1) % 3];
      const double limit = std::min(bestSq, cutoffSq);
      const Eigen::Vector3d gap = (loB[j] - hiA[i]).cwiseMax(loA[i] - hiB[j]).cwiseMax(0.0);
      if (gap.squaredNorm() >= limit) continue;
      if (!mayBeInterior(dA[i], aa[i], nA1[i], dB[j], bb[j], nB1[j], p1 - p2)) continue;
      if (linesApart(p1, q1, p2, q2, limit)) continue;
      Eigen::Vector3d x1, x2;
      if (!interiorEdgeEdge(p1, q1, p2, q2, x1, x2)) continue;
      const double d2 = (x1 - x2).squaredNorm();
      if (d2 < bestSq) {
        bestSq = d2;
        r.pointA = x1;
        r.pointB = x2;
        found = true;
      }
    }
  const double best = found ? std::sqrt(bestSq) : std::numeric_limits<double>::infinity();
  r.distance = best;
  return r;
}

}  // namespace unidist::mesh
