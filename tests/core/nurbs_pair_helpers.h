// Helpers shared by the NURBS pair tests: a solid of one surface, random poses, and the check of an answer's
// value and proved bounds against a truth.
#pragma once

#include "unidist/distance.h"
#include "unidist/nurbs.h"

#include <gtest/gtest.h>

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

}  // namespace nurbs_pair_helpers
