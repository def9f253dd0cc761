// The two objectives the patch search minimises: distance to a point (closestPoint) and −d·p (support). Internal.
#pragma once

#include "nurbs/bernstein_bound.h"
#include "nurbs/gradient_sign.h"
#include "nurbs/patch_search.h"
#include "nurbs/point_convexity.h"
#include "nurbs/support_bound.h"

#include <algorithm>
#include <limits>

namespace unidist::nurbs {

/// Subdivisions a closing bound that may well fail is allowed (a continuum's pieces settle within ~15).
constexpr int kQuickHalvings = 20;

/// The cheap first try of provesNoMinimum: the tangent cones. Su never orthogonal to the objective's direction
/// rules out interior critical points and those on the edges t = const, likewise Sv (Su and Sv vanish only on
/// collapsed edges, whose points are a corner's).
inline bool conesProveNoMinimum(const PatchNode& n, const Cone& towards) {
  const bool u = !canBeOrthogonal(n.cu, towards), v = !canBeOrthogonal(n.cv, towards);
  const bool edgeS = n.s0 == 0 || n.s1 == 1, edgeT = n.t0 == 0 || n.t1 == 1;
  return (u || v) && (!edgeS || v) && (!edgeT || u);
}

/// |S − q|; Newton works on ½|S − q|², whose Hessian is the first fundamental form minus ρ times the second.
class PointObjective final : public Objective {
 public:
  PointObjective(const Eigen::Vector3d& q, double modelSize) : q_(q), floor_(0.02 * modelSize) {}
  double value(const Eigen::Vector3d& p) const override { return (p - q_).norm(); }
  double rank(const Eigen::Vector3d& p) const override { return (p - q_).squaredNorm(); }
  double rankOf(double value) const override { return value < 0 ? -1.0 : value * value; }
  double lowerBound(const PatchNode& n) const override {
    return std::max((q_ - n.ball.center).norm() - n.ball.radius, boxDistance(n, q_));
  }
  double lowerBound(const PatchNode& n, double enough) const override {
    const double byBall = (q_ - n.ball.center).norm() - n.ball.radius;
    return byBall >= enough ? byBall : std::max(byBall, boxDistance(n, q_));
  }
  double tightLowerBound(const PatchNode& n) const override {
    return std::max(lowerBound(n), bernsteinDistanceBound(n.net, q_, scratch_));
  }
  // Twice bernsteinDistanceBound's rounding allowance: far from the model (tens of its sizes) a tolerance of
  // 1e-13 × size is below it, and the pieces around the nearest point, all tied to rounding, would be split on.
  double resolution(double value, std::size_t terms) const override { return 2 * bernsteinRounding(terms, value, q_); }
  // The nearest distance certified by concavity of γW² − |X − qW|² over the piece (support_bound.h): exact where
  // the piece stays outside a sphere about q that touches it, which at a pole the curvature form cannot show;
  // elsewhere it is the same coefficient-ratio bound as tightLowerBound's (computed once, there).
  double closingBound(const PatchNode& n, double enough) const override {
    return nearestBound(n, enough, kDistanceHalvings);
  }
  double quickClosingBound(const PatchNode& n, double enough) const override {
    return nearestBound(n, enough, kQuickHalvings);
  }
  Cone criticalDirections(const BoundingSphere& b) const override { return coneTowards(q_, b.center, b.radius); }
  void derivatives(const SurfaceDerivatives& d, Eigen::Vector2d& g, Eigen::Matrix2d& H) const override {
    const Eigen::Vector3d r = d.point - q_;
    g << r.dot(d.du), r.dot(d.dv);
    H << d.du.dot(d.du) + r.dot(d.duu), d.du.dot(d.dv) + r.dot(d.duv), d.du.dot(d.dv) + r.dot(d.duv),
        d.dv.dot(d.dv) + r.dot(d.dvv);
  }
  // g_a = (S − q)·S_a: S and S_a are evaluated to a few ulps of |S| and |S_a| + |S| (the quotient rule), q − S
  // to an ulp of |q| + |S|.
  double gradientError(const SurfaceDerivatives& d) const override {
    const double r = (d.point - q_).norm(), scale = d.point.norm() + q_.norm();
    const double speed = std::max(d.du.norm(), d.dv.norm());
    return 256 * std::numeric_limits<double>::epsilon() * (scale * speed + r * (speed + d.point.norm()));
  }
  double curvature(const PatchNode& n, const PatchForest& forest) const override {
    return convexAtMiddle(n, q_) ? leastCurvature(curvatureForm(n, forest), q_) : 0;
  }
  double basinBound(const PatchNode& n, const PatchHit& h, double curvature) const override {
    return convexDistanceBound(n, q_, h, curvature);
  }
  bool provesBasins() const override { return true; }
  double edgeBound(const PatchNode& n, const PatchForest& forest, const PatchHit& h) const override {
    return edgeDistanceBound(n, forest, q_, h, gradient_);
  }
  // Near the surface the distance is convex over a small piece whatever q, so pieces of a fixed small size
  // are polished too (otherwise a query on the surface would subdivide down to the tolerance).
  double leafScale(const BoundingSphere& b) const override { return std::max((q_ - b.center).norm(), floor_); }
  bool provesNoMinimum(const PatchNode& n, const PatchForest& forest, double negligible) const override {
    return conesProveNoMinimum(n, criticalDirections(n.ball)) ||
           pointHoldsNoMinimum(n, forest, q_, gradient_, negligible);
  }
  void startRanks(const StartSet& start, double* out) const override {
    const double* x = start.px.data();
    const double* y = start.py.data();
    const double* z = start.pz.data();
    const double qx = q_.x(), qy = q_.y(), qz = q_.z();
    for (std::size_t k = 0; k < start.px.size(); ++k) {
      const double dx = x[k] - qx, dy = y[k] - qy, dz = z[k] - qz;
      out[k] = dx * dx + dy * dy + dz * dz;
    }
  }
  // lowerBound() of each node where its ball says it may be below `below`.
  void startBounds(const StartSet& start, double below, double* out) const override {
    const double* x = start.cx.data();
    const double* y = start.cy.data();
    const double* z = start.cz.data();
    const double* r = start.radius.data();
    const double qx = q_.x(), qy = q_.y(), qz = q_.z();
    for (std::size_t k = 0; k < start.cx.size(); ++k) {
      const double dx = qx - x[k], dy = qy - y[k], dz = qz - z[k], reach = below + r[k];
      out[k] = dx * dx + dy * dy + dz * dz < 1.0000001 * reach * reach ? 0.0 : std::numeric_limits<double>::infinity();
    }
    for (std::size_t k = 0; k < start.cx.size(); ++k)
      if (out[k] == 0) out[k] = lowerBound(*start.nodes[k]);
  }

