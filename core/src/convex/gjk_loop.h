// The GJK loop over any pair of support callables (gjk.h's gjk runs it on std::function support maps; callers
// with small point sets in a hot loop run it on plain lambdas, which the compiler inlines). Internal.
#pragma once

#include "convex/gjk.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::detail {

namespace gjk_loop {

inline double maxAbs(const SupportPoint& s) { return std::max(s.a.cwiseAbs().maxCoeff(), s.b.cwiseAbs().maxCoeff()); }

/// Sets r.pointA and r.pointB from the simplex and returns pointA − pointB.
inline Eigen::Vector3d witnessPoints(GjkResult& r) {
  r.pointA.setZero();
  r.pointB.setZero();
  for (int i = 0; i < r.count; ++i) {
    r.pointA += r.lambda[i] * r.simplex[i].a;
    r.pointB += r.lambda[i] * r.simplex[i].b;
  }
  return r.pointA - r.pointB;
}

}  // namespace gjk_loop

/// Support of A − B in direction d for support callables: a = sA(d), b = sB(−d).
template <typename SupportA, typename SupportB>
SupportPoint minkowskiSupportOf(const SupportA& a, const SupportB& b, const Eigen::Vector3d& d) {
  SupportPoint s;
  s.a = a(d);
  s.b = b(-d);
  s.w = s.a - s.b;
  return s;
}

/// gjk (gjk.h) for support callables Vector3d(const Vector3d&). stopAbove: the loop also ends once the proved
/// lower bound reaches it (a caller that only asks "apart by at least this much?" has its answer).
template <typename SupportA, typename SupportB>
GjkResult gjkLoop(const SupportA& a, const SupportB& b, const SupportPoint& start, double lowerBound, double tolerance,
                  int maxIterations, ConvexScale& scale,
                  double stopAbove = std::numeric_limits<double>::infinity()) {
  GjkResult r;
  r.simplex[0] = start;
  r.lambda[0] = 1;
  r.count = 1;
  r.v = start.w;
  r.lowerBound = lowerBound;
  scale.coordMag = std::max(scale.coordMag, gjk_loop::maxAbs(start));
  for (int it = 0; it < maxIterations; ++it) {
    const double vv = r.v.squaredNorm();
    const double eps = scale.roundoff();
    // The origin is within rounding of the hull: overlap or contact (EPA decides which).
    if (vv <= eps * eps) {
      r.originInside = true;
      break;
    }
    const double vn = std::sqrt(vv);
    const SupportPoint s = minkowskiSupportOf(a, b, Eigen::Vector3d(-r.v));
    ++r.iterations;
    scale.coordMag = std::max(scale.coordMag, gjk_loop::maxAbs(s));
    const double vw = r.v.dot(s.w);
    const double gapAlongV = vw / vn;  // the separating-axis gap along v (see gjk.h)
    r.lowerBound = std::max(r.lowerBound, gapAlongV);
    // Stop on the gap along the current v, not on the best bound so far, measured from the distance of the
    // real points (not |v|, which on sliver simplices differs from it by ~1e-12 relative): then the current
    // points are certified too, their depths in A and B summing to at most this gap.
    r.witnessGap = gjk_loop::witnessPoints(r).norm() - gapAlongV;
    if (r.witnessGap <= tolerance || r.lowerBound >= stopAbove) break;
    // w is not beyond the current support plane by more than rounding: no further progress is possible.
    if (vn - gapAlongV <= eps) break;
    bool duplicate = false;
    for (int i = 0; i < r.count; ++i) duplicate = duplicate || s.w == r.simplex[i].w;
    if (duplicate) break;

    SupportPoint cand[4];
    Eigen::Vector3d pts[4];
    for (int i = 0; i < r.count; ++i) cand[i] = r.simplex[i];
    cand[r.count] = s;
    for (int i = 0; i <= r.count; ++i) pts[i] = cand[i].w;
    const SubSimplex sub = closestOnSimplex(pts, r.count + 1);
    // Cycling guard: the distance must strictly decrease, else rounding has taken over; keep the last simplex.
    if (sub.count < 4 && !(sub.v.squaredNorm() < vv)) break;
    r.count = sub.count;
    for (int i = 0; i < sub.count; ++i) {
      r.simplex[i] = cand[sub.index[i]];
      r.lambda[i] = sub.lambda[i];
    }
    r.v = sub.v;
    r.witnessGap = std::numeric_limits<double>::infinity();  // the new v has not been checked yet
    if (sub.count == 4) {
      r.originInside = true;
      break;
    }
  }
  r.upperBound = gjk_loop::witnessPoints(r).norm();  // two real points of A and B (convex combinations of supports)
  r.lowerBound = std::min(r.lowerBound, r.upperBound);  // equal up to rounding when they cross
  r.converged = r.upperBound - r.lowerBound <= tolerance && r.witnessGap <= tolerance;
  return r;
}

/// gjkLoop, and then, for a separated run that stalled on a degenerate simplex (a box vertex against a rim, a
/// needle-thin triangle) before its bounds met, up to four restarts from a single support point along the best
/// direction so far: that drops the degenerate simplex and keeps the proved lower bound; the tighter answer is
/// kept. `iterations` counts every run's.
template <typename SupportA, typename SupportB>
GjkResult gjkWithRestarts(const SupportA& a, const SupportB& b, const SupportPoint& start, double lowerBound,
                          double tolerance, int maxIterations, ConvexScale& scale, int& iterations,
                          double stopAbove = std::numeric_limits<double>::infinity()) {
  GjkResult g = gjkLoop(a, b, start, lowerBound, tolerance, maxIterations, scale, stopAbove);
  iterations = g.iterations;
  for (int restart = 0; restart < 4 && !g.converged && !g.originInside && g.lowerBound > 0 &&
                        g.lowerBound < stopAbove && iterations < maxIterations;
       ++restart) {
    const SupportPoint fresh = minkowskiSupportOf(a, b, Eigen::Vector3d(-g.v));
    GjkResult again = gjkLoop(a, b, fresh, g.lowerBound, tolerance, maxIterations - iterations, scale, stopAbove);
    iterations += again.iterations;
    if (again.originInside) break;  // rounding-level contact: let the first answer (and EPA) decide
    again.lowerBound = std::max(again.lowerBound, g.lowerBound);
    if (again.upperBound <= g.upperBound) {
      g = again;
    } else {
      g.lowerBound = again.lowerBound;
      g.converged = g.upperBound - g.lowerBound <= tolerance && g.witnessGap <= tolerance;
      if (again.iterations <= 1) break;  // no progress possible from here
    }
  }
  return g;
}

}  // namespace unidist::detail
