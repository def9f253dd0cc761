// LDLᵀ with diagonal pivoting for the 4×4 systems of the pair Newton steps. Eigen's LDLT does the same through
// its dynamic-size block kernels: about ten times the instructions on a 4×4, and the polish solves one per step
// (7 % of a whole surface–surface query). Same conventions as Eigen's: the largest remaining diagonal entry is
// the next pivot; a zero pivot gives a zero component (the pseudo-inverse of D), so a Hessian singular along a
// circle of minima still gives the step across it. Internal.
#pragma once

#include <Eigen/Core>

#include <cmath>
#include <limits>
#include <utility>

namespace unidist::nurbs {

template <int N>
class SmallLdlt {
 public:
  using Matrix = Eigen::Matrix<double, N, N>;
  using Vector = Eigen::Matrix<double, N, 1>;

  explicit SmallLdlt(const Matrix& m) : a_(m) {
    for (int k = 0; k < N; ++k) {
      int pivot = k;
      for (int i = k + 1; i < N; ++i)
        if (std::abs(a_(i, i)) > std::abs(a_(pivot, pivot))) pivot = i;
      order_[k] = pivot;
      if (pivot != k) {
        a_.row(k).swap(a_.row(pivot));
        a_.col(k).swap(a_.col(pivot));
      }
      for (int j = 0; j < k; ++j) a_(k, k) -= a_(k, j) * a_(k, j) * a_(j, j);
      for (int i = k + 1; i < N; ++i)
        for (int j = 0; j < k; ++j) a_(i, k) -= a_(i, j) * a_(k, j) * a_(j, j);
      const double d = a_(k, k);
      if (!std::isfinite(d)) valid_ = false;
      if (d < 0) positive_ = false;
      if (d != 0) {
        if (zeroSeen_) valid_ = false;  // a pivot after a zero one: not semidefinite (Eigen's NumericalIssue)
        for (int i = k + 1; i < N; ++i) a_(i, k) /= d;
      } else {
        zeroSeen_ = true;
        for (int i = k + 1; i < N; ++i)
          if (a_(i, k) != 0) valid_ = false;
      }
    }
  }

  /// Factored without a non-finite or misplaced zero pivot, and no negative one: the matrix is positive
  /// semidefinite to rounding.
  bool positiveSemidefinite() const { return valid_ && positive_; }

  Vector solve(const Vector& b) const {
    Vector x = b;
    for (int k = 0; k < N; ++k) std::swap(x[k], x[order_[k]]);
    for (int i = 0; i < N; ++i)
      for (int j = 0; j < i; ++j) x[i] -= a_(i, j) * x[j];
    for (int i = 0; i < N; ++i) x[i] = std::abs(a_(i, i)) > std::numeric_limits<double>::min() ? x[i] / a_(i, i) : 0.0;
    for (int i = N - 1; i >= 0; --i)
      for (int j = i + 1; j < N; ++j) x[i] -= a_(j, i) * x[j];
    for (int k = N - 1; k >= 0; --k) std::swap(x[k], x[order_[k]]);
    return x;
  }

 private:
  Matrix a_;  // L strictly below the diagonal, D on it, after the pivots' swaps
  int order_[N] = {};
  bool valid_ = true, positive_ = true, zeroSeen_ = false;
};

}  // namespace unidist::nurbs
