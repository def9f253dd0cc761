#include "nurbs/patch_tree.h"

#include "nurbs/binomial.h"
#include "nurbs/reparametrise.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::nurbs {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Slack added to every cone angle: the cones are computed in floating point from rounded nets.
constexpr double kAngleSlack = 1e-9;
// What the cone tests allow for (radians): the slack coneTowards leaves out of its cosine and sine, and rounding.
constexpr double kConeSlack = 2 * kAngleSlack;

double angleBetween(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  // atan2 of |a x b| and a·b stays accurate near 0 and π, unlike acos.
  return std::atan2(a.cross(b).norm(), a.dot(b));
}

/// De Casteljau at a on points[0..n]: left gets the part over [0,a], right the part over [a,1].
void splitRow(const std::vector<Eigen::Vector4d>& points, double a, std::vector<Eigen::Vector4d>& left,
              std::vector<Eigen::Vector4d>& right) {
  std::vector<Eigen::Vector4d> work = points;
  const std::size_t n = points.size();
  left.assign(n, Eigen::Vector4d::Zero());
  right.assign(n, Eigen::Vector4d::Zero());
  for (std::size_t level = 0; level < n; ++level) {
    left[level] = work[0];
    right[n - 1 - level] = work[n - 1 - level];
    for (std::size_t i = 0; i + level + 1 < n; ++i) work[i] = (1 - a) * work[i] + a * work[i + 1];
  }
}

}  // namespace

/// Bernstein coefficients (up to positive factors per coefficient) of the numerator X_u W − X W_u of Su:
/// p Σ B_{i'}^{p-1}(u) B_k^p(u) B_j^q(v) B_l^q(v) [D((i'+1,j),(k,l)) − D((i',j),(k,l))], grouped by degree-
/// elevated index (i'+k, j+l), where D(a, b) = w_b X_a − w_a X_b = w_a w_b (P_a − P_b) (computed from the
/// Euclidean points so that equal points give exactly zero). With transpose the roles of u and v swap.
std::vector<Eigen::Vector3d> derivativeCoefficients(const RationalBezierPatch& patch, bool transpose) {
  const int p = transpose ? patch.degreeV : patch.degreeU, q = transpose ? patch.degreeU : patch.degreeV;
  std::vector<Eigen::Vector3d> P(static_cast<std::size_t>((p + 1) * (q + 1)));
  std::vector<double> w(P.size());
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j <= q; ++j) {
      const Eigen::Vector4d& h = transpose ? patch.at(j, i) : patch.at(i, j);
      const auto k = static_cast<std::size_t>(i * (q + 1) + j);
      P[k] = h.head<3>() / h[3];
      w[k] = h[3];
    }
  const auto idx = [q](int i, int j) { return static_cast<std::size_t>(i * (q + 1) + j); };
  const int R = 2 * p - 1, S = 2 * q;
  std::vector<Eigen::Vector3d> coef(static_cast<std::size_t>((R + 1) * (S + 1)), Eigen::Vector3d::Zero());
  // The v-factors C(q,j) C(q,l) / C(2q,j+l) once (this runs for every new tree node).
  std::vector<double> fv(static_cast<std::size_t>((q + 1) * (q + 1)));
  for (int j = 0; j <= q; ++j)
    for (int l = 0; l <= q; ++l)
      fv[static_cast<std::size_t>(j * (q + 1) + l)] = binomial(q, j) * binomial(q, l) / binomial(S, j + l);
  for (int i = 0; i < p; ++i)
    for (int k = 0; k <= p; ++k) {
      const double fu = binomial(p - 1, i) * binomial(p, k) / binomial(R, i + k);
      for (int j = 0; j <= q; ++j) {
        const std::size_t a = idx(i + 1, j), b = idx(i, j);
        for (int l = 0; l <= q; ++l) {
          const std::size_t c = idx(k, l);
          const double f = fu * fv[static_cast<std::size_t>(j * (q + 1) + l)] * w[c];
          coef[static_cast<std::size_t>((i + k) * (S + 1) + j + l)] += f * (w[a] * (P[a] - P[c]) - w[b] * (P[b] - P[c]));
        }
      }
    }
  return coef;
}

