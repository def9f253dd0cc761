// Display tessellation of any core model, for pictures only (never for queries): triangles with per-vertex
// normals, plus lines and points for what has no surface to shade. Built once per model and reused every frame.
//
// Chordal error: the primitives' circles are cut into chords whose sagitta is at most
// `relativeChordError` × that circle's radius, so every point of a curved primitive's triangles lies within
// 2 × relativeChordError × its largest radius of the exact surface (two directions of curvature add up);
// vertices lie on the surface. Boxes and meshes are exact. NURBS patches are sampled on a grid whose spacing
// follows the turning of their control nets (the same angle per chord as the primitives; a measured, not proved,
// bound: tests/render). A half-space is an unbounded model: it becomes a square of `planeHalfExtent` around the
// point of the plane closest to `planeCentre`, with grid lines.
#pragma once

#include "unidist/model.h"

#include <Eigen/Geometry>

#include <cstdint>
#include <vector>

namespace unidist::render {

struct DisplayMesh {
  std::vector<Eigen::Vector3d> positions;   ///< triangle vertices (model frame)
  std::vector<Eigen::Vector3d> normals;     ///< one outward unit normal per position
  std::vector<std::uint32_t> triangles;     ///< three indices into positions per triangle, counter-clockwise outside
  std::vector<Eigen::Vector3d> linePoints;  ///< segment end points, two per segment (drawn unlit, darker)
  std::vector<Eigen::Vector3d> points;      ///< drawn as dots (point clouds)
  std::vector<Eigen::Vector3d> pointNormals;  ///< one per point, for shading the dots

  std::size_t triangleCount() const { return triangles.size() / 3; }
};

struct TessellationOptions {
  double relativeChordError = 2e-3;  ///< sagitta of a chord over its circle's radius, in (0, 0.25]
  double planeHalfExtent = 1.0;      ///< half side of the square drawn for a half-space
  Eigen::Vector3d planeCentre = Eigen::Vector3d::Zero();  ///< model frame; the square is centred at its projection
};

/// Chords per full circle for the given relative sagitta (at least 8, at most 1024).
int segmentsPerCircle(double relativeChordError);

/// The display tessellation of `model` in its own frame. Throws InputError for options out of range.
DisplayMesh tessellate(const Model& model, const TessellationOptions& options = {});

}  // namespace unidist::render
