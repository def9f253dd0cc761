// Helpers that append shaded geometry to a DisplayMesh: a parametric grid and a flat polygon fan. Triangles are
// oriented by the normals given (counter-clockwise seen from where the normal points); zero-area triangles
// (a grid row collapsed to a pole or an apex) are left out.
#pragma once

#include "unidist/render/display_mesh.h"

#include <functional>

namespace unidist::render {

/// A surface point and its outward unit normal.
struct SurfaceSample {
  Eigen::Vector3d point;
  Eigen::Vector3d normal;
};

/// (rows + 1) × (columns + 1) samples sample(i, j), i = 0..rows, j = 0..columns, joined into 2 triangles per cell.
void appendGrid(DisplayMesh& mesh, int rows, int columns, const std::function<SurfaceSample(int i, int j)>& sample);

/// A flat convex polygon (its corners in order, either direction) with one normal.
void appendFan(DisplayMesh& mesh, const std::vector<Eigen::Vector3d>& corners, const Eigen::Vector3d& normal);

}  // namespace unidist::render
