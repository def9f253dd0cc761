#include "nurbs/support_tube.h"

#include "nurbs/bernstein_product.h"

#include <Eigen/Eigenvalues>

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace unidist::nurbs {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

/// The principal curvatures k1 <= k2 of the patch at x, positive where it bends away from its normal on the
/// side of `toward`, that unit normal, and the parameter direction of k1's line of curvature; none where the first
/// fundamental form is singular (a pole).
struct Curvatures {
  double k1, k2;
  Eigen::Vector3d point, normal;
  Eigen::Vector2d along1;  // parameters moving along k1's principal direction, one unit of length per unit
};
std::optional<Curvatures> principalCurvatures(const RationalBezierPatch& patch, const Eigen::Vector2d& x,
                                              const Eigen::Vector3d& toward) {
  const SurfaceDerivatives d = patch.derivatives(x[0], x[1]);
  Eigen::Vector3d normal = d.du.cross(d.dv);
  if (!(normal.norm() > 0)) return std::nullopt;
  normal = normal.dot(toward) >= 0 ? Eigen::Vector3d(normal.normalized()) : Eigen::Vector3d(-normal.normalized());
  Eigen::Matrix2d G, H;
  G << d.du.squaredNorm(), d.du.dot(d.dv), d.du.dot(d.dv), d.dv.squaredNorm();
  H << -normal.dot(d.duu), -normal.dot(d.duv), -normal.dot(d.duv), -normal.dot(d.dvv);
  const Eigen::LLT<Eigen::Matrix2d> llt(G);
  if (llt.info() != Eigen::Success || !(G.determinant() > 1e-20 * G.squaredNorm())) return std::nullopt;
  const Eigen::Matrix2d Li = Eigen::Matrix2d(llt.matrixL()).inverse();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(Li * H * Li.transpose());
  if (eigen.info() != Eigen::Success) return std::nullopt;
  // The orthonormal tangent frame is [du dv]·L⁻ᵀ: an eigenvector v in it is the parameter direction L⁻ᵀv.
  Curvatures c{eigen.eigenvalues()[0], eigen.eigenvalues()[1], d.point, normal,
               Li.transpose() * eigen.eigenvectors().col(0)};
  if (!std::isfinite(c.k1) || !std::isfinite(c.k2)) return std::nullopt;
  return c;
}

/// The centre of curvature of the k2 direction (across a ring's tube: a point of its core circle).
Eigen::Vector3d focalPoint(const Curvatures& c) { return c.point - c.normal / c.k2; }

double distanceToCircle(const Eigen::Vector3d& x, const Eigen::Vector3d& centre, const Eigen::Vector3d& axis, double R) {
  const Eigen::Vector3d r = x - centre;
  const double z = axis.dot(r);
  return std::hypot((r - z * axis).norm() - R, z);
}

}  // namespace