Cone coneOfVectors(const std::vector<Eigen::Vector3d>& vectors) {
  // A coefficient that is zero in exact arithmetic (the collapsed edge of a pole) comes out of subdivision as
  // rounding noise pointing anywhere; counted, it would open the cone to everything near every pole (and how
  // often that happens depends on the model's scale). Vectors at rounding level of the largest are dropped.
  // Axis: the mean of the unit vectors; angle: the widest of them, by one atan2 (this runs for every new tree
  // node, so no trigonometry per vector).
  double largest = 0;
  for (const Eigen::Vector3d& v : vectors) largest = std::max(largest, v.squaredNorm());
  const double noise = 1e-24 * largest;  // squared: 1e-12 of the largest norm
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& v : vectors)
    if (const double n2 = v.squaredNorm(); n2 > noise) sum += v / std::sqrt(n2);
  const double length = sum.norm();
  if (!(length > 0)) return Cone{};
  const Eigen::Vector3d axis = sum / length;
  double leastCos = 2;
  const Eigen::Vector3d* widest = nullptr;
  for (const Eigen::Vector3d& v : vectors)
    if (const double n2 = v.squaredNorm(); n2 > noise) {
      if (const double c = axis.dot(v) / std::sqrt(n2); c < leastCos) leastCos = c, widest = &v;
    }
  if (!(leastCos > 0)) return Cone{};  // a vector at π/2 or beyond: the cone would not be convex
  const double angle = angleBetween(axis, *widest) + kAngleSlack;
  if (angle >= 0.5 * kPi) return Cone{};
  return makeCone(axis, angle);
}

Cone crossCone(const Cone& cu, const Cone& cv) {
  if (cu.all || cv.all) return Cone{};
  const double beta = angleBetween(cu.axis, cv.axis), sum = cu.angle + cv.angle;
  if (!(sum < beta && beta < kPi - sum)) return Cone{};
  const double su = std::sin(cu.angle), sv = std::sin(cv.angle);
  const double s = std::sqrt(su * su + 2 * su * sv * std::abs(std::cos(beta)) + sv * sv) / std::sin(beta);
  if (!(s < 1)) return Cone{};
  const Eigen::Vector3d axis = cu.axis.cross(cv.axis);
  return makeCone(axis.normalized(), std::asin(s) + kAngleSlack);
}

Cone makeCone(const Eigen::Vector3d& axis, double angle) {
  Cone c;
  c.axis = axis;
  c.angle = angle;
  c.all = false;
  c.cosine = std::cos(angle);
  c.sine = std::sin(angle);
  return c;
}

Cone coneTowards(const Eigen::Vector3d& q, const Eigen::Vector3d& c, double r) {
  const Eigen::Vector3d d = q - c;
  const double n = d.norm();
  if (!(n > r * (1 + 1e-12))) return Cone{};
  Cone out;
  out.axis = d / n;
  out.all = false;
  out.sine = std::min(1.0, r / n);
  out.cosine = std::sqrt(std::max(0.0, 1 - out.sine * out.sine));  // of the angle without its slack
  out.angle = std::asin(out.sine) + kAngleSlack;
  return out;
}

namespace {

/// With S the sum of the two cones' angles and an angle θ given by its cosine and sine: whether θ <= S, i.e.
/// sin(θ − S) <= 0 (always when S >= π/2). The slack is in radians (sines of small angles), so tiny cones stay
/// tiny.
bool withinSumOfAngles(const Cone& a, const Cone& b, double cosTheta, double sinTheta) {
  const double cosSum = a.cosine * b.cosine - a.sine * b.sine, sinSum = a.sine * b.cosine + a.cosine * b.sine;
  return cosSum <= 0 || sinTheta * cosSum - cosTheta * sinSum <= kConeSlack;
}

}  // namespace

