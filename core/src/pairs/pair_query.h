// What every pair routine receives: two posed models and the query's settings. Internal.
#pragma once

#include "unidist/distance.h"

namespace unidist::detail {

/// A model placed in the world; converts points and directions between the world W and the model frame M.
struct PosedModel {
  const Model& model;
  Eigen::Isometry3d X_WM;

  Eigen::Vector3d toLocal(const Eigen::Vector3d& p_W) const { return X_WM.inverse(Eigen::Isometry) * p_W; }
  Eigen::Vector3d toWorld(const Eigen::Vector3d& p_M) const { return X_WM * p_M; }
  Eigen::Vector3d dirToLocal(const Eigen::Vector3d& v_W) const { return X_WM.linear().transpose() * v_W; }
  Eigen::Vector3d dirToWorld(const Eigen::Vector3d& v_M) const { return X_WM.linear() * v_M; }

  /// Closest surface point to a world point, answered in world coordinates.
  SurfacePoint closestWorld(const Eigen::Vector3d& q_W) const {
    SurfacePoint s = model.closestPoint(toLocal(q_W));
    s.point = toWorld(s.point);
    s.normal = dirToWorld(s.normal);
    return s;
  }
  Eigen::Vector3d supportWorld(const Eigen::Vector3d& d_W) const { return toWorld(model.support(dirToLocal(d_W))); }
};

struct QueryContext {
  double tolerance;   ///< absolute, > 0 after defaulting (0 from the user becomes a rounding-level value)
  int maxIterations;
  /// Set by searches that only need to know whether the solids' interiors are disjoint (the penetration
  /// search tests translated copies): a routine may then stop as soon as it has proved an overlap, returning
  /// upperBound <= 0 and an unknown (-inf) lowerBound, instead of measuring the penetration.
  bool overlapVerdictOnly = false;
};

/// What a routine returns under overlapVerdictOnly once it has proved the interiors meet.
inline DistanceResult overlapVerdict() {
  DistanceResult r;
  r.distance = 0;
  r.upperBound = 0;
  r.lowerBound = -std::numeric_limits<double>::infinity();
  r.status = Status::Bounded;
  r.method = "overlap-verdict";
  return r;
}

using PairFn = DistanceResult (*)(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

/// The same answer seen with A and B exchanged: points swap, the normal flips, the distance is symmetric.
inline DistanceResult swapped(DistanceResult r) {
  std::swap(r.pointA, r.pointB);
  r.normal = -r.normal;
  return r;
}

/// Fills status from the bounds and the tolerance.
inline void settleStatus(DistanceResult& r, double tolerance) {
  r.status = (r.upperBound - r.lowerBound <= tolerance) ? Status::Certified : Status::Bounded;
}

/// A unit vector orthogonal to v (any; deterministic).
Eigen::Vector3d anyOrthogonal(const Eigen::Vector3d& v);

}  // namespace unidist::detail
