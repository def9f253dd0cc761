#include "nurbs/pair_newton.h"

#include "nurbs/small_ldlt.h"

#include <Eigen/LU>

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist::nurbs {
namespace {

constexpr int kSteps = 40;
constexpr int kDampings = 12;
constexpr int kCollinearSteps = 20;
constexpr int kCollinearHalvings = 6;
constexpr double kCollinearAngle = 1e-8;  // a collinear-Newton end is taken only where its pair is this collinear

struct Eval {
  SurfaceDerivatives a, b;  // b already in A's frame
  double value = 0;         // ½|r|², r = a − b
};

Eval evaluate(const RationalBezierPatch& pa, const RationalBezierPatch& pb, const Eigen::Isometry3d& X_AB,
              const Eigen::Vector4d& x) {
  Eval e;
  e.a = pa.derivatives(x[0], x[1]);
  SurfaceDerivatives b = pb.derivatives(x[2], x[3]);
  const Eigen::Matrix3d R = X_AB.linear();
  b.point = X_AB * b.point;
  for (Eigen::Vector3d* v : {&b.du, &b.dv, &b.duu, &b.duv, &b.dvv}) *v = R * *v;
  e.b = b;
  e.value = 0.5 * (e.a.point - e.b.point).squaredNorm();
  return e;
}

/// The residual's Jacobian in (s, t, u, v).
Eigen::Matrix<double, 3, 4> jacobian(const Eval& e) {
  Eigen::Matrix<double, 3, 4> J;
  J << e.a.du, e.a.dv, -e.b.du, -e.b.dv;
  return J;
}

/// Gradient of ½|S_A − S_B|² in (s, t, u, v).
Eigen::Vector4d gradient(const Eval& e) { return jacobian(e).transpose() * (e.a.point - e.b.point); }

/// Gradient and Hessian of ½|S_A − S_B|² in (s, t, u, v).
void derivatives(const Eval& e, Eigen::Vector4d& g, Eigen::Matrix4d& H) {
  const Eigen::Vector3d r = e.a.point - e.b.point;
  const Eigen::Matrix<double, 3, 4> J = jacobian(e);
  g = J.transpose() * r;
  H = J.transpose() * J;
  H(0, 0) += r.dot(e.a.duu);
  H(0, 1) += r.dot(e.a.duv);
  H(1, 0) += r.dot(e.a.duv);
  H(1, 1) += r.dot(e.a.dvv);
  H(2, 2) -= r.dot(e.b.duu);
  H(2, 3) -= r.dot(e.b.duv);
  H(3, 2) -= r.dot(e.b.duv);
  H(3, 3) -= r.dot(e.b.dvv);
}

/// Thomas et al.'s extremal-distance conditions written to stay regular as the distance goes to 0: the segment
/// orthogonal to A's tangents, B's tangents orthogonal to A's normal N = S_s × S_t. (The gradient of ½|S_A − S_B|²
/// vanishes with the distance: its Hessian's curvature part shrinks with it, and near contact Newton on it crawls.)
/// Returns F; J receives its Jacobian in (s, t, u, v).
Eigen::Vector4d collinearEquations(const Eval& e, Eigen::Matrix4d& J) {
  const SurfaceDerivatives& a = e.a;
  const SurfaceDerivatives& b = e.b;
  const Eigen::Vector3d d = b.point - a.point;
  const Eigen::Vector3d N = a.du.cross(a.dv);
  const Eigen::Vector3d Ns = a.duu.cross(a.dv) + a.du.cross(a.duv), Nt = a.duv.cross(a.dv) + a.du.cross(a.dvv);
  J << -a.du.dot(a.du) + d.dot(a.duu), -a.dv.dot(a.du) + d.dot(a.duv), b.du.dot(a.du), b.dv.dot(a.du),
      -a.du.dot(a.dv) + d.dot(a.duv), -a.dv.dot(a.dv) + d.dot(a.dvv), b.du.dot(a.dv), b.dv.dot(a.dv),
      Ns.dot(b.du), Nt.dot(b.du), N.dot(b.duu), N.dot(b.duv),
      Ns.dot(b.dv), Nt.dot(b.dv), N.dot(b.duv), N.dot(b.dvv);
  return {d.dot(a.du), d.dot(a.dv), N.dot(b.du), N.dot(b.dv)};
}

/// Whether e's pair is collinear to within `angle` (radians): the normals parallel and the segment along them.
bool collinear(const Eval& e, double angle) {
  const Eigen::Vector3d nA = e.a.du.cross(e.a.dv), nB = e.b.du.cross(e.b.dv);
  if (!(nA.norm() > 0) || !(nB.norm() > 0)) return false;
  const Eigen::Vector3d uA = nA.normalized(), d = e.b.point - e.a.point;
  if (!(uA.cross(nB.normalized()).norm() <= angle)) return false;
  // The segment's sideways part, to within the points' rounding (at a gap of 1e-9 its direction is only good to
  // ~1e-7).
  const double rounding = 1024 * std::numeric_limits<double>::epsilon() * (e.a.point.norm() + e.b.point.norm());
  return uA.cross(d).norm() <= angle * d.norm() + rounding;
}

/// Newton on collinearEquations from e (in place), each step kept only where it lowers the distance (halved
/// otherwise): the end of a descent that ran out of steps next to a contact. Taken only where it ends inside the
/// patches on a collinear pair, nearer than the descent's end; otherwise x and e are left as they were (where the
/// equations are degenerate, a ball under a ring's parabolic line, its steps wander along the contact, and an end
/// that is neither the descent's nor a solution misleads the search's certificates).
void collinearPolish(const RationalBezierPatch& pa, const RationalBezierPatch& pb, const Eigen::Isometry3d& X_AB,
                     Eigen::Vector4d& x, Eval& e, int& evaluations) {
  Eigen::Vector4d y = x;
  Eval ey = e;
  for (int step = 0; step < kCollinearSteps; ++step) {
    Eigen::Matrix4d J;
    const Eigen::Vector4d F = collinearEquations(ey, J);
    const Eigen::FullPivLU<Eigen::Matrix4d> lu(J);
    if (!lu.isInvertible()) break;
    Eigen::Vector4d delta = -lu.solve(F);
    if (!delta.allFinite()) break;
    bool accepted = false, converged = false;
    for (int halving = 0; halving < kCollinearHalvings && !accepted; ++halving, delta *= 0.5) {
      const Eigen::Vector4d trial = y + delta;
      if (!((trial.array() > 0).all() && (trial.array() < 1).all())) continue;  // inside the patches only
      const Eval et = evaluate(pa, pb, X_AB, trial);
      ++evaluations;
      if (et.value < ey.value) {
        accepted = true;
        converged = (trial - y).cwiseAbs().maxCoeff() < 1e-14;
        y = trial;
        ey = et;
      }
    }
    if (!accepted || converged) break;
  }
  if (ey.value < e.value && collinear(ey, kCollinearAngle)) {
    x = y;
    e = ey;
  }
}

}  // namespace

PairHit polishPair(const RationalBezierPatch& a, const RationalBezierPatch& b, const Eigen::Isometry3d& X_AB,
                   const Eigen::Vector4d& x0) {
  Eigen::Vector4d x = x0.cwiseMax(0.0).cwiseMin(1.0);
  Eval e = evaluate(a, b, X_AB, x);
  int evaluations = 1;
  bool ranOut = true;  // whether the descent used every step without settling
  for (int step = 0; step < kSteps; ++step) {
    Eigen::Vector4d g;
    Eigen::Matrix4d H;
    derivatives(e, g, H);
    // Active set: a variable at a bound whose descent leaves the box stays there.
    Eigen::Vector4d free = Eigen::Vector4d::Ones();
    for (int k = 0; k < 4; ++k)
      if ((x[k] <= 0 && g[k] > 0) || (x[k] >= 1 && g[k] < 0)) free[k] = 0;
    if (free.sum() == 0) {
      ranOut = false;
      break;
    }
    Eigen::Matrix4d M = H;
    for (int k = 0; k < 4; ++k)
      if (free[k] == 0) {
        M.row(k).setZero();
        M.col(k).setZero();
        M(k, k) = 1;
        g[k] = 0;
      }
    // Levenberg: add μ·diag until the step decreases the distance (μ = 0 first: plain Newton).
    const double scale = std::max(M.diagonal().cwiseAbs().maxCoeff(), 1e-300);
    bool accepted = false;
    double mu = 0;
    for (int k = 0; k < kDampings && !accepted; ++k, mu = (mu == 0 ? 1e-6 * scale : 10 * mu)) {
      Eigen::Matrix4d Md = M;
      Md.diagonal().array() += mu;
      const SmallLdlt<4> ldlt(Md);
      if (!ldlt.positiveSemidefinite()) continue;
      Eigen::Vector4d delta = -ldlt.solve(g);
      delta = delta.cwiseProduct(free);
      if (!delta.allFinite()) continue;
      const Eigen::Vector4d trial = (x + delta).cwiseMax(0.0).cwiseMin(1.0);
      if (trial == x) break;
      const Eval et = evaluate(a, b, X_AB, trial);
      ++evaluations;
      // Near the end the distance is flat to rounding while the gradient, which the convexity certificate
      // starts from, still shrinks: a short plain Newton step is judged by the gradient, and one that does not
      // shrink it ends the run (damping it would only spend evaluations on rounding noise).
      bool better = et.value < e.value;
      if (mu == 0 && !better && (trial - x).cwiseAbs().maxCoeff() < 1e-7) {
        if (!(gradient(et).cwiseProduct(free).norm() < g.norm())) break;
        better = true;
      }
      if (better) {
        accepted = true;
        const double moved = (trial - x).cwiseAbs().maxCoeff();
        x = trial;
        e = et;
        if (moved < 1e-14) {  // converged to rounding level
          step = kSteps;
          ranOut = false;
        }
      }
    }
    if (!accepted) {
      ranOut = false;
      break;
    }
  }
  if (ranOut) collinearPolish(a, b, X_AB, x, e, evaluations);
  PairHit hit;
  hit.x = x;
  hit.pA = e.a.point;
  hit.pB = e.b.point;
  hit.value = (hit.pB - hit.pA).norm();
  hit.evaluations = evaluations;
  return hit;
}

}  // namespace unidist::nurbs
