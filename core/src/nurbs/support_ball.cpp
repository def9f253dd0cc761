#include "nurbs/support_ball.h"

#include "nurbs/support_bound.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::nurbs {
namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kExactReach = 2;  // a node within this many of its radii of the touching point is certified exactly
constexpr double kCircleOfMinima = 1e-6;  // relative: the outer surface curves toward the inner as much as it can
constexpr double kSameDirection = 0.99;  // cosine: a closest pair's normal and segment are parallel but for rounding
constexpr double kUmbilic = 1e-9;  // relative spread of the principal curvatures: a sphere's point
constexpr double kMinMargin = 0.002;  // of the inner surface's curvature: a ball fitting by less is not used

/// The least normal curvature of the patch at x, curving away from the direction `toward` (positive: the
/// surface bends away from a point on that side), or NaN where the first fundamental form is singular; with
/// `spread`, the greatest less the least.
double leastCurvatureAway(const RationalBezierPatch& patch, const Eigen::Vector2d& x, const Eigen::Vector3d& toward,
                          double* spread = nullptr) {
  const SurfaceDerivatives d = patch.derivatives(x[0], x[1]);
  Eigen::Matrix2d G, H;
  G << d.du.squaredNorm(), d.du.dot(d.dv), d.du.dot(d.dv), d.dv.squaredNorm();
  H << -toward.dot(d.duu), -toward.dot(d.duv), -toward.dot(d.duv), -toward.dot(d.dvv);
  const Eigen::LLT<Eigen::Matrix2d> llt(G);
  if (llt.info() != Eigen::Success || !(G.determinant() > 1e-20 * G.squaredNorm())) return std::nan("");
  const Eigen::Matrix2d L = llt.matrixL();
  const Eigen::Matrix2d Li = L.inverse();
  const Eigen::Matrix2d M = Li * H * Li.transpose();  // the shape operator in an orthonormal tangent frame
  const double mean = 0.5 * (M(0, 0) + M(1, 1));
  const double half = std::hypot(0.5 * (M(0, 0) - M(1, 1)), 0.5 * (M(0, 1) + M(1, 0)));
  if (spread) *spread = 2 * half;
  return mean - half;
}

/// The unit normal of the patch at x on the side of unit `direction`; `direction` itself where the normal is not
/// defined (a pole) or is not within a few degrees of it (not a closest pair).
Eigen::Vector3d unitNormalNear(const RationalBezierPatch& patch, const Eigen::Vector2d& x, const Eigen::Vector3d& direction) {
  const SurfaceDerivatives d = patch.derivatives(x[0], x[1]);
  const Eigen::Vector3d normal = d.du.cross(d.dv);
  const double length = normal.norm();
  if (!(length > 1e-12 * d.du.norm() * d.dv.norm())) return direction;
  const Eigen::Vector3d unit = normal.dot(direction) >= 0 ? Eigen::Vector3d(normal / length) : Eigen::Vector3d(-normal / length);
  return unit.dot(direction) >= kSameDirection ? unit : direction;
}

/// ρ with the two margins equal: the inner surface's least curvature kInner above 1/ρ by as much as the outer's
/// kOuter is above −1/(ρ + d). The first margin grows with ρ, the second shrinks.
double balancedRadius(double kInner, double kOuter, double d) {
  double lo = 1 / kInner, hi = kOuter < 0 ? -1 / kOuter - d : 1e6 * lo;
  for (int k = 0; k < 60; ++k) {
    const double rho = std::sqrt(lo * hi);
    if (kInner - 1 / rho < kOuter + 1 / (rho + d)) {
      lo = rho;
    } else {
      hi = rho;
    }
  }
  return std::sqrt(lo * hi);
}

double farthestControlPoint(const PatchNode& n, const Eigen::Vector3d& c) {
  double far = 0;
  for (const Eigen::Vector3d& p : n.points) far = std::max(far, (p - c).squaredNorm());
  return std::sqrt(far);
}

}  // namespace

