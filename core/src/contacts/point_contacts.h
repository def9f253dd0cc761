// Contacts from point queries: the vertices of a mesh (or the points of a cloud) against any other model. A mesh
// vertex is kept when the other model's signed distance there is within the margin and no larger than at any of its
// mesh neighbours (a local minimum over the vertex graph; ties allowed within tol) — so a box resting on a plane
// gives its four bottom corners, and a mesh sunk into a solid its locally deepest vertices. On a plateau (a vertex
// inside a flat region facing the other model, with an equally distant neighbour) only the region's boundary
// vertices are kept. A cloud has no neighbours: each leaf of its hierarchy (at most four nearby points) gives its
// nearest point and the points as near within tol. The mesh's / cloud's hierarchy is descended with a point query at
// each node's ball centre (the signed distance is 1-Lipschitz, so a ball farther than its radius plus the margin
// holds nothing). Internal.
#pragma once

#include "contacts/mesh_features.h"
#include "unidist/contacts.h"
#include "unidist/point_cloud.h"

#include <vector>

namespace unidist::contact {

/// `isA`: whether the mesh / cloud is model A of the query (the contact's roles follow). `onlyInside`: keep
/// negative distances only (mesh–mesh, where the normal cone search finds the rest). Contacts in world.
void meshVertexContacts(const TriangleMesh& m, const MeshFeatures& mf, const Eigen::Isometry3d& X_WM, const Model& o,
                        const Eigen::Isometry3d& X_WO, double margin, double tol, bool isA, bool onlyInside,
                        std::vector<Contact>& out);

void cloudPointContacts(const PointCloud& c, const Eigen::Isometry3d& X_WC, const Model& o,
                        const Eigen::Isometry3d& X_WO, double margin, double tol, bool isA, std::vector<Contact>& out);

}  // namespace unidist::contact
