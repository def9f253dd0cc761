// Builds library models from the oracle's shape descriptions, and the shapes used across pair tests.
#pragma once

#include "core/oracles.h"
#include "unidist/distance.h"
#include "unidist/primitives.h"

#include <gtest/gtest.h>

#include <memory>
#include <vector>

namespace fixtures {

inline std::unique_ptr<unidist::Model> makeModel(const oracle::Shape& s) {
  if (s.kind == "sphere") return std::make_unique<unidist::Sphere>(s.p0);
  if (s.kind == "box") return std::make_unique<unidist::Box>(Eigen::Vector3d(s.p0, s.p1, s.p2));
  if (s.kind == "capsule") return std::make_unique<unidist::Capsule>(s.p0, s.p1);
  if (s.kind == "cylinder") return std::make_unique<unidist::Cylinder>(s.p0, s.p1);
  if (s.kind == "cone") return std::make_unique<unidist::Cone>(s.p0, s.p1);
  if (s.kind == "torus") return std::make_unique<unidist::Torus>(s.p0, s.p1);
  return nullptr;
}

/// Sizes chosen unequal and not powers of two, so no symmetry hides an error.
inline std::vector<oracle::Shape> convexShapes(double scale = 1) {
  return {{"sphere", 0.6 * scale},
          {"box", 0.5 * scale, 0.35 * scale, 0.25 * scale},
          {"capsule", 0.2 * scale, 0.45 * scale},
          {"cylinder", 0.4 * scale, 0.3 * scale},
          {"cone", 0.45 * scale, 0.4 * scale}};
}

inline oracle::Shape torusShape(double scale = 1) { return {"torus", 0.8 * scale, 0.2 * scale}; }

/// Places B (rotation already in XB) so that its lowest point along n touches A's highest point along n
/// shifted by gap·n: the two support planes then separate them and the true distance is exactly gap.
inline void placeAtGap(const oracle::Shape& a, const oracle::Pose& XA, const oracle::Shape& b, oracle::Pose& XB,
                       const oracle::Vec& n, double gap) {
  XB.translation().setZero();
  const oracle::Vec top = oracle::worldSupport(a, XA, n);
  const oracle::Vec bottom = oracle::worldSupport(b, XB, -n);
  XB.translation() = top + gap * n - bottom;
}

/// Smooth pairs give the direction oracle a smooth function to minimise; polytope edges and cylinder rims
/// give it ridges where it can stall by ~1e-5 (it still bounds the depth from above).
inline bool smoothPair(const oracle::Shape& a, const oracle::Shape& b) {
  auto smooth = [](const oracle::Shape& s) { return s.kind == "sphere" || s.kind == "capsule"; };
  return smooth(a) && smooth(b);
}

/// Checks a penetration answer against the direction oracle:
///  * the depth is realised along the reported normal (an independent support evaluation);
///  * it is never worse than the best direction of the oracle's dense search (a global check);
///  * no direction near the reported normal does better (a local-optimality check at several radii, which
///    also holds where the oracle's own refinement stalls on the ridges of polytope edges and rims);
///  * where the oracle converges (smooth pairs) it matches it to `tolerance`.
inline void expectPenetrationMatchesOracle(const oracle::Shape& sa, const oracle::Pose& XA, const oracle::Shape& sb,
                                           const oracle::Pose& XB, const unidist::DistanceResult& r, double tolerance) {
  const double depth = oracle::convexPenetration(sa, XA, sb, XB);
  const double ours = -r.distance;
  // At a ridge (edge against rim) the overlap grows linearly with the normal's error, and EPA's normal is
  // only as good as its last polytope face: allow 1e-6 of the depth there.
  EXPECT_NEAR(oracle::overlapAlong(sa, XA, sb, XB, r.normal), ours, tolerance + (smoothPair(sa, sb) ? 0 : 1e-6 * depth));
  EXPECT_LE(ours, depth + tolerance);
  const oracle::Vec t1 = oracle::Vec::UnitX().cross(r.normal).norm() > 0.5 ? oracle::Vec(oracle::Vec::UnitX().cross(r.normal).normalized())
                                                                          : oracle::Vec(oracle::Vec::UnitY().cross(r.normal).normalized());
  const oracle::Vec t2 = r.normal.cross(t1);
  double bestNearby = 1e300;
  for (double radius : {1e-2, 1e-3, 1e-4, 1e-5, 1e-6})
    for (int k = 0; k < 64; ++k) {
      const double angle = 2 * M_PI * k / 64;
      const oracle::Vec u = (r.normal + radius * (std::cos(angle) * t1 + std::sin(angle) * t2)).normalized();
      bestNearby = std::min(bestNearby, oracle::overlapAlong(sa, XA, sb, XB, u));
    }
  EXPECT_GE(bestNearby, ours - tolerance);
  if (smoothPair(sa, sb)) {
    EXPECT_NEAR(ours, depth, tolerance);
  }
  EXPECT_GE(r.upperBound, -depth - tolerance);  // the upper bound may not claim less depth than realised
}

}  // namespace fixtures
