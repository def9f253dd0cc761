#include "nurbs/support_tube.h"

#include "nurbs/bernstein_product.h"
#include "nurbs/binomial.h"
#include "nurbs/support_bound.h"

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

/// Proved outside the tube of radius s about the circle (radius R) from the node's control points alone, whose
/// hull holds the node: all of them beyond the tube's slab on one side (the distance to the circle is at least
/// the height over its plane), or all within R − s of the axis (the distance to the axis is convex, so it is
/// largest over the hull at one of them). A node far from the tube is settled without its quartic.
bool outsideByHull(const std::vector<Eigen::Vector3d>& points, const Eigen::Vector3d& centre,
                   const Eigen::Vector3d& axis, double R, double s) {
  double low = std::numeric_limits<double>::infinity(), high = -low, farthest = 0;
  for (const Eigen::Vector3d& x : points) {
    const Eigen::Vector3d r = x - centre;
    const double z = axis.dot(r);
    low = std::min(low, z);
    high = std::max(high, z);
    farthest = std::max(farthest, (r - z * axis).squaredNorm());
  }
  return low >= s || high <= -s || std::sqrt(farthest) <= R - s;
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

bool SupportTube::narrowTo(const SupportTube& fresh, double slack) {
  const auto near = [&](const Circle& a, const Circle& b) {
    return (a.centre - b.centre).norm() <= slack && R_ * (a.axis - b.axis).norm() <= slack;
  };
  const bool same = innerIsA_ == fresh.innerIsA_ && std::abs(R_ - fresh.R_) <= slack &&
                    std::abs(inner_ - fresh.inner_) <= slack && near(circleA_, fresh.circleA_) &&
                    near(circleB_, fresh.circleB_) && fresh.outer_ <= outer_;
  if (!same) return false;
  outer_ = fresh.outer_;
  outerSide_.memo = NodeMemo();
  outerSide_.lastNode = nullptr;
  return true;
}

bool SupportTube::covered(const ProvedBoxes& boxes, const PatchNode& node) {
  const auto patch = static_cast<std::size_t>(node.patch);
  if (patch >= boxes.size()) return false;
  return std::any_of(boxes[patch].begin(), boxes[patch].end(), [&](const ProvedBox& b) {
    return b.s0 <= node.s0 && node.s1 <= b.s1 && b.t0 <= node.t0 && node.t1 <= b.t1;
  });
}

std::vector<double>& SupportTube::quarticOf(const RationalBezierPatch& net, const Circle& circle, double s,
                                            double& allowance) {
  const int p = net.degreeU, q = net.degreeV;
  const std::size_t count = net.net.size();
  Scratch& m = scratch_;
  // Every form below is held scaled by its binomials (x̃_ij = C(n,i)·C(m,j)·x_ij): a Bernstein product is then
  // a plain sum of products, one multiply-add per term, unscaled once at the end.
  m.y.resize(count);
  for (auto* v : {&m.axial, &m.w}) v->resize(count);
  double yMax = 0, wMax = 0, reach = 0;
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j <= q; ++j) {
      const auto k = static_cast<std::size_t>(i * (q + 1) + j);
      const double w = net.net[k][3], scale = binomial(p, i) * binomial(q, j);
      const Eigen::Vector3d y = net.net[k].head<3>() - circle.centre * w;
      m.y[k] = scale * y;
      m.axial[k] = scale * circle.axis.dot(y);
      m.w[k] = scale * w;
      yMax = std::max(yMax, y.norm());
      wMax = std::max(wMax, w);
      reach = std::max(reach, net.net[k].head<3>().norm());
    }
  // |y|², (axis·y)² and W², degree (2p, 2q).
  const std::size_t squares = static_cast<std::size_t>((2 * p + 1) * (2 * q + 1));
  for (auto* v : {&m.yy, &m.zz, &m.ww}) v->assign(squares, 0.0);
  addScaledSquare(p, q, m.y.data(), 1.0, m.yy.data());
  addScaledSquare(p, q, m.axial.data(), 1.0, m.zz.data());
  addScaledSquare(p, q, m.w.data(), 1.0, m.ww.data());
  // The quartic u² − 4R²·ρ²·W², u = |y|² + (R² − s²)W², ρ² = |y|² − (axis·y)²: the squares' scaled coefficients
  // are already those of degree (2p, 2q), as the products need.
  const double shift = R_ * R_ - s * s, fourR2 = 4 * R_ * R_;
  for (auto* v : {&m.u, &m.rho2}) v->resize(squares);
  for (std::size_t k = 0; k < squares; ++k) {
    m.u[k] = m.yy[k] + shift * m.ww[k];
    m.rho2[k] = m.yy[k] - m.zz[k];
  }
  std::vector<double>& quartic = m.quartic;
  quartic.assign(static_cast<std::size_t>((4 * p + 1) * (4 * q + 1)), 0.0);
  addScaledSquare(2 * p, 2 * q, m.u.data(), 1.0, quartic.data());
  addScaledProduct(2 * p, 2 * q, m.rho2.data(), m.ww.data(), -fourR2, quartic.data());
  unscaleByBinomials(4 * p, 4 * q, quartic.data());
  // Rounding: each coefficient is a mean of products of means of products; counted per unit of the largest
  // terms, with y's own rounding (ε of |X| + |centre|·W) on top.
  const double uMax = yMax * yMax + std::abs(shift) * wMax * wMax;
  const double terms = (p + 1) * (q + 1) + (2 * p + 1) * (2 * q + 1) + 16;
  const double scale = uMax * uMax + 4 * R_ * R_ * yMax * yMax * wMax * wMax;
  const double ofY = 16 * (uMax + 4 * R_ * R_ * wMax * wMax) * yMax * (reach + circle.centre.norm() * wMax);
  allowance = kEps * (4 * terms * scale + ofY);
  return quartic;
}