 private:
  /// The nearest distance over the piece by certifyDistanceExtreme, its forms halved at most `halvings` times.
  double nearestBound(const PatchNode& n, double enough, int halvings) const {
    const DistanceExtreme e = certifyDistanceExtreme(n.net, q_, false, true, enough, halvings);
    return e.proved ? std::max(lowerBound(n), e.value) : tightLowerBound(n);
  }
  Eigen::Vector3d q_;
  double floor_;
  mutable BernsteinScratch scratch_;  // one objective per query and thread
  mutable GradientScratch gradient_;
};

/// −d·S: its minimiser is a support point in direction d.
class SupportObjective final : public Objective {
 public:
  SupportObjective(const Eigen::Vector3d& d, double modelSize) : d_(d), size_(modelSize) {}
  double value(const Eigen::Vector3d& p) const override { return -d_.dot(p); }
  // The convex hull of the control points holds the subpatch, so max d·P over them bounds d·S; much tighter
  // than the ball at a pole, where every cell along the collapsed edge touches the extreme point. Widened by
  // the ball's rounding allowance.
  double lowerBound(const PatchNode& n) const override {
    double most = -std::numeric_limits<double>::infinity();
    for (const Eigen::Vector3d& p : n.points) most = std::max(most, d_.dot(p));
    return -most - 256 * std::numeric_limits<double>::epsilon() * (n.ball.center.cwiseAbs().maxCoeff() + n.ball.radius);
  }
  Cone criticalDirections(const BoundingSphere&) const override { return makeCone(d_.normalized(), 0.0); }
  void derivatives(const SurfaceDerivatives& s, Eigen::Vector2d& g, Eigen::Matrix2d& H) const override {
    g << -d_.dot(s.du), -d_.dot(s.dv);
    H << -d_.dot(s.duu), -d_.dot(s.duv), -d_.dot(s.duv), -d_.dot(s.dvv);
  }
  double leafScale(const BoundingSphere&) const override { return size_; }
  bool provesNoMinimum(const PatchNode& n, const PatchForest& forest, double negligible) const override {
    return conesProveNoMinimum(n, criticalDirections(n.ball)) ||
           supportHoldsNoMinimum(n, forest, d_, gradient_, negligible);
  }

 private:
  Eigen::Vector3d d_;
  double size_;
  mutable GradientScratch gradient_;  // one objective per query and thread
};

}  // namespace unidist::nurbs
