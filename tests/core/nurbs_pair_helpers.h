// Helpers shared by the NURBS pair tests: a solid of one surface, random poses, the check of an answer's value
// and proved bounds against a truth, and the closest pair's patches and parameters (to fit a separator to).
#pragma once

#include "unidist/distance.h"
#include "unidist/nurbs.h"

#include <gtest/gtest.h>

#include <limits>
#include <memory>
#include <random>
#include <vector>

namespace nurbs_pair_helpers {

inline std::shared_ptr<unidist::NurbsModel> solid(unidist::NurbsSurface s) {
  std::vector<unidist::NurbsSurface> v;
  v.push_back(std::move(s));
  return std::make_shared<unidist::NurbsModel>(std::move(v), true);
}

/// A uniformly random rotation and a translation in the cube [−spread, spread]³.
inline Eigen::Isometry3d randomPose(std::mt19937& rng, double spread) {
  std::uniform_real_distribution<double> u(-1, 1);
  Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
  X.linear() = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized().toRotationMatrix();
  X.translation() = spread * Eigen::Vector3d(u(rng), u(rng), u(rng));
  return X;
}

/// The proved bounds hold the truth (to slack) and the value is within the bounds' width of it.
inline void expectBracket(const unidist::DistanceResult& r, double truth, double slack) {
  EXPECT_LE(r.lowerBound, truth + slack);
  EXPECT_GE(r.upperBound, truth - slack);
  EXPECT_NEAR(r.distance, truth, slack + (r.upperBound - r.lowerBound));
}

/// The closest pair of two NURBS models, B at X_AB in A's frame, from the distance query itself: the points (both
/// in A's frame) and the patch and parameters of each (the patch whose Gauss–Newton projection lands on it).
struct ClosestPair {
  int patchA = -1, patchB = -1;
  Eigen::Vector2d xA, xB;
  Eigen::Vector3d pA, pB;
};
inline ClosestPair closestPair(const unidist::NurbsModel& a, const unidist::NurbsModel& b,
                               const Eigen::Isometry3d& X_AB) {
  const unidist::DistanceResult r =
      unidist::distance(a, Eigen::Isometry3d::Identity(), b, X_AB, unidist::DistanceOptions{});
  ClosestPair c;
  c.pA = r.pointA;
  c.pB = r.pointB;
  const auto locate = [](const unidist::NurbsModel& m, const Eigen::Vector3d& p, int& patch, Eigen::Vector2d& x) {
    double best = std::numeric_limits<double>::infinity();
    for (std::size_t k = 0; k < m.patches().size(); ++k)
      for (int i = 0; i <= 64; ++i)
        for (int j = 0; j <= 64; ++j) {
          const Eigen::Vector2d y(i / 64.0, j / 64.0);
          const double d = (m.patches()[k].derivatives(y[0], y[1]).point - p).norm();
          if (d < best) best = d, patch = static_cast<int>(k), x = y;
        }
    for (int step = 0; step < 30; ++step) {  // Gauss-Newton onto the point
      const unidist::SurfaceDerivatives d = m.patches()[static_cast<std::size_t>(patch)].derivatives(x[0], x[1]);
      Eigen::Matrix<double, 3, 2> J;
      J << d.du, d.dv;
      x = (x - (J.transpose() * J).ldlt().solve(J.transpose() * (d.point - p))).cwiseMax(0.0).cwiseMin(1.0);
    }
  };
  locate(a, c.pA, c.patchA, c.xA);
  locate(b, X_AB.inverse() * c.pB, c.patchB, c.xB);
  return c;
}

}  // namespace nurbs_pair_helpers
