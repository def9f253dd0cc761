// What the contact search needs beyond the mesh's own data: the triangles meeting at a vertex, a vertex's
// neighbours, and per hierarchy node a normal cone widened by the normals of every triangle that shares a vertex
// with the node's triangles (local minima sit on edges and vertices, whose normal sets reach into the
// neighbours' normals; algorithms.md §4.3). Plus the features (vertex, edge, face) and their generalised normal
// sets. Everything is computed lazily and memoised for one query: the triangles at a vertex are found through the
// hierarchy (descending the nodes whose exact box holds the vertex), and a node's cone from its leaves, so a
// query pays for the part of the mesh it explores, not O(triangles). One object per query and thread. Internal.
#pragma once

#include "contacts/cones.h"
#include "unidist/mesh.h"

#include <cstdint>
#include <unordered_map>
#include <vector>

namespace unidist::contact {

class MeshFeatures {
 public:
  explicit MeshFeatures(const TriangleMesh& m) : m_(m), bvh_(m.bvh()) {}
  /// Triangles having vertex v as a corner.
  const std::vector<std::uint32_t>& trianglesAt(std::uint32_t v) const;
  /// Vertices sharing an edge with v.
  std::vector<std::uint32_t> neighbours(std::uint32_t v) const;
  /// Widened normal cone of hierarchy node i (see the top of this file).
  const DirCone& cone(std::uint32_t i) const;

 private:
  const TriangleMesh& m_;
  const mesh::MeshBvh& bvh_;
  mutable std::unordered_map<std::uint32_t, std::vector<std::uint32_t>> trianglesAt_;
  mutable std::unordered_map<std::uint32_t, DirCone> cones_;
};

/// A vertex (a), an edge (a < b) or a face (triangle a) of a mesh.
struct Feature {
  enum Kind : std::uint8_t { Vertex, Edge, Face } kind = Face;
  std::uint32_t a = 0, b = 0;
  std::uint64_t key() const { return (std::uint64_t(kind) << 62) | (std::uint64_t(a) << 31) | b; }
};

/// The feature of triangle t that holds a closest point classified as f.
Feature featureOf(const TriangleMesh& m, int t, TriangleFeature f);

/// Calls fn(triangle) for every triangle holding the feature.
template <class Fn>
void forIncident(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f, Fn&& fn) {
  if (f.kind == Feature::Face) {
    fn(f.a);
    return;
  }
  for (const std::uint32_t t : mf.trianglesAt(f.a)) {
    const auto& tri = m.triangles()[t];
    if (f.kind == Feature::Vertex || tri[0] == f.b || tri[1] == f.b || tri[2] == f.b) fn(t);
  }
}

/// Whether unit u is in the generalised normal set of the feature at its point p: p is the closest point to
/// p + h·u (small h) of every triangle holding the feature, i.e. (x − p)·u <= slack·|x − p| for their vertices
/// x. For a solid, u must also leave the solid (positive on the sum of the triangles' outward normals).
bool inNormalSet(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f, const Eigen::Vector3d& p,
                 const Eigen::Vector3d& u, double slack);

/// Whether every triangle holding the feature faces u (normal within max(slack, 1e-6) rad; either side for an
/// open mesh) and the feature is not on an open surface's boundary: it is inside a flat region facing u.
bool isFlat(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f, const Eigen::Vector3d& u, double slack);

/// Whether a vertex sits on a straight crease between a flat region facing u and one other plane: a point on the
/// side of a flat contact region, not one of its corners.
bool onStraightCrease(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f, const Eigen::Vector3d& u,
                      double slack);

/// Sum of the outward normals of the triangles holding the feature (a direction leaving a solid there).
Eigen::Vector3d normalSum(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f);

/// One triangle holding the feature (for Contact::feature).
int someTriangle(const MeshFeatures& mf, const Feature& f);

}  // namespace unidist::contact
