#include "nurbs/pair_newton.h"

#include <Eigen/Cholesky>

#include <algorithm>
#include <cmath>

namespace unidist::nurbs {
namespace {

constexpr int kSteps = 40;
constexpr int kDampings = 12;

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

}  // namespace

PairHit polishPair(const RationalBezierPatch& a, const RationalBezierPatch& b, const Eigen::Isometry3d& X_AB,
                   const Eigen::Vector4d& x0) {
  Eigen::Vector4d x = x0.cwiseMax(0.0).cwiseMin(1.0);
  Eval e = evaluate(a, b, X_AB, x);
  int evaluations = 1;
  for (int step = 0; step < kSteps; ++step) {
    Eigen::Vector4d g;
    Eigen::Matrix4d H;
    derivatives(e, g, H);
    // Active set: a variable at a bound whose descent leaves the box stays there.
    Eigen::Vector4d free = Eigen::Vector4d::Ones();
    for (int k = 0; k < 4; ++k)
      if ((x[k] <= 0 && g[k] > 0) || (x[k] >= 1 && g[k] < 0)) free[k] = 0;
    if (free.sum() == 0) break;
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
      const Eigen::LDLT<Eigen::Matrix4d> ldlt(Md);
      if (ldlt.info() != Eigen::Success || !ldlt.isPositive()) continue;
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
        if (moved < 1e-14) step = kSteps;  // converged to rounding level
      }
    }
    if (!accepted) break;
  }
  PairHit hit;
  hit.x = x;
  hit.pA = e.a.point;
  hit.pB = e.b.point;
  hit.value = (hit.pB - hit.pA).norm();
  hit.evaluations = evaluations;
  return hit;
}

}  // namespace unidist::nurbs
