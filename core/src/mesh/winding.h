// Generalized winding number of a triangle mesh (Jacobson, Kavan & Sorkine-Hornung 2013): the sum of the
// signed solid angles of the triangles seen from q, over 4π. 1 inside and 0 outside a closed, outward
// oriented surface; in between near the holes of an open one. Internal.
//
// Exact hierarchical evaluation (the "boundary" variant of Jacobson et al., not Barill et al.'s far-field
// approximation): the triangles of a hierarchy node form a patch whose solid angle depends only on its
// boundary curve as long as q cannot see through the difference. For q outside the node's box, close the
// patch by the fan of its boundary half-edges from the box centre: patch + reversed fan is a closed surface
// inside the (convex) box, whose winding number at q is 0, so
//     Ω(patch) = Σ over boundary half-edges u → v of Ω(centre, u, v).
// Nodes whose boundary is longer than their triangle count are summed triangle by triangle. A closed mesh's
// root has no boundary, so q outside the whole box costs nothing; a query costs ~O(√n) solid angles.
// Van Oosterom & Strackee's formula gives each triangle's solid angle.
#pragma once

#include "mesh/bvh.h"

#include <cstdint>
#include <vector>

namespace unidist::mesh {

struct WindingData {
  /// Per node: boundary half-edges [edgeStart[i], edgeStart[i + 1]) of `edges`; a node whose list was not
  /// kept (a leaf, or a boundary as long as its triangle list) has useBoundary[i] = 0.
  std::vector<std::uint32_t> edgeStart;
  std::vector<std::uint8_t> useBoundary;
  std::vector<std::array<std::uint32_t, 2>> edges;  ///< (from, to) vertex ids
  std::size_t memoryBytes() const;
};

WindingData buildWindingData(const MeshBvh& bvh, const std::vector<TriangleMesh::Triangle>& triangles,
                             const std::vector<std::uint32_t>& twin);

/// Signed solid angle of triangle (a, b, c) seen from the origin (a, b, c relative to the eye), in [−2π, 2π].
double solidAngle(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c);

double windingNumber(const Eigen::Vector3d& q, const MeshBvh& bvh, const WindingData& data,
                     const std::vector<Eigen::Vector3d>& vertices,
                     const std::vector<TriangleMesh::Triangle>& triangles);

}  // namespace unidist::mesh
