// Consumer of the installed package: a unit sphere 3 along x from a 2x2x2 box is 1 away, along -x.
#include <unidist/adapters/spec.h>
#include <unidist/bullet/version.h>
#include <unidist/distance.h>
#include <unidist/ode/version.h>
#include <unidist/primitives.h>

#include <cmath>
#include <cstdio>

int main() {
  const unidist::Sphere sphere(1.0);
  const unidist::Box box(Eigen::Vector3d(1.0, 1.0, 1.0));
  const Eigen::Isometry3d X_WA(Eigen::Translation3d(3.0, 0.0, 0.0));
  const unidist::DistanceResult r = unidist::distance(sphere, X_WA, box, Eigen::Isometry3d::Identity());
  const bool ok = std::abs(r.distance - 1.0) < 1e-9 && (r.normal + Eigen::Vector3d::UnitX()).norm() < 1e-9 &&
                  (r.pointB - r.pointA - r.distance * r.normal).norm() < 1e-9;
  std::printf("sphere-box distance %.17g (%s): %s\n", r.distance, unidist::toString(r.status), ok ? "ok" : "WRONG");

  // The same pair through the adapters (spec and pose strings).
  const auto spec = unidist::parsePrimitiveSpec("box:hx=1,hy=1,hz=1");
  const double d = unidist::distance(sphere, unidist::parsePose("3 0 0 1 0 0 0"), *spec,
                                     Eigen::Isometry3d::Identity()).distance;
  const bool okSpec = std::abs(d - 1.0) < 1e-9;
  std::printf("via adapters %.17g: %s\n%s\n%s\n", d, okSpec ? "ok" : "WRONG",
              unidist::bullet::engineVersion().c_str(), unidist::ode::engineConfiguration().c_str());
  return ok && okSpec ? 0 : 1;
}
