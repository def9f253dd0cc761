// Display tessellation of the analytic primitives from their exact parameters (see display_mesh.h for the
// chordal error). Vertices are computed from the closed-form surface, so they lie on it to rounding.
#include "tessellate.h"

#include "mesh_builder.h"

#include <cmath>

namespace unidist::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

Eigen::Vector3d radial(double angle) { return {std::cos(angle), std::sin(angle), 0}; }

/// Rows of a capsule's profile (a sphere when halfLength is 0): latitude and the z offset of its centre.
struct ProfileRow {
  double latitude, zOffset;
};

/// Sphere or capsule: latitude rows from the south pole to the north pole, the lower half about z = -h, the
/// upper half about z = +h (the band between the two equators is the capsule's cylinder).
DisplayMesh roundedSolid(double r, double h, int segments) {
  std::vector<ProfileRow> rows;
  const int quarter = segments / 4;
  for (int k = 0; k <= quarter; ++k) rows.push_back({-kPi / 2 + k * (kPi / 2) / quarter, -h});
  for (int k = h > 0 ? 0 : 1; k <= quarter; ++k) rows.push_back({k * (kPi / 2) / quarter, h});
  DisplayMesh mesh;
  appendGrid(mesh, static_cast<int>(rows.size()) - 1, segments, [&](int i, int j) {
    const ProfileRow& row = rows[static_cast<std::size_t>(i)];
    const double u = (j == segments ? 0 : j) * 2 * kPi / segments;  // the seam repeats the first column exactly
    const Eigen::Vector3d n = std::cos(row.latitude) * radial(u) + std::sin(row.latitude) * Eigen::Vector3d::UnitZ();
    return SurfaceSample{r * n + Eigen::Vector3d(0, 0, row.zOffset), n};
  });
  return mesh;
}

std::vector<Eigen::Vector3d> circle(double r, double z, int segments) {
  std::vector<Eigen::Vector3d> out;
  for (int j = 0; j < segments; ++j) out.push_back(r * radial(j * 2 * kPi / segments) + Eigen::Vector3d(0, 0, z));
  return out;
}

DisplayMesh cylinder(double r, double h, int segments) {
  DisplayMesh mesh;
  appendGrid(mesh, 1, segments, [&](int i, int j) {
    const Eigen::Vector3d n = radial((j == segments ? 0 : j) * 2 * kPi / segments);
    return SurfaceSample{r * n + Eigen::Vector3d(0, 0, i ? h : -h), n};
  });
  appendFan(mesh, circle(r, h, segments), Eigen::Vector3d::UnitZ());
  appendFan(mesh, circle(r, -h, segments), -Eigen::Vector3d::UnitZ());
  return mesh;
}

/// Base disc of radius r at z = -h, apex at z = +h. The apex row repeats per column, each with the normal of its
/// column, so the side shades smoothly around.
DisplayMesh cone(double r, double h, int segments) {
  DisplayMesh mesh;
  const double slant = std::hypot(2 * h, r);
  appendGrid(mesh, 1, segments, [&](int i, int j) {
    const Eigen::Vector3d u = radial((j == segments ? 0 : j) * 2 * kPi / segments);
    const Eigen::Vector3d n = (2 * h / slant) * u + (r / slant) * Eigen::Vector3d::UnitZ();
    return SurfaceSample{i ? Eigen::Vector3d(0, 0, h) : Eigen::Vector3d(r * u + Eigen::Vector3d(0, 0, -h)), n};
  });
  appendFan(mesh, circle(r, -h, segments), -Eigen::Vector3d::UnitZ());
  return mesh;
}

DisplayMesh torus(double R, double r, int segments) {
  DisplayMesh mesh;
  appendGrid(mesh, segments, segments, [&](int i, int j) {
    const Eigen::Vector3d toward = radial((i == segments ? 0 : i) * 2 * kPi / segments);  // centre-circle direction
    const double v = (j == segments ? 0 : j) * 2 * kPi / segments;                        // around the tube
    const Eigen::Vector3d n = std::cos(v) * toward + std::sin(v) * Eigen::Vector3d::UnitZ();
    return SurfaceSample{R * toward + r * n, n};
  });
  return mesh;
}

