// The warm start's point projections (unidist/contact_manifold.h): the tracker's local projection
// (tracking::LocalSurface: a point Newton on the NURBS surface from the cached feature and (u, v), the exact
// search where Newton cannot answer) for each NURBS model of a pair; every other model answers its exact
// closest point, which is already cheap (closed forms, hierarchies). Owned by one ContactCache: not shared
// between threads. Internal.
#pragma once

#include "tracking/local_surface.h"

#include <memory>

namespace unidist::contact {

class WarmProjections {
 public:
  WarmProjections(const Model& a, const Model& b);
  /// Whether it was made for these two models (a cache may be handed another pair's models: start again).
  bool serves(const Model& a, const Model& b) const { return &a == a_ && &b == b_; }
  /// m's surface point nearest q_M (m's frame) near the hint (feature, param); updates the counters.
  SurfacePoint project(const Model& m, const Eigen::Vector3d& q_M, int feature, const Eigen::Vector2d& param);
  const tracking::Work& work() const { return work_; }

 private:
  const Model* a_;
  const Model* b_;
  std::unique_ptr<tracking::LocalSurface> la_, lb_;  // NURBS models only
  tracking::Work work_;
};

/// The projection the manifold uses: the warm start's when there is one, the model's exact query otherwise.
inline SurfacePoint projectOnto(WarmProjections* local, const Model& m, const Eigen::Vector3d& q_M, int feature,
                                const Eigen::Vector2d& param) {
  return local ? local->project(m, q_M, feature, param) : m.closestPoint(q_M);
}

}  // namespace unidist::contact
