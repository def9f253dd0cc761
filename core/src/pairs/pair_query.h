// What every pair routine receives: two posed models and the query's settings. Internal.
#pragma once

#include "unidist/distance.h"

#include <algorithm>
#include <vector>

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

/// Both models' axes in the world, each both ways (12 directions): the ways a solid resting on or stacked with
/// another most often leaves it (a ring lifted along its axis), tried by the escape and touching searches.
inline std::vector<Eigen::Vector3d> axesOfBoth(const PosedModel& a, const PosedModel& b) {
  std::vector<Eigen::Vector3d> axes;
  axes.reserve(12);
  for (int k = 0; k < 3; ++k)
    for (double sign : {1.0, -1.0}) {
      axes.emplace_back(sign * a.X_WM.linear().col(k));
      axes.emplace_back(sign * b.X_WM.linear().col(k));
    }
  return axes;
}

struct QueryContext {
  double tolerance;   ///< absolute, > 0 after defaulting (0 from the user becomes a rounding-level value)
  int maxIterations;
  /// Set by searches that only need to know whether the solids' interiors are disjoint (the penetration
  /// search tests translated copies): a routine may then stop as soon as it has proved an overlap, returning
  /// upperBound <= 0 and an unknown (-inf) lowerBound, instead of measuring the penetration.
  bool overlapVerdictOnly = false;
  /// With overlapVerdictOnly, set by the penetration search's separation tests: only a proof that the interiors
  /// are disjoint is of use, so a routine answers notProvedApart instead of spending more to prove an overlap.
  bool apartProofOnly = false;
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

/// What a routine returns under overlapVerdictOnly when surfaces within a fraction of the tolerance cannot be
/// proved apart: no verdict either way, and the realised gap `gap` (>= 0) as the upper bound (crossing surfaces
/// only lower the signed distance).
inline DistanceResult notProvedApart(double gap) {
  DistanceResult r = overlapVerdict();
  r.distance = r.upperBound = gap;
  return r;
}

using PairFn = DistanceResult (*)(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

/// Whether p (model frame) lies inside the solid m; a point outside its bounding box needs no point query. The
/// NURBS pair searches test containment first with it: a contained model proves the overlap, and their surface
/// searches would only spend their budgets (on concentric models every subpatch stays a candidate).
inline bool insideSolid(const Model& m, const Eigen::Vector3d& p_M) {
  return m.isSolid() && m.localBounds().distanceTo(p_M) == 0 && m.inside(p_M);
}

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

/// A separation answer from the closest points pA_M, pB_M found in a's frame, with a proved lower bound;
/// `touchNormal_M` (a's frame) is the normal used if the points coincide.
inline DistanceResult separationFromPoints(const PosedModel& a, const Eigen::Vector3d& pA_M, const Eigen::Vector3d& pB_M,
                                           const Eigen::Vector3d& touchNormal_M, double lowerBound, int iterations,
                                           const char* method, double tolerance) {
  DistanceResult r;
  r.method = method;
  r.iterations = iterations;
  r.pointA = a.toWorld(pA_M);
  r.pointB = a.toWorld(pB_M);
  const Eigen::Vector3d gap = r.pointB - r.pointA;
  r.distance = gap.norm();
  r.normal = r.distance > 0 ? Eigen::Vector3d(gap / r.distance) : a.dirToWorld(touchNormal_M);
  r.upperBound = r.distance;
  r.lowerBound = std::min(lowerBound, r.distance);
  settleStatus(r, tolerance);
  return r;
}

/// A depth answer for solids whose surfaces are proved to meet: distance <= 0 holds, whatever the search said.
inline void capAtContact(DistanceResult& r, double tolerance) {
  r.upperBound = std::min(r.upperBound, 0.0);
  r.lowerBound = std::min(r.lowerBound, r.upperBound);
  r.distance = std::clamp(r.distance, r.lowerBound, r.upperBound);
  settleStatus(r, tolerance);
}

/// A unit vector orthogonal to v (any; deterministic).
Eigen::Vector3d anyOrthogonal(const Eigen::Vector3d& v);

}  // namespace unidist::detail