// φ the angle between the axes and φ' = min(φ, π − φ), with cos φ' = |a·b| and sin φ' = |a x b| (both accurate
// for small angles, where a cosine alone is not): some direction of a within b or −b when φ' <= S.
bool meetsEitherWay(const Cone& a, const Cone& b) {
  if (a.all || b.all) return true;
  return withinSumOfAngles(a, b, std::abs(a.axis.dot(b.axis)), a.axis.cross(b.axis).norm());
}

// Some pair orthogonal when |φ − π/2| <= S, i.e. ψ = π/2 − φ' <= S (cos ψ = |a x b|, sin ψ = |a·b|).
bool canBeOrthogonal(const Cone& a, const Cone& b) {
  if (a.all || b.all) return true;
  return withinSumOfAngles(a, b, a.axis.cross(b.axis).norm(), std::abs(a.axis.dot(b.axis)));
}

bool mayHoldCritical(const PatchNode& n, const Cone& towards, bool corners) {
  if (towards.all || n.normal.all || meetsEitherWay(n.normal, towards)) return true;
  const bool edgeU = n.s0 == 0 || n.s1 == 1, edgeV = n.t0 == 0 || n.t1 == 1;  // edges s = const, t = const
  if (corners && edgeU && edgeV) return true;
  // Along an edge s = const the extremum of the edge curve needs the direction orthogonal to Sv; and vice versa.
  return (edgeU && canBeOrthogonal(n.cv, towards)) || (edgeV && canBeOrthogonal(n.cu, towards));
}

BoundingSphere ballOfNet(const std::vector<Eigen::Vector4d>& net) {
  std::vector<Eigen::Vector3d> points;
  points.reserve(net.size());
  for (const Eigen::Vector4d& h : net) points.push_back(h.head<3>() / h[3]);
  return ballOfPoints(points);
}

BoundingSphere ballOfPoints(const std::vector<Eigen::Vector3d>& points) {
  Aabb box;
  for (const Eigen::Vector3d& p : points) box.extend(p);
  BoundingSphere b;
  b.center = box.center();
  for (const Eigen::Vector3d& p : points) b.radius = std::max(b.radius, (p - b.center).norm());
  // Widen for the rounding of the subdivided net and of this computation (relative to the coordinates' size).
  const double scale = b.center.cwiseAbs().maxCoeff() + b.radius;
  b.radius += 256 * std::numeric_limits<double>::epsilon() * scale;
  return b;
}

void tangentCones(const RationalBezierPatch& patch, Cone& cu, Cone& cv) {
  cu = coneOfVectors(derivativeCoefficients(patch, false));
  cv = coneOfVectors(derivativeCoefficients(patch, true));
}

namespace {

/// The frame box of a node: third axis along its normal cone (or Su x Sv of the cone axes), first along Su.
FrameBox frameBoxOf(const std::vector<Eigen::Vector3d>& points, const BoundingSphere& ball, const Cone& cu,
                    const Cone& cv, const Cone& normal) {
  FrameBox box;
  Eigen::Vector3d e3 = Eigen::Vector3d::UnitZ();
  if (!normal.all) {
    e3 = normal.axis;
  } else if (!cu.all && !cv.all && cu.axis.cross(cv.axis).norm() > 1e-3) {
    e3 = cu.axis.cross(cv.axis).normalized();
  }
  Eigen::Vector3d e1 = cu.all ? Eigen::Vector3d::UnitX() : cu.axis;
  e1 -= e1.dot(e3) * e3;
  if (!(e1.norm() > 1e-3)) e1 = e3.unitOrthogonal();
  e1.normalize();
  box.axes.row(0) = e1;
  box.axes.row(1) = e3.cross(e1).normalized();
  box.axes.row(2) = e3;
  box.lo.setConstant(std::numeric_limits<double>::infinity());
  box.hi.setConstant(-std::numeric_limits<double>::infinity());
  for (const Eigen::Vector3d& p : points) {
    const Eigen::Vector3d y = box.axes * (p - ball.center);
    box.lo = box.lo.cwiseMin(y);
    box.hi = box.hi.cwiseMax(y);
  }
  // The net's rounding as the ball allows for it (256 ulps of the coordinates), and this computation's.
  const double scale = ball.center.cwiseAbs().maxCoeff() + ball.radius;
  const double widen = 256 * std::numeric_limits<double>::epsilon() * scale;
  box.lo.array() -= widen;
  box.hi.array() += widen;
  return box;
}

}  // namespace

