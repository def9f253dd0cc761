// Display tessellation of triangle meshes (as they are, flat-shaded), point clouds (dots) and NURBS models
// (each rational Bézier patch on its own grid), and the dispatch over every model type.
#include "tessellate.h"

#include "mesh_builder.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/point_cloud.h"

#include <cmath>

namespace unidist::render {
namespace {

constexpr double kPi = 3.14159265358979323846;

/// Flat shading: each triangle gets its own three vertices with its face normal, so creases stay sharp.
DisplayMesh triangleMesh(const TriangleMesh& mesh) {
  DisplayMesh out;
  const auto& triangles = mesh.triangles();
  out.positions.reserve(3 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Eigen::Vector3d& n = mesh.faceNormal(static_cast<int>(t));
    for (int k = 0; k < 3; ++k) {
      out.triangles.push_back(static_cast<std::uint32_t>(out.positions.size()));
      out.positions.push_back(mesh.vertices()[static_cast<std::size_t>(triangles[t][k])]);
      out.normals.push_back(n);
    }
  }
  return out;
}

/// Dots shaded by the cloud's normals, or (where it has none) by the direction from the cloud's centroid,
/// which reads well for the blob-like clouds of the demos.
DisplayMesh pointCloud(const PointCloud& cloud) {
  DisplayMesh out;
  out.points = cloud.points();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (const Eigen::Vector3d& p : out.points) centroid += p;
  if (!out.points.empty()) centroid /= static_cast<double>(out.points.size());
  for (std::size_t i = 0; i < out.points.size(); ++i) {
    Eigen::Vector3d n = i < cloud.normals().size() ? cloud.normals()[i] : Eigen::Vector3d::Zero();
    if (!(n.norm() > 0)) n = out.points[i] - centroid;
    out.pointNormals.push_back(n.norm() > 0 ? Eigen::Vector3d(n.normalized()) : Eigen::Vector3d::UnitZ());
  }
  return out;
}

/// Total turning angle of the control polygon along one parameter direction, the largest over the rows. A
/// Bézier curve turns no more than its control polygon, so this many chords of the primitives' angle suffice
/// where the curvature radius is about the patch's size.
double controlTurning(const RationalBezierPatch& patch, bool alongU) {
  const int rows = alongU ? patch.degreeV : patch.degreeU, length = alongU ? patch.degreeU : patch.degreeV;
  double most = 0;
  for (int r = 0; r <= rows; ++r) {
    double turning = 0;
    Eigen::Vector3d previous = Eigen::Vector3d::Zero();
    for (int k = 0; k < length; ++k) {
      const Eigen::Vector3d edge = alongU ? Eigen::Vector3d(patch.point(k + 1, r) - patch.point(k, r))
                                          : Eigen::Vector3d(patch.point(r, k + 1) - patch.point(r, k));
      if (!(edge.norm() > 0)) continue;
      if (previous.norm() > 0) turning += std::atan2(previous.cross(edge).norm(), previous.dot(edge));
      previous = edge;
    }
    most = std::max(most, turning);
  }
  return most;
}

DisplayMesh nurbs(const NurbsModel& model, int segmentsPerCircle) {
  DisplayMesh out;
  const double chordAngle = 2 * kPi / segmentsPerCircle;
  const auto& patches = model.patches();
  for (std::size_t k = 0; k < patches.size(); ++k) {
    const RationalBezierPatch& patch = patches[k];
    const auto count = [&](bool alongU) {
      const int degree = alongU ? patch.degreeU : patch.degreeV;
      return std::clamp(static_cast<int>(std::ceil(controlTurning(patch, alongU) / chordAngle)), std::max(degree, 1),
                        256);
    };
    const int rows = count(true), columns = count(false);
    appendGrid(out, rows, columns, [&](int i, int j) {
      const double s = double(i) / rows, t = double(j) / columns;
      return SurfaceSample{patch.evaluate(s, t), model.patchNormal(static_cast<int>(k), s, t)};
    });
  }
  return out;
}

}  // namespace

DisplayMesh tessellate(const Model& model, const TessellationOptions& options) {
  if (!(options.planeHalfExtent > 0) || !std::isfinite(options.planeHalfExtent) || !options.planeCentre.allFinite())
    throw InputError("display tessellation: the plane's square needs a finite centre and a half extent > 0");
  switch (model.type()) {
    case ModelType::Mesh:
      return triangleMesh(static_cast<const TriangleMesh&>(model));
    case ModelType::PointCloud:
      return pointCloud(static_cast<const PointCloud&>(model));
    case ModelType::Nurbs:
      return nurbs(static_cast<const NurbsModel&>(model), segmentsPerCircle(options.relativeChordError));
    default:
      return tessellatePrimitive(model, options);
  }
}

}  // namespace unidist::render
