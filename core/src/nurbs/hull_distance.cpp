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
  int iterations = 0;
  const GjkResult g = detail::gjkWithRestarts(supportA, supportB, start, -std::numeric_limits<double>::infinity(),
                                              tolerance, maxIterations, scale, iterations, stopAbove);
  HullDistance out;
  out.lower = std::min(g.lowerBound, (g.pointB - g.pointA).norm());
  out.pointA = g.pointA;
  out.pointB = g.pointB;
  out.iterations = iterations;
  return out;
}

}  // namespace unidist::nurbs