bool SupportTube::proved(Side& side, const PatchNode& node, const Circle& circle, double s, bool inside) {
  if (&node != side.lastNode) {
    side.lastResult = verdict(side, node, circle, s, inside);
    side.lastNode = &node;
  }
  return side.lastResult;
}

bool SupportTube::verdict(Side& side, const PatchNode& node, const Circle& circle, double s, bool inside) {
  ProvedBoxes& boxes = side.boxes;
  if (covered(boxes, node)) return true;
  const bool result = side.memo.get(node, [&] {
    // The ball first: the distance to the circle moves by at most the radius over it.
    const double atCentre = distanceToCircle(node.ball.center, circle.centre, circle.axis, R_);
    if (inside ? atCentre + node.ball.radius <= s : atCentre - node.ball.radius >= s) return 1.0;
    if (inside ? atCentre - node.ball.radius > s : atCentre + node.ball.radius < s) return 0.0;  // on the wrong side
    if (!inside && outsideByHull(node.points, circle.centre, circle.axis, R_, s)) return 1.0;
    const RationalBezierPatch& net = node.net;
    const int p = net.degreeU, q = net.degreeV;
    if (2 * std::max(p, q) > kMaxNurbsDegree) return 0.0;  // its degree (4p, 4q) beyond the binomial table
    double allowance = 0;
    std::vector<double>& quartic = quarticOf(net, circle, s, allowance);
    const bool byCoefficients = std::all_of(quartic.begin(), quartic.end(),
                                            [&](double f) { return inside ? f <= -allowance : f >= allowance; });
    if (byCoefficients) return 1.0;
    // Next to the contact the quartic's least value on the outer side is a sliver of the tolerance, which the
    // coefficients reach only at ~1e-5 of a patch (a cross term's coefficients fall below its values). The
    // quartic is convex there: proved so, its extreme is exact to rounding.
    double largest = 0;
    for (double& f : quartic) {
      if (!inside) f = -f;
      largest = std::max(largest, std::abs(f));
    }
    if (!(largest > 0)) return 0.0;
    const SupportBound b = certifyPolynomialMaximum(4 * p, 4 * q, quartic.data(), allowance / largest);
    return b.proved && b.upper <= -allowance ? 1.0 : 0.0;
  }) > 0;
  if (result) {
    const auto patch = static_cast<std::size_t>(node.patch);
    if (patch >= boxes.size()) boxes.resize(patch + 1);
    boxes[patch].push_back({node.s0, node.s1, node.t0, node.t1});
  }
  return result;
}

double SupportTube::gap(const PatchNode& na, const PatchNode& nb) {
  const PatchNode& inner = innerIsA_ ? na : nb;
  const PatchNode& outer = innerIsA_ ? nb : na;
  const Circle& innerCircle = innerIsA_ ? circleA_ : circleB_;
  const Circle& outerCircle = innerIsA_ ? circleB_ : circleA_;
  // The inner side first: a ring's own core circle proves all of it at its root patches.
  const bool innerProved = proved(innerSide_, inner, innerCircle, inner_, true);
  lastUnproved_ = 0;
  if (!innerProved) return -std::numeric_limits<double>::infinity();
  if (!proved(outerSide_, outer, outerCircle, outer_, false)) {
    lastUnproved_ = innerIsA_ ? 1 : -1;
    return -std::numeric_limits<double>::infinity();
  }
  return outer_ - inner_;
}

}  // namespace unidist::nurbs