std::optional<SupportTube> SupportTube::fit(const SeparatorContact& contact, double needed, double tolerance) {
  const auto& [patchA, xA, patchB, xB, X_AB, pA, pB] = contact;
  const Eigen::Vector3d gap = pB - pA;
  const double d = gap.norm();
  if (!(d > 0) || !(needed > 0) || !(tolerance > 0)) return std::nullopt;
  const Eigen::Vector3d n = gap / d;
  const Eigen::Matrix3d& R = X_AB.linear();
  // Each side's curvatures bending away from the other (own frame); the inner side is a saddle curving toward
  // the other along its first principal direction. Of two saddles, the one curving toward the other more.
  const RationalBezierPatch* patches[2] = {&patchA, &patchB};
  const Eigen::Vector2d xs[2] = {xA, xB};
  const Eigen::Vector3d towards[2] = {n, -(R.transpose() * n)};
  std::optional<Curvatures> at[2];
  for (int side = 0; side < 2; ++side) {
    at[side] = principalCurvatures(*patches[side], xs[side], towards[side]);
    if (at[side] && !(at[side]->k1 < 0 && at[side]->k2 > 0)) at[side].reset();
  }
  if (!at[0] && !at[1]) return std::nullopt;
  SupportTube tube;
  tube.innerIsA_ = at[0] && (!at[1] || -at[0]->k1 * at[1]->k2 >= -at[1]->k1 * at[0]->k2);
  const int side = tube.innerIsA_ ? 0 : 1;
  const Curvatures& c = *at[side];
  // The circle through three centres of curvature across the tube, at the contact and a chord either side along
  // the line of curvature that bends toward the outer side: a ring's core circle itself, whatever the latitude
  // of the contact on its tube (the osculating torus at the contact would tilt away from it).
  const double chord = 0.25 / -c.k1;
  // Chords either side where the patch has room, else two on the side that has (a contact on a patch edge).
  const auto room = [&](double sign) {
    double t = std::numeric_limits<double>::infinity();
    for (int i = 0; i < 2; ++i) {
      const double step = sign * c.along1[i];
      if (step > 0) t = std::min(t, (1 - xs[side][i]) / step);
      if (step < 0) t = std::min(t, -xs[side][i] / step);
    }
    return 0.9 * t;
  };
  const double ahead = std::min(chord, room(1)), behind = std::min(chord, room(-1));
  double offsets[2] = {ahead, -behind};
  if (std::min(ahead, behind) < 0.25 * chord) {
    const double wide = ahead >= behind ? std::min(2 * chord, room(1)) : -std::min(2 * chord, room(-1));
    offsets[0] = wide;
    offsets[1] = 0.5 * wide;
  }
  if (!(std::abs(offsets[0]) >= chord / 16)) return std::nullopt;
  Eigen::Vector3d focal[3] = {focalPoint(c), Eigen::Vector3d::Zero(), Eigen::Vector3d::Zero()};
  for (int k = 1; k <= 2; ++k) {
    const Eigen::Vector2d x = (xs[side] + offsets[k - 1] * c.along1).cwiseMax(0.0).cwiseMin(1.0);
    const std::optional<Curvatures> ck = principalCurvatures(*patches[side], x, towards[side]);
    if (!ck || !(ck->k2 > 0)) return std::nullopt;
    focal[k] = focalPoint(*ck);
  }
  const Eigen::Vector3d u = focal[1] - focal[0], v = focal[2] - focal[0];
  const Eigen::Vector3d normal = u.cross(v);
  if (!(normal.squaredNorm() > 1e-24 * u.squaredNorm() * v.squaredNorm())) return std::nullopt;  // collinear
  const Eigen::Vector3d ownCentre =
      focal[0] + (u.squaredNorm() * v.cross(normal) + v.squaredNorm() * normal.cross(u)) / (2 * normal.squaredNorm());
  tube.R_ = (focal[0] - ownCentre).norm();
  const double r = 1 / c.k2;
  tube.inner_ = r + 0.25 * tolerance;
  // The outer side proved outside the wider tube: the gap `needed`, and the rounding margin the pair search
  // takes off every bound (a few hundred ulps of the models' extent).
  tube.outer_ = tube.inner_ + needed + 1024 * kEps * (ownCentre.norm() + tube.R_ + pA.norm() + pB.norm());
  // Only a tube no wider than its core circle is inside exactly where its quartic is negative (beyond, the
  // quartic's other factor changes sign near the axis).
  if (!(tube.outer_ <= tube.R_) || !std::isfinite(tube.R_)) return std::nullopt;
  const Eigen::Vector3d ownAxis = normal.normalized();
  const Eigen::Vector3d centre = tube.innerIsA_ ? ownCentre : Eigen::Vector3d(X_AB * ownCentre);
  const Eigen::Vector3d axis = tube.innerIsA_ ? ownAxis : Eigen::Vector3d(R * ownAxis);
  tube.circleA_ = {centre, axis};
  tube.circleB_ = {X_AB.inverse() * centre, R.transpose() * axis};
  return tube;
}

bool SupportTube::covered(const std::vector<ProvedBox>& boxes, const PatchNode& node) {
  return std::any_of(boxes.begin(), boxes.end(), [&](const ProvedBox& b) {
    return b.patch == node.patch && b.s0 <= node.s0 && node.s1 <= b.s1 && b.t0 <= node.t0 && node.t1 <= b.t1;
  });
}

