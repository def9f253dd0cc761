// Spatialized normal cone search between two triangle meshes (algorithms.md §4.3): every pair of features
// (vertex, edge, face) whose closest points are mutually locally closest — the direction from A's point to B's
// lies in A's generalised normal set there and its opposite in B's — with distance <= margin. Internal.
//
// Traversal: depth-first over node pairs; a pair is dropped when its lower bound (ball gap, and A's box against
// B's box turned into A's frame) exceeds the margin, or — only when the volumes are apart, so that the cone of
// segment directions between the balls is meaningful, and both nodes are small (their cones are built from every
// triangle below them) — when A's widened cone cannot hold a segment direction, B's cannot hold its opposite, or
// the two cannot be opposite. Leaves: the 6 vertex–triangle and the 9
// edge–edge closest pairs of each triangle pair (a local minimum between two triangulated surfaces always has
// one end at a vertex or both inside edges; parallel edges are covered by their end vertices), each tested
// against the features' normal sets and deduplicated on the feature pair. Where both ends lie inside flat
// regions facing each other (a face-on-face contact) only the corners of the contact polygon are kept: a
// vertex against a flat region when the vertex is not itself inside a flat region nor in the middle of a
// straight side of it, and an edge crossing only between two edges that bound their flat regions.
#pragma once

#include "contacts/mesh_features.h"
#include "unidist/contacts.h"

#include <array>
#include <vector>

namespace unidist::contact {

struct SnchResult {
  std::vector<Contact> contacts;                        ///< in A's frame
  std::vector<std::array<std::uint32_t, 2>> overlapping;  ///< leaf pairs whose volumes overlap (penetration candidates)
  long nodePairs = 0, leafPairs = 0;
};

/// B is posed in A's frame by X_AB. dirEps: below this distance the direction comes from the features
/// rather than from the two points (rounding dominates there).
SnchResult snchSearch(const TriangleMesh& a, const MeshFeatures& fa, const TriangleMesh& b, const MeshFeatures& fb,
                      const Eigen::Isometry3d& X_AB, double margin, double tol, double dirEps);

/// Whether two leaves of the search hold a pair of crossing triangles.
bool leavesIntersect(const TriangleMesh& a, const TriangleMesh& b, const Eigen::Isometry3d& X_AB, std::uint32_t leafA,
                     std::uint32_t leafB);

}  // namespace unidist::contact
