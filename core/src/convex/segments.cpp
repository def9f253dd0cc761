// Closest points point–segment and segment–segment; see segments.h for the method and its accuracy.
#include "convex/segments.h"

#include <cmath>
#include <utility>

namespace unidist::detail {
namespace {

// Clamp to [0, 1]; a NaN (impossible for finite input, kept for safety) becomes 0.
double clamp01(double x) { return x > 0 ? (x < 1 ? x : 1.0) : 0.0; }

// a + t (b − a), exact at both ends.
Eigen::Vector3d lerp(const Eigen::Vector3d& a, const Eigen::Vector3d& b, double t) {
  if (t == 0) return a;
  if (t == 1) return b;
  return a + t * (b - a);
}

}  // namespace

PointSegmentClosest closestPointSegment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  PointSegmentClosest r;
  const Eigen::Vector3d d = b - a;
  const double dd = d.squaredNorm();
  r.t = dd > 0 ? clamp01((p - a).dot(d) / dd) : 0.0;
  r.point = lerp(a, b, r.t);
  r.distance = (p - r.point).norm();
  return r;
}

SegmentSegmentClosest closestSegmentSegment(const Eigen::Vector3d& p1, const Eigen::Vector3d& q1,
                                            const Eigen::Vector3d& p2, const Eigen::Vector3d& q2) {
  // Work with L = the longer segment and S = the shorter; swap back at the end.
  const bool swapped = (q2 - p2).squaredNorm() > (q1 - p1).squaredNorm();
  const Eigen::Vector3d& pL = swapped ? p2 : p1;
  const Eigen::Vector3d& qL = swapped ? q2 : q1;
  const Eigen::Vector3d& pS = swapped ? p1 : p2;
  const Eigen::Vector3d& qS = swapped ? q1 : q2;
  const Eigen::Vector3d dL = qL - pL, dS = qS - pS;
  const double dLL = dL.squaredNorm();

  double sL = 0, tS = 0;  // parameters on L and S
  bool interior = false;
  if (dLL > 0 && dS.squaredNorm() > 0) {
    // Interior critical point by Gram–Schmidt against L: for fixed tS the best point of L's line leaves the part
    // of X(tS) = (pS − pL) + tS dS orthogonal to u = dL/|dL|, i.e. rPerp + tS w; minimise that over tS.
    const Eigen::Vector3d u = dL / std::sqrt(dLL);
    Eigen::Vector3d w = dS - dS.dot(u) * u;
    w -= w.dot(u) * u;  // second pass: orthogonal to u to working precision even when dS is nearly parallel
    const Eigen::Vector3d r = pS - pL;
    const Eigen::Vector3d rPerp = r - r.dot(u) * u;
    const double ww = w.squaredNorm();
    if (ww > 0) {
      const double t = -rPerp.dot(w) / ww;
      if (t >= 0 && t <= 1) {
        const double s = (r + t * dS).dot(dL) / dLL;
        if (s >= 0 && s <= 1) {
          sL = s;
          tS = t;
          interior = true;
        }
      }
    }
  }
  SegmentSegmentClosest out;
  Eigen::Vector3d xL, xS;
  if (interior) {
    xL = lerp(pL, qL, sL);
    xS = lerp(pS, qS, tS);
  } else {
    // The minimum lies on a side of the parameter square: an endpoint of one segment against the other.
    const PointSegmentClosest c[4] = {closestPointSegment(pL, pS, qS), closestPointSegment(qL, pS, qS),
                                      closestPointSegment(pS, pL, qL), closestPointSegment(qS, pL, qL)};
    int best = 0;
    for (int i = 1; i < 4; ++i)
      if (c[i].distance < c[best].distance) best = i;
    switch (best) {
      case 0: sL = 0; tS = c[0].t; xL = pL; xS = c[0].point; break;
      case 1: sL = 1; tS = c[1].t; xL = qL; xS = c[1].point; break;
      case 2: sL = c[2].t; tS = 0; xL = c[2].point; xS = pS; break;
      default: sL = c[3].t; tS = 1; xL = c[3].point; xS = qS; break;
    }
  }
  if (swapped) {
    out.s = tS; out.t = sL; out.point1 = xS; out.point2 = xL;
  } else {
    out.s = sL; out.t = tS; out.point1 = xL; out.point2 = xS;
  }
  out.distance = (out.point1 - out.point2).norm();
  return out;
}

}  // namespace unidist::detail
