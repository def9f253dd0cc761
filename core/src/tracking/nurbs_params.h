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
    const double size = m.localBounds().diagonal();
    for (const NurbsSurface& s : m.surfaces()) {
      SurfaceParams p;
      p.lo = {s.uMin(), s.vMin()};
      p.hi = {s.uMax(), s.vMax()};
      // Periodic when the two opposite domain edges coincide pointwise (sampled; 1e-9 × size, the solid-closure
      // tolerance of nurbs.h).
      constexpr int kSamples = 9;
      for (int k = 0; k < 2; ++k) {
        bool same = true;
        for (int i = 0; i <= kSamples && same; ++i) {
          const double t = p.lo[1 - k] + (p.hi[1 - k] - p.lo[1 - k]) * i / kSamples;
          const Eigen::Vector3d a = k == 0 ? s.evaluate(p.lo[0], t) : s.evaluate(t, p.lo[1]);
          const Eigen::Vector3d b = k == 0 ? s.evaluate(p.hi[0], t) : s.evaluate(t, p.hi[1]);
          same = (a - b).norm() <= 1e-9 * size;
        }
        // An edge collapsed to a point (a pole) also "coincides": require the edge to have length.
        const Eigen::Vector3d e0 = k == 0 ? s.evaluate(p.lo[0], p.lo[1]) : s.evaluate(p.lo[0], p.lo[1]);
        const Eigen::Vector3d e1 = k == 0 ? s.evaluate(p.lo[0], 0.5 * (p.lo[1] + p.hi[1]))
                                          : s.evaluate(0.5 * (p.lo[0] + p.hi[0]), p.lo[1]);
        p.periodic[k] = same && (e0 - e1).norm() > 1e-9 * size;
      }
      surfaces_.push_back(p);
    }
  }
  const SurfaceParams& of(int surface) const { return surfaces_[static_cast<std::size_t>(surface)]; }

 private:
  std::vector<SurfaceParams> surfaces_;
};

}  // namespace unidist::tracking
