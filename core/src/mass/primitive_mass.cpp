// Closed-form volume, centre of mass and inertia of the primitives, in their own frames (primitives.h):
// every solid of revolution is about z; the cone's base is at z = −h and its apex at z = +h, so its centre
// of mass is a quarter of the height above the base, at z = −h/2.
#include "mass/mass_parts.h"

#include <cmath>

namespace unidist::mass {
namespace {

constexpr double kPi = 3.14159265358979323846;

MassProperties diagonal(double volume, const Eigen::Vector3d& moments, double comZ = 0) {
  MassProperties out;
  out.volume = volume;
  out.centerOfMass = {0, 0, comZ};
  out.inertia = moments.asDiagonal();
  return out;
}

MassProperties sphere(const Sphere& s) {
  const double r = s.radius(), v = 4.0 / 3.0 * kPi * r * r * r;
  return diagonal(v, Eigen::Vector3d::Constant(0.4 * v * r * r));
}

MassProperties box(const Box& b) {
  const Eigen::Vector3d h = b.halfExtents(), h2 = h.cwiseProduct(h);
  const double v = 8 * h.prod();
  return diagonal(v, v / 3 * Eigen::Vector3d(h2.y() + h2.z(), h2.x() + h2.z(), h2.x() + h2.y()));
}

MassProperties cylinder(const Cylinder& c) {
  const double r = c.radius(), H = 2 * c.halfHeight(), v = kPi * r * r * H;
  const double side = v * (3 * r * r + H * H) / 12;
  return diagonal(v, {side, side, v * r * r / 2});
}

MassProperties cone(const Cone& c) {
  const double r = c.radius(), H = 2 * c.halfHeight(), v = kPi * r * r * H / 3;
  const double side = v * (3.0 / 20.0 * r * r + 3.0 / 80.0 * H * H);
  return diagonal(v, {side, side, 0.3 * v * r * r}, -c.halfHeight() / 2);
}

MassProperties capsule(const Capsule& c) {
  // Cylinder of length 2h plus two hemispheres; each hemisphere's transverse moment about the capsule centre
  // is (2/5) m r² about its own flat face centre, moved by the parallel axis theorem (the cross terms of
  // its centroid offset 3r/8 cancel to 2/5 r² + h² + 3hr/4 per unit volume).
  const double r = c.radius(), h = c.halfLength(), H = 2 * h;
  const double vCyl = kPi * r * r * H, vBall = 4.0 / 3.0 * kPi * r * r * r;
  const double side = vCyl * (3 * r * r + H * H) / 12 + vBall * (0.4 * r * r + h * h + 0.75 * h * r);
  return diagonal(vCyl + vBall, {side, side, vCyl * r * r / 2 + 0.4 * vBall * r * r});
}

MassProperties torus(const Torus& t) {
  const double R = t.majorRadius(), a = t.tubeRadius(), v = 2 * kPi * kPi * R * a * a;
  const double side = v * (R * R / 2 + 5.0 / 8.0 * a * a);
  return diagonal(v, {side, side, v * (R * R + 0.75 * a * a)});
}

}  // namespace

bool primitiveMass(const Model& m, MassProperties& out) {
  switch (m.type()) {
    case ModelType::Sphere: out = sphere(dynamic_cast<const Sphere&>(m)); return true;
    case ModelType::Box: out = box(dynamic_cast<const Box&>(m)); return true;
    case ModelType::Capsule: out = capsule(dynamic_cast<const Capsule&>(m)); return true;
    case ModelType::Cylinder: out = cylinder(dynamic_cast<const Cylinder&>(m)); return true;
    case ModelType::Cone: out = cone(dynamic_cast<const Cone&>(m)); return true;
    case ModelType::Torus: out = torus(dynamic_cast<const Torus&>(m)); return true;
    default: return false;
  }
}

}  // namespace unidist::mass
