#include "generic/surface_search.h"

#include <algorithm>
#include <cmath>
#include <queue>

namespace unidist::detail {
namespace {

struct OpenCell {
  SurfaceCell cell;
  double lower;
  bool operator>(const OpenCell& o) const { return lower > o.lower; }
};

}  // namespace

double fieldValue(const PosedModel& field, const Eigen::Vector3d& p_W) {
  const double sd = field.closestWorld(p_W).signedDistance;
  return field.model.isSolid() ? sd : std::abs(sd);
}

SurfaceMinimum minimizeFieldOverSurface(const PosedModel& surface, const PosedModel& field, double upperHint,
                                        const Eigen::Vector3d& hintPoint, double tolerance, int budget,
                                        int budgetOnceNegative) {
  auto fieldAt = [&](const Eigen::Vector3d& p_W) { return fieldValue(field, p_W); };

  SurfaceMinimum best;
  best.value = upperHint;
  best.point = hintPoint;
  std::priority_queue<OpenCell, std::vector<OpenCell>, std::greater<OpenCell>> open;
  auto visit = [&](const SurfaceCell& cell) {
    const Eigen::Vector3d sample_W = surface.toWorld(cell.sample);
    const double atSample = fieldAt(sample_W);
    const double atCentre = cell.sample == cell.center ? atSample : fieldAt(surface.toWorld(cell.center));
    best.evaluations += cell.sample == cell.center ? 1 : 2;
    if (atSample < best.value) {
      best.value = atSample;
      best.point = sample_W;
    }
    open.push({cell, atCentre - cell.radius});
  };
  for (const SurfaceCell& c : surface.model.surfaceCells()) visit(c);

  std::vector<SurfaceCell> children;
  int firstNegative = -1;  // evaluations spent when a negative value was first found
  while (!open.empty()) {
    const OpenCell top = open.top();
    if (top.lower >= best.value - tolerance) break;  // all the rest are pruned
    if (best.evaluations >= budget) {
      best.exhausted = true;
      break;
    }
    if (best.value < 0 && firstNegative < 0) firstNegative = best.evaluations;
    if (firstNegative >= 0 && best.evaluations - firstNegative >= budgetOnceNegative) {
      best.exhausted = true;
      break;
    }
    open.pop();
    children.clear();
    surface.model.splitCell(top.cell, children);
    for (const SurfaceCell& c : children) visit(c);
  }
  best.lowerBound = open.empty() ? best.value : std::min(best.value, open.top().lower);
  return best;
}

}  // namespace unidist::detail
