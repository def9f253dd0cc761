#include "nurbs/hull_distance.h"

#include "cloud/point_support.h"
#include "convex/gjk_loop.h"

namespace unidist::nurbs {

HullDistance hullDistance(const std::vector<Eigen::Vector3d>& a, const std::vector<Eigen::Vector3d>& b,
                          const Eigen::Isometry3d& X_AB, const Eigen::Vector3d& startA, const Eigen::Vector3d& startB,
                          double tolerance, int maxIterations, double stopAbove) {
  using detail::GjkResult;
  using detail::SupportPoint;
  const Eigen::Matrix3d R_BA = X_AB.linear().transpose();
  const auto supportA = [&a](const Eigen::Vector3d& d) { return supportOfPoints(a, d); };
  const auto supportB = [&](const Eigen::Vector3d& d) -> Eigen::Vector3d { return X_AB * supportOfPoints(b, R_BA * d); };
  detail::ConvexScale scale;
  SupportPoint start;
  start.a = startA;
  start.b = startB;
  start.w = startA - startB;
  GjkResult g = detail::gjkLoop(supportA, supportB, start,
                                -std::numeric_limits<double>::infinity(), tolerance, maxIterations, scale, stopAbove);
  int iterations = g.iterations;
  // As convexDistance does: a separated run stalled on a degenerate simplex restarts from one support point
  // along the best direction so far, keeping the proved bound and the tighter answer.
  for (int restart = 0; restart < 4 && !g.converged && !g.originInside && g.lowerBound > 0 &&
                        g.lowerBound < stopAbove && iterations < maxIterations;
       ++restart) {
    const SupportPoint fresh = detail::minkowskiSupportOf(supportA, supportB, Eigen::Vector3d(-g.v));
    GjkResult again =
        detail::gjkLoop(supportA, supportB, fresh, g.lowerBound, tolerance, maxIterations - iterations, scale, stopAbove);
    iterations += again.iterations;
    if (again.originInside) break;
    again.lowerBound = std::max(again.lowerBound, g.lowerBound);
    if (again.upperBound <= g.upperBound) {
      g = again;
    } else {
      g.lowerBound = again.lowerBound;
      g.converged = g.upperBound - g.lowerBound <= tolerance && g.witnessGap <= tolerance;
      if (again.iterations <= 1) break;
    }
  }
  HullDistance out;
  out.lower = std::min(g.lowerBound, (g.pointB - g.pointA).norm());
  out.pointA = g.pointA;
  out.pointB = g.pointB;
  out.iterations = iterations;
  return out;
}

}  // namespace unidist::nurbs
