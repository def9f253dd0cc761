// The torus and the sphere as exact rational NURBS solids. The torus: the tube circle (radius r about (R, 0) in
// the (rho, z) half-plane) revolved about z, both circles the standard 9-point rational quadratic form (weights 1,
// √½ alternating over the knots 0, ¼, ½, ¾, 1 doubled). The sphere: the meridian half circle (5 points, knots 0,
// ½, 1 doubled) revolved likewise; its poles are collapsed patch edges. The only inexact numbers are √½ and the
// products with it: the surfaces lie on the primitives to a few ulps of their size.
#include "unidist/nurbs.h"
#include "unidist/primitives.h"

#include <array>
#include <cmath>
#include <vector>

namespace unidist {
namespace {

struct CirclePoint {
  double c, s, w;  // Euclidean (cos-like, sin-like) control point of the unit circle and its weight
};

std::array<CirclePoint, 9> unitCircle() {
  const double h = std::sqrt(0.5);
  return {{{1, 0, 1}, {1, 1, h}, {0, 1, 1}, {-1, 1, h}, {-1, 0, 1}, {-1, -1, h}, {0, -1, 1}, {1, -1, h}, {1, 0, 1}}};
}

/// The unit circle's knots: its four quarters.
std::vector<double> circleKnots() { return {0, 0, 0, .25, .25, .5, .5, .75, .75, 1, 1, 1}; }

/// A degree-2 profile in the (rho, z) half-plane (Euclidean points and weights; knots `knotsV`) revolved about z
/// with the unit circle: u the angle about z, v along the profile.
NurbsSurface revolved(const std::vector<CirclePoint>& profile, std::vector<double> knotsV) {
  std::vector<std::vector<Eigen::Vector4d>> net;
  for (const CirclePoint& about : unitCircle()) {
    net.emplace_back();
    for (const CirclePoint& p : profile) net.back().emplace_back(about.c * p.c, about.s * p.c, p.s, about.w * p.w);
  }
  return {2, 2, circleKnots(), std::move(knotsV), std::move(net)};
}

NurbsSurface torusSurface(double R, double r) {
  std::vector<CirclePoint> tube;  // the tube circle about (R, 0)
  for (const CirclePoint& c : unitCircle()) tube.push_back({R + r * c.c, r * c.s, c.w});
  return revolved(tube, circleKnots());
}

NurbsSurface sphereSurface(double r) {
  const double h = std::sqrt(0.5);  // the meridian half circle, from the south pole to the north pole
  return revolved({{0, -r, 1}, {r, -r, h}, {r, 0, 1}, {r, r, h}, {0, r, 1}}, {0, 0, 0, .5, .5, 1, 1, 1});
}

}  // namespace

const NurbsModel& Sphere::asNurbs() const {
  return nurbs_.get([this] {
    std::vector<NurbsSurface> surfaces;
    surfaces.push_back(sphereSurface(r_));
    return std::make_shared<const NurbsModel>(std::move(surfaces), true);
  });
}

std::vector<StructureReport> Sphere::structures() const { return {nurbs_.report("exact-nurbs")}; }

std::size_t Sphere::memoryBytes() const { return sizeof(*this) + nurbs_.report("").bytes; }

const NurbsModel& Torus::asNurbs() const {
  return nurbs_.get([this] {
    std::vector<NurbsSurface> surfaces;
    surfaces.push_back(torusSurface(R_, r_));
    return std::make_shared<const NurbsModel>(std::move(surfaces), true);
  });
}

std::vector<StructureReport> Torus::structures() const { return {nurbs_.report("exact-nurbs")}; }

std::size_t Torus::memoryBytes() const { return sizeof(*this) + nurbs_.report("").bytes; }

}  // namespace unidist
