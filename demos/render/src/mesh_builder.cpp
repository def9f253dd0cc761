#include "mesh_builder.h"

namespace unidist::render {
namespace {

/// Adds triangle (a, b, c) of existing vertices, turned to face the mean of their normals; skips slivers.
void addTriangle(DisplayMesh& mesh, std::uint32_t a, std::uint32_t b, std::uint32_t c) {
  const Eigen::Vector3d& pa = mesh.positions[a];
  const Eigen::Vector3d cross = (mesh.positions[b] - pa).cross(mesh.positions[c] - pa);
  const double scale = (mesh.positions[b] - pa).squaredNorm() + (mesh.positions[c] - pa).squaredNorm();
  if (!(cross.norm() > 1e-12 * scale)) return;
  const Eigen::Vector3d outward = mesh.normals[a] + mesh.normals[b] + mesh.normals[c];
  if (cross.dot(outward) < 0) std::swap(b, c);
  mesh.triangles.insert(mesh.triangles.end(), {a, b, c});
}

}  // namespace

void appendGrid(DisplayMesh& mesh, int rows, int columns, const std::function<SurfaceSample(int, int)>& sample) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (int i = 0; i <= rows; ++i) {
    for (int j = 0; j <= columns; ++j) {
      const SurfaceSample s = sample(i, j);
      mesh.positions.push_back(s.point);
      mesh.normals.push_back(s.normal);
    }
  }
  const auto at = [&](int i, int j) { return first + static_cast<std::uint32_t>(i * (columns + 1) + j); };
  for (int i = 0; i < rows; ++i) {
    for (int j = 0; j < columns; ++j) {
      addTriangle(mesh, at(i, j), at(i + 1, j), at(i + 1, j + 1));
      addTriangle(mesh, at(i, j), at(i + 1, j + 1), at(i, j + 1));
    }
  }
}

void appendFan(DisplayMesh& mesh, const std::vector<Eigen::Vector3d>& corners, const Eigen::Vector3d& normal) {
  const auto first = static_cast<std::uint32_t>(mesh.positions.size());
  for (const Eigen::Vector3d& p : corners) {
    mesh.positions.push_back(p);
    mesh.normals.push_back(normal);
  }
  for (std::size_t k = 1; k + 1 < corners.size(); ++k)
    addTriangle(mesh, first, first + static_cast<std::uint32_t>(k), first + static_cast<std::uint32_t>(k + 1));
}

}  // namespace unidist::render
