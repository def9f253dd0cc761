// Non-convex solids given as unions of convex pieces, and their image-space queries (Kim, Hoff, Lin & Manocha,
// "Closest point query among the union of convex polytopes using rasterization hardware", 2002; see
// docs/raster.md): the closest point of the union's boundary to a point inside it, rendered on the six faces of
// a cube around the point, and the penetration depth of two unions through their pairwise Minkowski sums.
#pragma once

#include "unidist/distance.h"
#include "unidist/raster/offscreen_context.h"

#include <array>
#include <vector>

namespace unidist::raster {

/// One convex piece: the convex hull of its points, with outward triangles and facet planes.
struct ConvexPolytope {
  std::vector<Eigen::Vector3d> vertices;       ///< the hull's vertices
  std::vector<std::array<int, 3>> triangles;   ///< outward (counter-clockwise seen from outside), into vertices
  std::vector<Eigen::Vector4d> planes;         ///< one per facet: unit n and d with n·x + d <= 0 inside
  std::vector<int> triangleFacet;              ///< per triangle: its facet (index into planes); coplanar
                                               ///< triangles share one facet and one plane
  std::vector<int> sourceIndex;                ///< per vertex: its index in the points given to convexHull
  double tolerance = 0;  ///< how far any hull point may lie outside its facet planes (qhull's outer plane)
};

/// Convex hull (qhull, reentrant) of a point set. Throws InputError naming the problem for fewer than 4 points,
/// a flat or degenerate set, or a non-finite coordinate.
ConvexPolytope convexHull(const std::vector<Eigen::Vector3d>& points);

/// A solid as the union of convex pieces (which may overlap), in its own frame.
using ConvexUnion = std::vector<ConvexPolytope>;

struct BoundaryQueryOptions {
  int resolution = 256;  ///< pixels per side of each of the six cube faces (8..4096): the speed/accuracy dial
  /// Polish the best pixels' answer on the CPU: the foot of O on each facet seen near the best pixels, the
  /// closest point of O on each crease (two facets' line) and corner (three facets) among them; each kept
  /// only when proved to lie on the boundary. Exact when the closest point lies on those facets.
  bool refine = true;
  int candidates = 32;   ///< best pixels checked on the CPU (1..4096)
};

/// The closest point of the union's boundary to O. All distances are Euclidean, from O.
struct BoundaryPoint {
  bool inside = false;      ///< O lies inside some piece (if not: distance 0, point O, nothing rendered)
  double distance = 0;      ///< |point − O|: point lies on a piece's facet and within `pushOut` of the boundary
  double upperBound = 0;    ///< proved: a point this far from O is outside every piece (>= distance)
  double lowerBound = 0;    ///< proved: the largest depth of O in a single piece (a ball there is in the union)
  double pixelDistance = 0; ///< the image answer alone (best proved pixel, before the CPU polish)
  /// Error the resolution guarantees when the closest point lies inside a facet whose uncovered part holds a
  /// disc of radius distance·tan(angularSpacing) around it: distance·(1/cos(angularSpacing) − 1) (second
  /// order). At creases the error is first order: see resolutionErrorBound().
  double resolutionBound = 0;
  double angularSpacing = 0;  ///< the largest angle between any direction and the nearest pixel ray: √2/N
  double pushOut = 0;         ///< the step outside the facet used to prove `point` is on the boundary
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d direction = Eigen::Vector3d::UnitZ();  ///< unit, from O toward point
  int piece = -1;           ///< the piece whose facet holds point
  int facet = -1;           ///< that facet (index into the piece's planes)
  int passes = 0;           ///< rendering passes, summed over the six views (the containing pieces' pass included)
  int piecesRendered = 0, piecesCulled = 0;  ///< summed over the six views
  bool refined = false;     ///< the CPU polish found a closer proved point than the best pixel
};

/// The error bound of an N×N-per-face answer when the outside of the union near the closest point c contains a
/// cone of half-angle `outsideHalfAngle` (radians, in (0, π/2]) around the direction from O to c: the pixel
/// answer d satisfies d* <= d <= d*·sin γ / sin(γ − α), α = √2/N (infinite when α >= γ). γ = π/2 inside a facet
/// gives d*/cos α (second order); a right-angled groove gives γ = π/4 (first order, ≈ d*·α).
double resolutionErrorBound(double trueDistance, int resolution, double outsideHalfAngle);

/// Kim et al.'s query on `context` (made current on the calling thread at resolution × resolution). Throws
/// InputError for an empty union, a malformed piece, a non-finite O or options out of range.
BoundaryPoint closestBoundaryPoint(OffscreenContext& context, const ConvexUnion& pieces, const Eigen::Vector3d& O,
                                   const BoundaryQueryOptions& options = {});

struct UnionDistanceOptions {
  double tolerance = -1;   ///< as DistanceOptions::tolerance (separation distances are exact GJK answers)
  int resolution = 256;    ///< per cube face, for the penetration depth
  bool refine = true;      ///< as BoundaryQueryOptions::refine
  int maxIterations = 1000;  ///< GJK support evaluations per piece pair
};

/// What unionDistanceReport measured besides the answer.
struct UnionDistanceReport {
  DistanceResult result;
  BoundaryPoint boundary;   ///< the query on the Minkowski sums (penetration only)
  int piecePairs = 0;       ///< |A| × |B|
  int overlappingPairs = 0; ///< pairs whose Minkowski sum strictly contains the origin
  int sums = 0;             ///< Minkowski sums built (pairs not culled)
  double sumsSeconds = 0;   ///< time spent building the sums (hulls)
  double querySeconds = 0;  ///< time spent in closestBoundaryPoint
};

/// Signed distance of two unions of convex pieces with the contract's meaning (docs/query-contract.md):
/// separated or touching → the exact minimum over piece pairs (GJK); overlapping → −(minimum translation
/// distance) from the boundary of the union of the pairwise Minkowski sums A_i ⊕ (−B_j) closest to the origin,
/// bounded by the deepest single pair (a proved lower bound of the depth) and the proved boundary point found by
/// rasterization; status certified only when those bounds meet the tolerance. method = "raster" (penetration)
/// or "convex pieces" (separation). Throws InputError for an empty union, a malformed piece, a non-finite pose
/// or options out of range.
DistanceResult unionDistance(OffscreenContext& context, const ConvexUnion& a, const Eigen::Isometry3d& X_WA,
                             const ConvexUnion& b, const Eigen::Isometry3d& X_WB, const UnionDistanceOptions& options = {});

/// unionDistance with what it measured (pairs, sums, times).
UnionDistanceReport unionDistanceReport(OffscreenContext& context, const ConvexUnion& a, const Eigen::Isometry3d& X_WA,
                                        const ConvexUnion& b, const Eigen::Isometry3d& X_WB,
                                        const UnionDistanceOptions& options = {});

}  // namespace unidist::raster
