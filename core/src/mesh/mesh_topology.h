// Mesh cleaning and connectivity: exact welding, zero-area and duplicate triangle removal, edge topology
// (which half-edges pair up, which edges are boundary, non-manifold or misoriented), vertex fans, signed
// volume. All linear time (bucketing by the smallest vertex index instead of sorting or hashing). Internal.
#pragma once

#include "unidist/mesh.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace unidist::mesh {

using Triangle = TriangleMesh::Triangle;

constexpr std::uint32_t kNoTwin = std::numeric_limits<std::uint32_t>::max();

/// For each input vertex the id of its position among the distinct positions (ids in order of first
/// appearance). Positions are equal when every coordinate compares equal (so -0 == +0).
std::vector<std::uint32_t> weldExact(const std::vector<Eigen::Vector3d>& vertices, std::size_t& distinct);

/// Indices (into `triangles`) of the triangles to keep: zero-area ones (a repeated index, or collinear
/// vertices decided exactly) and repeats of an earlier triangle with the same three vertices (either
/// orientation) are dropped and counted.
std::vector<std::uint32_t> keptTriangles(const std::vector<Eigen::Vector3d>& vertices,
                                         const std::vector<Triangle>& triangles, std::size_t& zeroArea,
                                         std::size_t& duplicates);

struct EdgeTopology {
  std::vector<std::uint32_t> twin;  ///< per half-edge 3t + k: the opposite half-edge, or kNoTwin
  std::size_t edges = 0, boundary = 0, nonManifold = 0, misoriented = 0;
  bool closed() const { return boundary == 0 && nonManifold == 0; }
  /// No edge traversed twice in the same direction (an edge of three or more triangles counts as misoriented
  /// unless its directions alternate; it makes the mesh open anyway).
  bool consistent() const { return misoriented == 0; }
};

/// Half-edge 3t + k runs from triangles[t][k] to triangles[t][(k + 1) % 3]. Two half-edges are twins when
/// their edge has exactly these two and they run in opposite directions.
EdgeTopology buildEdgeTopology(std::size_t vertexCount, const std::vector<Triangle>& triangles);

/// Number of separate triangle fans around each vertex (1 for a manifold vertex of a closed mesh). Needs
/// every half-edge to have a twin.
std::vector<std::uint32_t> fansPerVertex(std::size_t vertexCount, const std::vector<Triangle>& triangles,
                                         const std::vector<std::uint32_t>& twin);

/// Number of connected components of triangles joined by twin half-edges.
std::size_t connectedComponents(std::size_t triangleCount, const std::vector<std::uint32_t>& twin);

/// Signed volume enclosed (positive for outward normals), with coordinates taken relative to `origin` so
/// that a model far from the origin loses no digits.
double signedVolume(const std::vector<Eigen::Vector3d>& vertices, const std::vector<Triangle>& triangles,
                    const Eigen::Vector3d& origin);

}  // namespace unidist::mesh
