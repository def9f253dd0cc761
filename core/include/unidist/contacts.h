// Contact points: the local minima of distance between two posed models within a cut-off (the margin), each
// with points, a normal and a signed distance in the conventions of docs/query-contract.md
// (pointB − pointA = distance · normal; the normal points from A toward B, or for penetration the way B must
// move to separate). What each pair family gives is docs/contacts.md:
//  * mesh–mesh (and box primitives, which are converted to exact 12-triangle meshes): every pair of features
//    (vertex, edge, face) whose closest points are mutually locally closest, found by a spatialized normal cone
//    search over the two hierarchies; on a flat face-on-face contact the corners of the contact polygon; where
//    the solids overlap, the locally deepest vertices of each inside the other (local minima of signed distance
//    over the vertex graph), or the global penetration when no vertex is inside (crossing edges, containment);
//  * mesh or point cloud against anything: every vertex / point that is a local minimum of the other model's
//    signed distance over its mesh neighbours (clouds: over its hierarchy leaf), plus the global minimum;
//  * every other pair: the global minimum (unidist::distance) when it is within the margin.
// All functions are thread-safe; the models are not modified.
#pragma once

#include "unidist/model.h"
#include "unidist/query_options.h"

#include <vector>

namespace unidist {

/// The dial (QueryOptions): tolerance is the absolute slack for the tests (ties, "touching") and the accuracy
/// of the global queries; negative → 1e-9 × the larger bounding-box diagonal; never below 1e-12 × that
/// diagonal (rounding). relativeTolerance and maxIterations go to the global queries.
struct ContactOptions : QueryOptions {
  /// Report local minima with distance <= margin (>= 0). 0: touching or penetrating only.
  double margin = 0;
  /// At most this many contacts (the deepest first, then spread by position); 0: no limit.
  int maxContacts = 0;
};

struct Contact {
  Eigen::Vector3d pointA = Eigen::Vector3d::Zero();  ///< world, on A's surface
  Eigen::Vector3d pointB = Eigen::Vector3d::Zero();  ///< world, on B's surface
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  ///< unit; pointB − pointA = distance · normal
  double distance = 0;                                ///< signed: < 0 when penetrating
  /// The model's feature holding the point: a triangle of a mesh, a point of a cloud, a primitive's feature.
  int featureA = 0, featureB = 0;
  /// Surface parameters of the points where the model has them (NURBS: (u, v) of surface `feature`), as
  /// SurfacePoint::param; zero elsewhere. manifoldContacts() keeps them as the warm start's hints.
  Eigen::Vector2d paramA = Eigen::Vector2d::Zero(), paramB = Eigen::Vector2d::Zero();
  /// Proved bound on how far `distance` is from the exact value of what it measures (docs/contacts.md): the
  /// distance between the two features (mesh–mesh local minima), the signed distance from the contact's vertex or
  /// cloud point to the other model, or the global signed distance (the contact unidist::distance gave). Covers
  /// rounding, the NURBS searches' tolerance, a level of detail's deviations, and (manifoldContacts) how far a
  /// contact was moved along its normal from where it was measured.
  double errorBound = 0;
};

/// Local minimum distances within options.margin, sorted by distance (deepest first). Throws InputError for
/// bad options (negative or non-finite margin, negative maxContacts), a non-finite pose, or two half-spaces.
std::vector<Contact> contacts(const Model& a, const Eigen::Isometry3d& X_WA, const Model& b,
                              const Eigen::Isometry3d& X_WB, const ContactOptions& options = {});

}  // namespace unidist
