#include "probe_path.h"

#include <algorithm>
#include <cmath>

namespace unidist::haptic {
namespace {

/// Uniform Catmull-Rom between p1 and p2 at s in [0, 1].
Eigen::Vector3d catmullRom(const Eigen::Vector3d& p0, const Eigen::Vector3d& p1, const Eigen::Vector3d& p2,
                           const Eigen::Vector3d& p3, double s) {
  const double s2 = s * s, s3 = s2 * s;
  return 0.5 * ((2 * p1) + (p2 - p0) * s + (2 * p0 - 5 * p1 + 4 * p2 - p3) * s2 + (3 * p1 - p0 - 3 * p2 + p3) * s3);
}

}  // namespace

std::vector<Eigen::Isometry3d> samplePath(const std::vector<Eigen::Isometry3d>& waypoints, int steps) {
  const int segments = static_cast<int>(waypoints.size()) - 1;
  const auto at = [&](int i) -> const Eigen::Isometry3d& {  // the ends repeat: zero curvature there
    return waypoints[static_cast<std::size_t>(std::clamp(i, 0, segments))];
  };
  std::vector<Eigen::Isometry3d> out;
  out.reserve(static_cast<std::size_t>(std::max(steps, 0)));
  for (int k = 0; k < steps; ++k) {
    const double t = static_cast<double>(segments) * k / (steps - 1);
    const int i = std::min(static_cast<int>(std::floor(t)), segments - 1);
    const double s = t - i;
    Eigen::Isometry3d X = Eigen::Isometry3d::Identity();
    X.translation() = catmullRom(at(i - 1).translation(), at(i).translation(), at(i + 1).translation(),
                                 at(i + 2).translation(), s);
    const Eigen::Quaterniond q0(at(i).linear()), q1(at(i + 1).linear());
    X.linear() = q0.slerp(s * s * (3 - 2 * s), q1).toRotationMatrix();  // slerp takes the shorter arc
    out.push_back(X);
  }
  return out;
}

}  // namespace unidist::haptic