DisplayMesh box(const Eigen::Vector3d& half) {
  DisplayMesh mesh;
  for (int axis = 0; axis < 3; ++axis) {
    for (double side : {1.0, -1.0}) {
      const int a = (axis + 1) % 3, b = (axis + 2) % 3;
      std::vector<Eigen::Vector3d> corners;
      for (const auto& [sa, sb] : {std::pair{-1.0, -1.0}, {1.0, -1.0}, {1.0, 1.0}, {-1.0, 1.0}}) {
        Eigen::Vector3d p;
        p[axis] = side * half[axis];
        p[a] = sa * half[a];
        p[b] = sb * half[b];
        corners.push_back(p);
      }
      appendFan(mesh, corners, side * Eigen::Vector3d::Unit(axis));
    }
  }
  return mesh;
}

/// A square of the plane n·x = d around the point closest to `centre`, with grid lines (8 cells a side).
DisplayMesh plane(const Plane& plane, const TessellationOptions& options) {
  const Eigen::Vector3d& n = plane.normal();
  const Eigen::Vector3d origin = options.planeCentre - (n.dot(options.planeCentre) - plane.offset()) * n;
  const Eigen::Vector3d t1 = n.unitOrthogonal(), t2 = n.cross(t1);
  const double e = options.planeHalfExtent;
  DisplayMesh mesh;
  appendFan(mesh, {origin - e * t1 - e * t2, origin + e * t1 - e * t2, origin + e * t1 + e * t2, origin - e * t1 + e * t2},
            n);
  constexpr int kCells = 8;
  for (int k = 0; k <= kCells; ++k) {
    const double s = -e + 2 * e * k / kCells;
    mesh.linePoints.insert(mesh.linePoints.end(), {origin + s * t1 - e * t2, origin + s * t1 + e * t2,
                                                   origin - e * t1 + s * t2, origin + e * t1 + s * t2});
  }
  return mesh;
}

}  // namespace

int segmentsPerCircle(double relativeChordError) {
  if (!(relativeChordError > 0 && relativeChordError <= 0.25))
    throw InputError("display tessellation: relative chord error must be in (0, 0.25] (got " +
                     std::to_string(relativeChordError) + ")");
  // A chord over the angle 2π/n has sagitta r (1 − cos(π/n)); a multiple of 4 keeps the equators and the
  // capsule's seams on grid rows.
  const int n = static_cast<int>(std::ceil(kPi / std::acos(1 - relativeChordError)));
  return std::clamp((n + 3) / 4 * 4, 8, 1024);
}

DisplayMesh tessellatePrimitive(const Model& model, const TessellationOptions& options) {
  const int n = segmentsPerCircle(options.relativeChordError);
  switch (model.type()) {
    case ModelType::Sphere:
      return roundedSolid(static_cast<const Sphere&>(model).radius(), 0, n);
    case ModelType::Capsule: {
      const auto& c = static_cast<const Capsule&>(model);
      return roundedSolid(c.radius(), c.halfLength(), n);
    }
    case ModelType::Cylinder: {
      const auto& c = static_cast<const Cylinder&>(model);
      return cylinder(c.radius(), c.halfHeight(), n);
    }
    case ModelType::Cone: {
      const auto& c = static_cast<const Cone&>(model);
      return cone(c.radius(), c.halfHeight(), n);
    }
    case ModelType::Torus: {
      const auto& t = static_cast<const Torus&>(model);
      return torus(t.majorRadius(), t.tubeRadius(), n);
    }
    case ModelType::Box:
      return box(static_cast<const Box&>(model).halfExtents());
    case ModelType::Plane:
      return plane(static_cast<const Plane&>(model), options);
    default:
      throw InputError(std::string("display tessellation: ") + toString(model.type()) + " is not a primitive");
  }
}

}  // namespace unidist::render
