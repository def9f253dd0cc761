// Model-independent pieces: type names, box arithmetic, the default bounding sphere and level of detail.
#include "unidist/model.h"

#include "lod/stand_in_cache.h"
#include "unidist/query_options.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace unidist {

const char* toString(ModelType t) {
  switch (t) {
    case ModelType::Sphere: return "sphere";
    case ModelType::Box: return "box";
    case ModelType::Capsule: return "capsule";
    case ModelType::Cylinder: return "cylinder";
    case ModelType::Cone: return "cone";
    case ModelType::Torus: return "torus";
    case ModelType::Plane: return "plane";
    case ModelType::Mesh: return "mesh";
    case ModelType::PointCloud: return "pointcloud";
    case ModelType::Nurbs: return "nurbs";
  }
  return "unknown";
}

// Arvo's method: each output coordinate is t_i + sum_j R_ij x_j with x_j free in [min_j, max_j], so its
// extremes take the smaller and the larger of R_ij·min_j and R_ij·max_j term by term. This is exactly the
// box of the eight moved corners. A zero R_ij is skipped so that 0·inf never makes a NaN for half-spaces.
Aabb Aabb::transformed(const Eigen::Isometry3d& X) const {
  if (empty()) return Aabb{};
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  const Eigen::Matrix3d R = X.linear();
  Aabb out;
  for (int i = 0; i < 3; ++i) {
    const double t = X.translation()[i];
    double lo = t, hi = t, loSize = std::abs(t), hiSize = std::abs(t);
    for (int j = 0; j < 3; ++j) {
      if (R(i, j) == 0.0) continue;
      const double a = R(i, j) * min[j], b = R(i, j) * max[j];
      lo += std::min(a, b);
      hi += std::max(a, b);
      loSize += std::abs(std::min(a, b));
      hiSize += std::abs(std::max(a, b));
    }
    // Outward by a few ulps of what was summed: the sums round, and the box must still hold every moved
    // corner. A side whose sum is infinite is infinite already.
    out.min[i] = std::isfinite(loSize) ? lo - 4.0 * kEps * loSize : lo;
    out.max[i] = std::isfinite(hiSize) ? hi + 4.0 * kEps * hiSize : hi;
  }
  return out;
}

double Aabb::distanceTo(const Eigen::Vector3d& p) const {
  if (empty()) return std::numeric_limits<double>::infinity();
  const Eigen::Vector3d gap = p - clamp(p);
  // Scaled so that a huge gap does not overflow its square.
  const double m = gap.cwiseAbs().maxCoeff();
  return m > 0 ? m * (gap / m).norm() : 0.0;
}

BoundingSphere Model::localBoundingSphere() const {
  const Aabb box = localBounds();
  BoundingSphere s;
  if (box.empty()) return s;  // nothing to hold: radius 0 at the origin
  if (!box.bounded()) {
    s.radius = std::numeric_limits<double>::infinity();
    return s;
  }
  s.center = box.center();
  // The half diagonal, a few ulps larger so that the rounded centre (off by ulps of its own size, which
  // can exceed the box's far from the origin) still holds every corner.
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  const Eigen::Vector3d half = 0.5 * box.max - 0.5 * box.min;  // halves first: max - min may overflow
  const double m = half.cwiseAbs().maxCoeff();
  const double halfDiagonal = m > 0 ? m * (half / m).norm() : 0.0;  // scaled: the squares may overflow
  s.radius = halfDiagonal * (1.0 + 8.0 * kEps) + 8.0 * kEps * s.center.norm();
  return s;
}

namespace lod {
void checkLevel(double maxDeviation) {
  if (const char* why = invalidLevelOfDetail(maxDeviation)) throw InputError(why);
}
}  // namespace lod

StandIn Model::atDetail(double maxDeviation) const {
  lod::checkLevel(maxDeviation);
  return StandIn{this, 0.0};
}

}  // namespace unidist
