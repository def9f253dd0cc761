// Parameter domains of a NURBS model's surfaces for the local Newton iterations: the domain box, and which
// directions are periodic (the surface meets itself across the seam: a revolved sphere or torus), so that a
// point moving across a seam continues on the other side instead of stopping at the domain's edge. Internal.
#pragma once

#include "unidist/nurbs.h"

#include <cmath>
#include <vector>

namespace unidist::tracking {

struct SurfaceParams {
  Eigen::Vector2d lo = Eigen::Vector2d::Zero(), hi = Eigen::Vector2d::Ones();
  bool periodic[2] = {false, false};

  double scale() const { return (hi - lo).cwiseAbs().maxCoeff(); }
  /// Within the domain (periodic directions always are), with a rounding slack.
  bool inside(const Eigen::Vector2d& x) const {
    for (int k = 0; k < 2; ++k) {
      const double slack = 1e-12 * (hi[k] - lo[k]);
      if (!periodic[k] && (x[k] < lo[k] - slack || x[k] > hi[k] + slack)) return false;
    }
    return true;
  }
  /// Periodic directions wrapped into [lo, hi), the others clamped.
  Eigen::Vector2d wrap(Eigen::Vector2d x) const {
    for (int k = 0; k < 2; ++k) {
      const double w = hi[k] - lo[k];
      if (periodic[k]) {
        x[k] = lo[k] + std::fmod(x[k] - lo[k], w);
        if (x[k] < lo[k]) x[k] += w;
      } else {
        x[k] = std::min(std::max(x[k], lo[k]), hi[k]);
      }
    }
    return x;
  }
};

class ModelParams {
 public:
  explicit ModelParams(const NurbsModel& m) {
    for (int k = 0; k < static_cast<int>(m.surfaces().size()); ++k) {
      const NurbsSurface& s = m.surfaces()[static_cast<std::size_t>(k)];
      SurfaceParams p;
      p.lo = {s.uMin(), s.vMin()};
      p.hi = {s.uMax(), s.vMax()};
      p.periodic[0] = m.periodic(k, 0);
      p.periodic[1] = m.periodic(k, 1);
      surfaces_.push_back(p);
    }
  }
  const SurfaceParams& of(int surface) const { return surfaces_[static_cast<std::size_t>(surface)]; }

 private:
  std::vector<SurfaceParams> surfaces_;
};

}  // namespace unidist::tracking
