// The models of the extremes suite — a ball, a box and a flat square sheet in each of the four representations
// (primitive, triangle mesh, point cloud, NURBS), plus degenerate inputs of the same shapes — each carrying what
// the oracles need without going through the library: its exact support map over the model's own points and
// its exact signed distance (analytic for primitives and NURBS, long-double brute force for meshes and clouds).
#pragma once

#include "core/case_budget.h"
#include "core/extremes_harness.h"
#include "core/mesh_fixtures.h"
#include "core/nurbs_fixtures.h"
#include "core/oracles.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/point_cloud.h"
#include "unidist/primitives.h"

#include <memory>
#include <optional>
#include <random>
#include <string>
#include <vector>

namespace extremes {

enum class Family { Prim, Mesh, Cloud, Nurbs };
enum class Kind { Ball, Box, Sheet, Capsule, Point };

const char* familyName(Family f);
/// "prim-mesh" etc.: the table row of a pair (families in the order prim, mesh, cloud, nurbs).
std::string pairName(Family a, Family b);

struct Body {
  Family family = Family::Prim;
  Kind kind = Kind::Ball;
  std::string label;
  std::shared_ptr<const unidist::Model> model;
  double radius = 0;              ///< ball, capsule radius (sheet: half side)
  Vec half = Vec::Zero();         ///< box half extents; capsule: (0, 0, half length)
  std::vector<Vec> points;        ///< mesh vertices or cloud points (model frame): support and brute force
  meshfix::Soup soup;             ///< mesh only: the triangles as given to the mesh (before its cleaning)
  bool exactBall() const { return kind == Kind::Ball && (family == Family::Prim || family == Family::Nurbs); }
  bool solid() const { return model->isSolid(); }
  /// A point of the model maximising u·x (model frame), exact over the model's own points.
  Vec support(const Vec& u) const;
  /// Signed distance of q (model frame) to the model: negative inside a solid, unsigned for clouds and sheets.
  double signedDistance(const Vec& q) const;
};

// Ideal shapes in each representation.
Body ball(Family f, double r);
Body box(Family f, const Vec& half);
Body sheet(Family f, double halfSide);  ///< square [-s, s]^2 in z = 0 (open; a half-space z <= 0 for Prim)

// Degenerate inputs of the same shapes (exact: the oracles are the ideal shapes').
Body thinBox(double halfSide, double halfThickness);        ///< primitive plate
Body needleCapsule(double radius, double halfLength);       ///< primitive needle
Body needleBox(const Vec& half);  ///< mesh box with 1e-9-wide needle triangles and zero-area/duplicate triangles
Body duplicatePointBall(double r);  ///< cloud on a sphere, every point given three times plus a 50-fold point
Body fullMultiplicityBall(double r);  ///< NURBS sphere with a knot of multiplicity p+1 inside and a repeated control point
Body extremeWeightBall(double r, double span);  ///< NURBS sphere, rational weights spanning 1/span ... span
Body singlePointCloud(const Vec& p);

/// A mesh body's soup, its points (the vertices) and its model, built on exactly these triangles.
void setMesh(Body& b, meshfix::Soup s);
/// A cloud body's points and its model.
void setCloud(Body& b, std::vector<Vec> points);

/// World support point of a posed body.
Vec worldSupport(const Body& b, const Pose& X, const Vec& u_W);

/// Places B (its rotation already in XB) so that B's lowest point along n sits gap·n above A's highest point:
/// the slab between the two support planes then proves the distance is exactly gap (any models, any gap >= 0).
void placeAtGap(const Body& a, const Pose& XA, const Body& b, Pose& XB, const Vec& n, double gap);

/// Exact signed distance of two overlapping (or any) posed bodies where an oracle exists:
///  * a cloud against anything: min over its points of the other's signed distance (clouds: unsigned);
///  * an exact ball against a convex solid or a sheet: the other's signed distance at the centre minus r;
///  * two convex polytopes (boxes, meshes): minus the penetration depth, the least support overlap over the
///    face normals of both and the cross products of their edges (exact for polytopes; overlapping only).
std::optional<double> signedDistanceOracle(const Body& a, const Pose& XA, const Body& b, const Pose& XB);

Pose rotation(const Vec& axis, double angle);
Pose randomRotation(std::mt19937_64& rng);
using oracle::randomUnit;

/// A case with the models and poses filled in (family and names from the bodies).
Case makeCase(const std::string& extreme, const Body& a, const Pose& XA, const Body& b, const Pose& XB, Truth truth);

}  // namespace extremes
