// A closed, outward-oriented mesh bounds its solid exactly, so the integrals are sums over the signed
// tetrahedra (c, a, b, d) of its triangles with a common apex c (Mirtich 1996; Tonon 2004): with
// D = (a−c)·((b−c)×(d−c)), a tetrahedron contributes D/6 to the volume, D/24·Σv to the first moment and
// D/120·(Σ v vᵀ + s sᵀ) (s = Σv, v relative to c) to the second moments. Exact up to rounding.
#include "mass/mass_parts.h"
#include "mass/volume_moments.h"

namespace unidist::mass {

MassProperties meshMass(const TriangleMesh& mesh) {
  VolumeMoments m;
  m.origin = mesh.localBounds().center();
  const std::vector<Eigen::Vector3d>& vertices = mesh.vertices();
  double volume6 = 0;
  Eigen::Vector3d first24 = Eigen::Vector3d::Zero();
  Eigen::Matrix3d second120 = Eigen::Matrix3d::Zero();
  for (const TriangleMesh::Triangle& t : mesh.triangles()) {
    const Eigen::Vector3d a = vertices[t[0]] - m.origin, b = vertices[t[1]] - m.origin, d = vertices[t[2]] - m.origin;
    const double D = a.dot(b.cross(d));
    const Eigen::Vector3d s = a + b + d;
    volume6 += D;
    first24 += D * s;
    second120 += D * (a * a.transpose() + b * b.transpose() + d * d.transpose() + s * s.transpose());
  }
  m.volume = volume6 / 6;
  m.first = first24 / 24;
  m.second = second120 / 120;
  return toMassProperties(m, mesh);
}

}  // namespace unidist::mass
