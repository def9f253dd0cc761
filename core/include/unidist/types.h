// Basic value types shared by every model and query. Units: model length; frames named as in FCL's
// monogram notation (p_AQ: point Q in frame A; X_WA: pose of A in world W).
#pragma once

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <limits>
#include <stdexcept>
#include <string>

namespace unidist {

/// Thrown when input (a size, a file, a spec) cannot make a valid model; the message names the problem.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// Largest coordinate magnitude a mesh vertex or a cloud point may have: their hierarchies keep float boxes
/// (float overflows at 3.4e38; this leaves room for the boxes' rounding and sums).
inline constexpr double kMaxModelCoordinate = 1e30;

/// Axis-aligned box; empty when min > max. Unbounded models (a half-space) use infinite coordinates.
struct Aabb {
  Eigen::Vector3d min = Eigen::Vector3d::Constant(std::numeric_limits<double>::infinity());
  Eigen::Vector3d max = Eigen::Vector3d::Constant(-std::numeric_limits<double>::infinity());

  bool empty() const { return (min.array() > max.array()).any(); }
  bool bounded() const { return min.allFinite() && max.allFinite(); }
  /// Computed from the halves and scaled, so that a box of finite extent never gives Inf (±1e300: max - min
  /// and its squares overflow); Inf only when the diagonal itself exceeds the largest double.
  double diagonal() const {
    if (empty()) return 0.0;
    const Eigen::Vector3d half = 0.5 * max - 0.5 * min;
    const double m = half.cwiseAbs().maxCoeff();
    return m > 0 ? 2.0 * (m * (half / m).norm()) : 0.0;
  }
  Eigen::Vector3d center() const { return 0.5 * (min + max); }
  void extend(const Eigen::Vector3d& p) {
    min = min.cwiseMin(p);
    max = max.cwiseMax(p);
  }
  /// The box of this box's eight corners moved by X (conservative for a rotated box).
  Aabb transformed(const Eigen::Isometry3d& X) const;
  /// Euclidean distance from p to the box (0 inside).
  double distanceTo(const Eigen::Vector3d& p) const;
  /// Closest point of the box to p (p itself when inside).
  Eigen::Vector3d clamp(const Eigen::Vector3d& p) const { return p.cwiseMax(min).cwiseMin(max); }
};

/// Ball containing a model (or a piece of its surface).
struct BoundingSphere {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();
  double radius = 0;
};

/// Answer of a point query on one model, all in the model's own frame.
struct SurfacePoint {
  Eigen::Vector3d point = Eigen::Vector3d::Zero();   ///< closest point on the surface
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ(); ///< outward unit normal there (a defined choice where not unique)
  double signedDistance = 0;  ///< |q - point|, negative when q is inside a solid
  int feature = 0;            ///< model-specific feature id (face, edge, vertex, patch, triangle, point index)
  Eigen::Vector2d param = Eigen::Vector2d::Zero();  ///< surface parameters where the model has them
  /// Proved: the true distance from q to the surface is within `error` of |signedDistance| (beyond rounding).
  /// 0 for the closed-form models (primitives, meshes, clouds); a NURBS model's search tolerance, or the gap its
  /// budget left open.
  double error = 0;
};

/// How sure an answer is: certified = proved within the requested tolerance; bounded = only the
/// reported [lowerBound, upperBound] interval is proved.
enum class Status { Certified, Bounded };

inline const char* toString(Status s) { return s == Status::Certified ? "certified" : "bounded"; }

}  // namespace unidist
