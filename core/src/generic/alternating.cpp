#include "generic/surface_search.h"

#include <cmath>

namespace unidist::detail {

PointPair alternate(const PosedModel& a, const PosedModel& b, const Eigen::Vector3d& start_W, double tolerance,
                    int maxSteps) {
  PointPair best;
  best.onA = a.closestWorld(start_W).point;
  best.onB = b.closestWorld(best.onA).point;
  best.gap = (best.onB - best.onA).norm();
  Eigen::Vector3d previousA = best.onA;
  for (int step = 1; step <= maxSteps; ++step) {
    const Eigen::Vector3d qA = a.closestWorld(best.onB).point;
    const Eigen::Vector3d qB = b.closestWorld(qA).point;
    const double gap = (qB - qA).norm();
    best.iterations = step;
    // A point query that is only local can break monotonicity: keep the better pair and stop.
    if (!(gap < best.gap)) break;
    const bool settled = best.gap - gap <= tolerance;
    const bool cycling = (qA - previousA).norm() <= tolerance;
    previousA = best.onA;
    best.onA = qA;
    best.onB = qB;
    best.gap = gap;
    if (settled || cycling) break;
  }
  return best;
}

std::vector<Eigen::Vector3d> alternationStarts(const PosedModel& a, const PosedModel& b) {
  std::vector<Eigen::Vector3d> starts;
  const Aabb boxA = a.model.localBounds().transformed(a.X_WM);
  const Aabb boxB = b.model.localBounds().transformed(b.X_WM);
  if (boxA.bounded() && boxB.bounded()) {
    // Per axis: the middle of the overlap of the two intervals, or the facing ends when they are apart.
    Eigen::Vector3d onA, onB;
    for (int i = 0; i < 3; ++i) {
      const double lo = std::max(boxA.min[i], boxB.min[i]), hi = std::min(boxA.max[i], boxB.max[i]);
      if (lo <= hi) {
        onA[i] = onB[i] = 0.5 * (lo + hi);
      } else if (boxA.max[i] < boxB.min[i]) {
        onA[i] = boxA.max[i];
        onB[i] = boxB.min[i];
      } else {
        onA[i] = boxA.min[i];
        onB[i] = boxB.max[i];
      }
    }
    starts.push_back(onB);
    starts.push_back(onA);
  }
  starts.push_back(a.toWorld(a.model.localBoundingSphere().center));
  starts.push_back(b.toWorld(b.model.localBoundingSphere().center));
  for (const SurfaceCell& c : a.model.surfaceCells()) starts.push_back(a.toWorld(c.sample));
  for (const SurfaceCell& c : b.model.surfaceCells()) starts.push_back(b.toWorld(c.sample));
  return starts;
}

}  // namespace unidist::detail