bool SupportTube::proved(NodeMemo& memo, std::vector<ProvedBox>& boxes, const PatchNode& node, const Circle& circle,
                         double s, bool inside) {
  if (covered(boxes, node)) return true;
  const bool result = memo.get(node, [&] {
      // The ball first: the distance to the circle moves by at most the radius over it.
    const double atCentre = distanceToCircle(node.ball.center, circle.centre, circle.axis, R_);
    if (inside ? atCentre + node.ball.radius <= s : atCentre - node.ball.radius >= s) return 1.0;
    if (inside ? atCentre - node.ball.radius > s : atCentre + node.ball.radius < s) return 0.0;  // on the wrong side
    // The quartic (|y|² + (R² − s²)W² )² − 4R²(|y|² − z²)W², y = X − centre·W, z = axis·y, in Bernstein form.
    const RationalBezierPatch& net = node.net;
    const int p = net.degreeU, q = net.degreeV;
    if (2 * std::max(p, q) > kMaxNurbsDegree) return 0.0;  // beyond the Bernstein products' fixed rows
    const std::size_t count = net.net.size();
    std::vector<Eigen::Vector3d> y(count);
    std::vector<double> z(count), w(count);
    double yMax = 0, wMax = 0, reach = 0;
    for (std::size_t k = 0; k < count; ++k) {
      w[k] = net.net[k][3];
      y[k] = net.net[k].head<3>() - circle.centre * w[k];
      z[k] = circle.axis.dot(y[k]);
      yMax = std::max(yMax, y[k].norm());
      wMax = std::max(wMax, w[k]);
      reach = std::max(reach, net.net[k].head<3>().norm());
    }
    const auto times = [](double a, double b) { return a * b; };
    std::vector<double> yy, zz, ww;
    product(p, q, y, p, q, y, dotOf, 0.0, yy);
    product(p, q, z, p, q, z, times, 0.0, zz);
    product(p, q, w, p, q, w, times, 0.0, ww);
    // One product for both terms: pairs (u, ρ²-form) times (u, W²), u = |y|² + (R² − s²)W².
    const double shift = R_ * R_ - s * s, fourR2 = 4 * R_ * R_;
    std::vector<Eigen::Vector2d> left(yy.size()), right(yy.size());
    for (std::size_t k = 0; k < yy.size(); ++k) {
      left[k] = {yy[k] + shift * ww[k], yy[k] - zz[k]};
      right[k] = {left[k][0], ww[k]};
    }
    std::vector<double> quartic;
    product(2 * p, 2 * q, left, 2 * p, 2 * q, right,
            [fourR2](const Eigen::Vector2d& l, const Eigen::Vector2d& r) { return l[0] * r[0] - fourR2 * l[1] * r[1]; },
            0.0, quartic);
    // Rounding: each coefficient is a mean of products of means of products; counted per unit of the largest
    // terms, with y's own rounding (ε of |X| + |centre|·W) on top.
    const double uMax = yMax * yMax + std::abs(shift) * wMax * wMax;
    const double terms = (p + 1) * (q + 1) + (2 * p + 1) * (2 * q + 1) + 16;
    const double scale = uMax * uMax + 4 * R_ * R_ * yMax * yMax * wMax * wMax;
    const double allowance =
        kEps * (4 * terms * scale + 16 * (uMax + 4 * R_ * R_ * wMax * wMax) * yMax * (reach + circle.centre.norm() * wMax));
    for (const double f : quartic) {
      if (!(inside ? f <= -allowance : f >= allowance)) return 0.0;
    }
      return 1.0;
  }) > 0;
  if (result) boxes.push_back({node.patch, node.s0, node.s1, node.t0, node.t1});
  return result;
}

double SupportTube::gap(const PatchNode& na, const PatchNode& nb) {
  const PatchNode& inner = innerIsA_ ? na : nb;
  const PatchNode& outer = innerIsA_ ? nb : na;
  const Circle& innerCircle = innerIsA_ ? circleA_ : circleB_;
  const Circle& outerCircle = innerIsA_ ? circleB_ : circleA_;
  // The inner side first: a ring's own core circle proves all of it at its root patches.
  const bool innerProved = proved(innerMemo_, innerBoxes_, inner, innerCircle, inner_, true);
  lastUnproved_ = 0;
  if (!innerProved) return -std::numeric_limits<double>::infinity();
  if (!proved(outerMemo_, outerBoxes_, outer, outerCircle, outer_, false)) {
    lastUnproved_ = innerIsA_ ? 1 : -1;
    return -std::numeric_limits<double>::infinity();
  }
  return outer_ - inner_;
}

}  // namespace unidist::nurbs