std::optional<SupportBall> SupportBall::fit(const SeparatorContact& contact) {
  const auto& [patchA, xA, patchB, xB, X_AB, pA, pB] = contact;
  const Eigen::Vector3d gap = pB - pA;
  const double d = gap.norm();
  if (!(d > 0)) return std::nullopt;
  const Eigen::Vector3d n = gap / d;
  double spreadA = 0, spreadB = 0;
  // Curvatures about each surface's own normal: at a gap of 1e-8 of the size the segment's direction is off by
  // ~1e-8 rad, which leaks that much of the second derivatives' tangential part into them (a unit sphere's read
  // 1 − 1.4e-8, its ball then off-centre by as much and no circle of minima certified below that).
  const Eigen::Vector3d nB = -(X_AB.linear().transpose() * n);
  const double kA = leastCurvatureAway(patchA, xA, unitNormalNear(patchA, xA, n), &spreadA);
  const double kB = leastCurvatureAway(patchB, xB, unitNormalNear(patchB, xB, nB), &spreadB);
  if (!std::isfinite(kA) || !std::isfinite(kB)) return std::nullopt;
  // The inner side needs a strictly convex contact; the outer side may curve toward it by less than the larger
  // ball (both convex is the support plane's case). A ball that barely fits leaves no margin for the
  // certificates to settle anything and costs them at every pair, but for one that fits exactly: a circle of
  // minima (the outer surface curving toward the inner as much as it can, about the inner's centre of
  // curvature), where the certificates settle the pairs along it by subdividing their forms across it. The
  // radius for each choice of inner side, NaN where none fits:
  // An inner side curving alike every way (a sphere) gets its own radius: its far side is then exact for every
  // node at any size (|X − cW|² − ρ²W² vanishes), and the margin is all the outer side's.
  const auto radiusFor = [d](double kInner, double spreadInner, double kOuter) {
    if (!(kInner > 0)) return std::nan("");
    if (kOuter < 0 && std::abs(1 / kInner + d + 1 / kOuter) <= kCircleOfMinima * (1 / kInner + d)) return 1 / kInner;
    if (kOuter < 0 && !(1 / kInner + d < -1 / kOuter)) return std::nan("");
    if (spreadInner <= kUmbilic * kInner) return 1 / kInner;
    const double rho = balancedRadius(kInner, kOuter, d);
    return kOuter >= 0 || kInner - 1 / rho > kMinMargin * kInner ? rho : std::nan("");
  };
  const double rhoB = radiusFor(kB, spreadB, kA), rhoA = radiusFor(kA, spreadA, kB);
  if (std::isnan(rhoB) && std::isnan(rhoA)) return std::nullopt;
  SupportBall ball;
  ball.innerIsB_ = !std::isnan(rhoB) && (kB >= kA || std::isnan(rhoA));
  ball.radius_ = ball.innerIsB_ ? rhoB : rhoA;
  // The centre along the inner surface's own normal: where the gap is small the segment's direction is
  // rounding over a short length (1e-10 rad at a gap of 1e-6 of the size), which puts a zero-margin ball's centre
  // off the axis it must lie on by more than a tight tolerance.
  const Eigen::Matrix3d& R = X_AB.linear();
  ball.centreA_ = ball.innerIsB_
                      ? Eigen::Vector3d(pB - ball.radius_ * (R * unitNormalNear(patchB, xB, -(R.transpose() * n))))
                      : Eigen::Vector3d(pA - ball.radius_ * unitNormalNear(patchA, xA, n));
  ball.centreB_ = X_AB.inverse() * ball.centreA_;
  ball.contactA_ = pA;
  ball.contactB_ = X_AB.inverse() * pB;
  return ball;
}

double SupportBall::certified(NodeMemo& memo, const PatchNode& node, const PatchNode* parent,
                              const Eigen::Vector3d& centre, const Eigen::Vector3d& contact, bool farthest,
                              double enough) {
  if (const double* known = memo.find(node)) return *known;
  // The parent's extreme holds for the node: where it already does, no certificate (a sphere's children all
  // inherit its radius).
  const double* ofParent = parent ? memo.find(*parent) : nullptr;
  const double inherited = ofParent ? *ofParent : (farthest ? kInf : 0.0);
  double value = inherited;
  if (farthest ? !(inherited <= enough) : !(inherited >= enough)) {
    const bool exact = (node.ball.center - contact).norm() <= kExactReach * node.ball.radius;
    const DistanceExtreme e = certifyDistanceExtreme(node.net, centre, farthest, exact, enough);
    if (e.proved) value = farthest ? std::min(value, e.value) : std::max(value, e.value);
  }
  memo.set(node, value);
  return value;
}

double SupportBall::gap(const PatchNode& na, const PatchNode& nb, double needed, const PatchNode* parentA,
                        const PatchNode* parentB) {
  const PatchNode& inner = innerIsB_ ? nb : na;
  const PatchNode& outer = innerIsB_ ? na : nb;
  const PatchNode* innerParent = innerIsB_ ? parentB : parentA;
  const PatchNode* outerParent = innerIsB_ ? parentA : parentB;
  const Eigen::Vector3d& cInner = innerIsB_ ? centreB_ : centreA_;
  const Eigen::Vector3d& cOuter = innerIsB_ ? centreA_ : centreB_;
  // Cheap bounds first: the farthest control point (|x − c| is convex, so its maximum over the hull is at one),
  // and the nearest the outer node's ball and frame box allow.
  double far = farthestControlPoint(inner, cInner);
  double near = std::max((outer.ball.center - cOuter).norm() - outer.ball.radius, boxDistance(outer, cOuter));
  if (near - far >= needed) return near - far;
  // A certified extreme is no better than the surface's own corners: certify only when they leave room.
  double cornerFar = 0, cornerNear = kInf;  // squared first: one square root each
  for (std::size_t k = 0; k < 4; ++k) {
    cornerFar = std::max(cornerFar, (inner.corners[k] - cInner).squaredNorm());
    cornerNear = std::min(cornerNear, (outer.corners[k] - cOuter).squaredNorm());
  }
  cornerFar = std::sqrt(cornerFar);
  cornerNear = std::sqrt(cornerNear);
  if (cornerNear - cornerFar < needed) return near - far;
  // The side that limits first: no near bound can settle the pair while the far one leaves no room.
  const Eigen::Vector3d& pInner = innerIsB_ ? contactB_ : contactA_;
  const Eigen::Vector3d& pOuter = innerIsB_ ? contactA_ : contactB_;
  if (cornerNear - far < needed)
    far = std::min(far, certified(innerIsB_ ? farB_ : farA_, inner, innerParent, cInner, pInner, true,
                                  cornerNear - needed));
  if (cornerNear - far < needed) return near - far;
  if (near - far < needed)
    near = std::max(near, certified(innerIsB_ ? nearA_ : nearB_, outer, outerParent, cOuter, pOuter, false,
                                    needed + far));
  return near - far;
}

}  // namespace unidist::nurbs
