// The 4×4 LDLᵀ of the pair Newton steps (core/src/nurbs/small_ldlt.h) against Eigen's LDLT: the same verdicts
// (positive semidefinite or not) and the same solutions, including the pseudo-inverse a zero pivot gives.
#include "nurbs/small_ldlt.h"

#include <Eigen/Cholesky>
#include <gtest/gtest.h>

#include <random>

namespace unidist::nurbs {
namespace {

using Matrix4 = Eigen::Matrix4d;
using Vector4 = Eigen::Vector4d;

void expectLikeEigen(const Matrix4& m, const Vector4& b) {
  const Eigen::LDLT<Matrix4> eigen(m);
  const SmallLdlt<4> ours(m);
  const bool eigenPositive = eigen.info() == Eigen::Success && eigen.isPositive();
  ASSERT_EQ(ours.positiveSemidefinite(), eigenPositive) << m;
  if (!eigenPositive) return;
  const Vector4 expected = eigen.solve(b), got = ours.solve(b);
  EXPECT_LE((got - expected).norm(), 1e-9 * (1 + expected.norm())) << m << "\nb = " << b.transpose();
}

TEST(SmallLdlt, SolvesPositiveDefiniteSystems) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 500; ++trial) {
    Matrix4 a;
    for (int i = 0; i < 16; ++i) a(i) = u(rng);
    const Matrix4 spd = a * a.transpose() + 1e-3 * Matrix4::Identity();
    const Vector4 b = Vector4::NullaryExpr([&] { return u(rng); });
    expectLikeEigen(spd, b);
    EXPECT_LE((spd * SmallLdlt<4>(spd).solve(b) - b).norm(), 1e-8 * b.norm());
  }
}

TEST(SmallLdlt, RejectsIndefiniteMatricesAsEigenDoes) {
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> u(-1, 1);
  int rejected = 0;
  for (int trial = 0; trial < 500; ++trial) {
    Matrix4 a;
    for (int i = 0; i < 16; ++i) a(i) = u(rng);
    const Matrix4 symmetric = a + a.transpose();
    expectLikeEigen(symmetric, Vector4::Ones());
    rejected += SmallLdlt<4>(symmetric).positiveSemidefinite() ? 0 : 1;
  }
  EXPECT_GT(rejected, 400);  // random symmetric matrices are nearly all indefinite
}

// A Hessian singular along one direction (a circle of minima): the zero pivot's component is dropped, the step
// is the least-squares one across the valley.
TEST(SmallLdlt, SingularDirectionGivesThePseudoInverseStep) {
  Matrix4 m = Matrix4::Zero();
  m.diagonal() << 4, 0, 2, 1;
  const Vector4 b(1, 3, 1, 1);
  expectLikeEigen(m, b);
  const Vector4 x = SmallLdlt<4>(m).solve(b);
  EXPECT_DOUBLE_EQ(x[1], 0);
  EXPECT_DOUBLE_EQ(x[0], 0.25);
  // Rank 2, rotated: a singular matrix that is not diagonal.
  Eigen::Matrix<double, 4, 2> basis;
  basis << 1, 0, 1, 1, 0, 1, 0, 0;
  expectLikeEigen(basis * basis.transpose(), basis * Eigen::Vector2d(0.3, -0.7));
}

TEST(SmallLdlt, NonFiniteInputIsNotPositive) {
  Matrix4 m = Matrix4::Identity();
  m(2, 2) = std::numeric_limits<double>::quiet_NaN();
  EXPECT_FALSE(SmallLdlt<4>(m).positiveSemidefinite());
  m(2, 2) = std::numeric_limits<double>::infinity();
  EXPECT_FALSE(SmallLdlt<4>(m).positiveSemidefinite());
}

}  // namespace
}  // namespace unidist::nurbs
