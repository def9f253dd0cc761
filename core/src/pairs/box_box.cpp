// Box–box signed distance: separating-axis theorem for overlap (exact depth), GJK for separation.
#include "pairs/box_box.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::detail {
namespace {

using Eigen::Matrix3d;
using Eigen::Vector3d;

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr int kMaxIterations = 1000;  // GJK on two boxes needs a handful; this only guards against rounding loops

// Support of a box with half extents h centred at the origin of its own frame (sign(0) taken as +).
Vector3d boxSupport(const Vector3d& h, const Vector3d& d) {
  return Vector3d(d.x() >= 0 ? h.x() : -h.x(), d.y() >= 0 ? h.y() : -h.y(), d.z() >= 0 ? h.z() : -h.z());
}

}  // namespace

BoxAxes boxSeparatingAxes(const Vector3d& halfA, const Vector3d& halfB, const Matrix3d& R_AB, const Vector3d& p_AB) {
  // overlap(L) = min(h_D(L), h_D(−L)) for D = A − B; the smallest over all face normals of D is the depth. Every
  // unit L gives overlap >= depth, so an edge–edge axis whose direction is blurred by rounding (nearly parallel
  // edges) can never undercut the true answer; it only stands for a sliver face of D whose support value it
  // reproduces to first order.
  BoxAxes out;
  auto test = [&](const Vector3d& L, BoxAxis::Kind kind, int i, int j) {
    const double rA = halfA.dot(L.cwiseAbs());
    const double rB = halfB.dot((R_AB.transpose() * L).cwiseAbs());
    const double s = L.dot(p_AB);
    const double overlap = rA + rB - std::abs(s);
    if (overlap < out.smallest.overlap)  // strict: on ties face normals (tested first) win
      out.smallest = BoxAxis{kind, i, j, s >= 0 ? L : Vector3d(-L), overlap};
  };
  for (int i = 0; i < 3; ++i) test(Vector3d::Unit(i), BoxAxis::Kind::FaceOfA, i, 0);
  for (int j = 0; j < 3; ++j) test(R_AB.col(j), BoxAxis::Kind::FaceOfB, 0, j);
  out.smallestFace = out.smallest;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Vector3d L = Vector3d::Unit(i).cross(R_AB.col(j));
      const double len = L.norm();
      if (len > 1e-150) test(L / len, BoxAxis::Kind::EdgePair, i, j);  // exactly parallel edges add no face to D
    }
  return out;
}

ConvexDistance boxBox(const Vector3d& halfA, const Eigen::Isometry3d& X_WA, const Vector3d& halfB,
                      const Eigen::Isometry3d& X_WB, double tolerance) {
  const Matrix3d R_WA = X_WA.linear();
  const Matrix3d R_AB = R_WA.transpose() * X_WB.linear();                   // columns: B's axes in A
  const Vector3d p_AB = R_WA.transpose() * (X_WB.translation() - X_WA.translation());  // B's centre in A

  // Separating-axis test over the 15 candidate directions, in A's frame.
  const BoxAxis best = boxSeparatingAxes(halfA, halfB, R_AB, p_AB).smallest;
  const double minOverlap = best.overlap;
  const Vector3d axis = best.direction;

  const SupportFn supportA = [&](const Vector3d& d) { return boxSupport(halfA, d); };
  ConvexDistance out;
  if (minOverlap < 0) {
    const SupportFn supportB = [&](const Vector3d& d) {
      return Vector3d(p_AB + R_AB * boxSupport(halfB, R_AB.transpose() * d));
    };
    out = convexDistance(supportA, supportB, tolerance, kMaxIterations);
    out.lowerBound = std::min(std::max(out.lowerBound, -minOverlap), out.distance);  // the best axis gap
  } else {
    // Overlap (or contact): depth = minOverlap along axis (the way B moves). Find the contact point of A and B
    // moved there.
    const double depth = minOverlap;
    const Vector3d shift = depth * axis;
    const SupportFn supportB = [&](const Vector3d& d) {
      return Vector3d(p_AB + shift + R_AB * boxSupport(halfB, R_AB.transpose() * d));
    };
    ConvexScale scale;
    scale.size = 2 * (halfA.norm() + halfB.norm());
    const double tol = tolerance > 0 ? tolerance : scale.roundoff();
    const GjkResult g = gjk(supportA, supportB, minkowskiSupport(supportA, supportB, axis),
                            -kInf, tol, kMaxIterations, scale);
    const Vector3d contact = 0.5 * (g.pointA + g.pointB);
    out.distance = -depth + 0.0;  // +0, not −0, for exact contact
    out.normal = axis;
    out.pointA = contact;
    out.pointB = contact - shift;
    out.lowerBound = out.upperBound = out.distance;
    out.iterations = g.iterations;
    // The depth is exact; the points are certified when GJK's two points met to the tolerance (a point of A
    // that close to B, which only touches A, lies that close to A's boundary, and likewise for B).
    out.converged = (g.pointA - g.pointB).norm() <= tol;
  }
  out.pointA = X_WA * out.pointA;
  out.pointB = X_WA * out.pointB;
  out.normal = R_WA * out.normal;
  return out;
}

}  // namespace unidist::detail