double boxDistance(const PatchNode& n, const Eigen::Vector3d& q) {
  const Eigen::Vector3d r = q - n.ball.center;
  const Eigen::Vector3d y = n.box.axes * r;
  const Eigen::Vector3d outside = (n.box.lo - y).cwiseMax(y - n.box.hi).cwiseMax(0.0);
  // The frame is orthonormal to a few ulps and r and y are rounded: allow 1e-12 of |r| and ulps of q.
  const double slack = 1e-12 * r.norm() + 8 * std::numeric_limits<double>::epsilon() * q.cwiseAbs().maxCoeff();
  return std::max(0.0, outside.norm() - slack);
}

RationalBezierPatch restrict(const RationalBezierPatch& patch, int direction, double a, double b) {
  RationalBezierPatch out = patch;
  const int lines = direction == 0 ? patch.degreeV + 1 : patch.degreeU + 1;
  const int length = direction == 0 ? patch.degreeU + 1 : patch.degreeV + 1;
  std::vector<Eigen::Vector4d> line(static_cast<std::size_t>(length)), left, right, unused;
  for (int l = 0; l < lines; ++l) {
    for (int k = 0; k < length; ++k) line[static_cast<std::size_t>(k)] = direction == 0 ? patch.at(k, l) : patch.at(l, k);
    if (b < 1) {
      splitRow(line, b, left, unused);
      line = left;
    }
    if (a > 0) {
      splitRow(line, a / b, unused, right);
      line = right;
    }
    for (int k = 0; k < length; ++k) (direction == 0 ? out.at(k, l) : out.at(l, k)) = line[static_cast<std::size_t>(k)];
  }
  return out;
}

RationalBezierPatch subpatch(const RationalBezierPatch& patch, double s0, double s1, double t0, double t1) {
  RationalBezierPatch out = restrict(restrict(patch, 0, s0, s1), 1, t0, t1);
  const Eigen::Vector2d first = patch.surfaceParam(s0, t0), last = patch.surfaceParam(s1, t1);
  out.u0 = first.x();
  out.u1 = last.x();
  out.v0 = first.y();
  out.v1 = last.y();
  out.stretchU = pieceStretch(patch.stretchU, s0, s1);
  out.stretchV = pieceStretch(patch.stretchV, t0, t1);
  return out;
}

std::unique_ptr<PatchNode> makeNode(RationalBezierPatch net, int patch, int depth, double s0, double s1, double t0,
                                    double t1) {
  auto n = std::make_unique<PatchNode>();
  n->net = std::move(net);
  n->patch = patch;
  n->depth = depth;
  n->s0 = s0;
  n->s1 = s1;
  n->t0 = t0;
  n->t1 = t1;
  n->points.reserve(n->net.net.size());
  for (const Eigen::Vector4d& h : n->net.net) n->points.push_back(h.head<3>() / h[3]);
  n->ball = ballOfPoints(n->points);
  tangentCones(n->net, n->cu, n->cv);
  n->normal = crossCone(n->cu, n->cv);
  n->box = frameBoxOf(n->points, n->ball, n->cu, n->cv, n->normal);
  const int p = n->net.degreeU, q = n->net.degreeV;
  n->corners = {n->net.point(0, 0), n->net.point(p, 0), n->net.point(0, q), n->net.point(p, q)};
  return n;
}

}  // namespace unidist::nurbs
