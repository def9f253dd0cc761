// Cones of directions covering the unit sphere: the cells of a cube map, split into quarters. Internal.
#pragma once

#include <Eigen/Core>

#include <array>
#include <vector>

namespace unidist::detail {

/// The directions through the square [u0,u1]×[v0,v1] of one face of the cube [−1,1]³ (gnomonic cell).
struct DirectionCone {
  int face = 0;  ///< 0..5: +x, −x, +y, −y, +z, −z
  double u0 = -1, u1 = 1, v0 = -1, v1 = 1;
  int level = 0;
  Eigen::Vector3d axis = Eigen::Vector3d::UnitX();  ///< the direction through the square's centre
  double halfAngle = 0;  ///< proved: every direction of the cell is within this angle of the axis
};

/// The unit direction through (u, v) on the given face.
Eigen::Vector3d cubeMapDirection(int face, double u, double v);

/// The cell [u0,u1]×[v0,v1] of a face, with axis and half-angle filled in.
DirectionCone makeCone(int face, double u0, double u1, double v0, double v1, int level);

/// Every face split into n×n cells: they cover all directions.
std::vector<DirectionCone> cubeMapCones(int n);

/// The four quarters of a cell.
std::array<DirectionCone, 4> splitCone(const DirectionCone& c);

}  // namespace unidist::detail
