// Independent point-to-surface oracle for NURBS surfaces without a closed form, shared by the tests and the
// benchmarks: a dense parameter grid, then projected Newton on the B-spline surface itself (a different path
// from the model's: no Bézier patches, no tree).
#pragma once

#include "unidist/nurbs.h"

#include <algorithm>
#include <cmath>
#include <vector>

namespace nurbs_fixtures {

struct GridOracle {
  const unidist::NurbsSurface& s;
  std::vector<Eigen::Vector3d> points;
  std::vector<Eigen::Vector2d> params;
  static constexpr int kN = 300;
  explicit GridOracle(const unidist::NurbsSurface& surface) : s(surface) {
    for (int i = 0; i <= kN; ++i)
      for (int j = 0; j <= kN; ++j) {
        const double u = s.uMin() + (s.uMax() - s.uMin()) * i / kN, v = s.vMin() + (s.vMax() - s.vMin()) * j / kN;
        points.push_back(s.evaluate(u, v));
        params.emplace_back(u, v);
      }
  }
  double distance(const Eigen::Vector3d& q) const {
    std::size_t best = 0;
    for (std::size_t k = 1; k < points.size(); ++k)
      if ((points[k] - q).squaredNorm() < (points[best] - q).squaredNorm()) best = k;
    Eigen::Vector2d x = params[best];
    double value = (points[best] - q).norm();
    for (int it = 0; it < 100; ++it) {
      const unidist::SurfaceDerivatives d = s.derivatives(x[0], x[1]);
      const Eigen::Vector3d r = d.point - q;
      Eigen::Matrix2d H;
      H << d.du.dot(d.du) + r.dot(d.duu), d.du.dot(d.dv) + r.dot(d.duv), d.du.dot(d.dv) + r.dot(d.duv), d.dv.dot(d.dv) + r.dot(d.dvv);
      const Eigen::Vector2d g(r.dot(d.du), r.dot(d.dv));
      // A parameter at a bound of the domain whose gradient points outward stays there (edge minima).
      const bool fixU = (x[0] <= s.uMin() && g[0] > 0) || (x[0] >= s.uMax() && g[0] < 0);
      const bool fixV = (x[1] <= s.vMin() && g[1] > 0) || (x[1] >= s.vMax() && g[1] < 0);
      Eigen::Vector2d step = H.determinant() > 0 && H(0, 0) > 0 ? Eigen::Vector2d(-H.inverse() * g) : Eigen::Vector2d(-g / (H.trace() + 1));
      if (fixU || fixV) {
        const int k = fixU ? 1 : 0;
        step.setZero();
        if (!(fixU && fixV)) step[k] = -g[k] / (H(k, k) > 0 ? H(k, k) : std::abs(H(k, k)) + 1);
      }
      bool improved = false;
      for (int h = 0; h < 30 && !improved; ++h, step *= 0.5) {
        Eigen::Vector2d y = x + step;
        y[0] = std::clamp(y[0], s.uMin(), s.uMax());
        y[1] = std::clamp(y[1], s.vMin(), s.vMax());
        const double vy = (s.evaluate(y[0], y[1]) - q).norm();
        if (vy < value) {
          value = vy;
          x = y;
          improved = true;
        }
      }
      if (!improved) break;
    }
    return value;
  }
};

}  // namespace nurbs_fixtures
