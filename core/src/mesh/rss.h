// Rectangle swept sphere (RSS) node volumes for mesh–mesh searches (internal): a rectangle and a radius, the
// set of points within `radius` of the rectangle.
//
// Fitting: the rectangle lies in the plane of the two largest principal axes of the points' covariance, its
// sides span the points' extents along those axes, and the radius is half their extent along the third axis,
// so every point lies straight above or below the rectangle within the radius. The rectangle is not shrunk
// at its edges (FCL's fit does that): on a curved cap the edge points sit at the extreme height, where the
// rounded edge leaves no room, so it was not tried. Padded a few ulps of the coordinates so rounding
// cannot leave a point outside; a triangle is the hull of its vertices and the volume is convex, so holding
// the vertices holds the triangles.
//
// Lower bound between two volumes: any unit direction u separates by |u·(cb − ca)| − (support of A along u) −
// (support of B along u), and the distance of the volumes is at least that gap less both radii. Tried
// directions: both normals and the direction between a closest-pair estimate of the two rectangles (two
// steps of alternating projection, started at B's centre), which is the exact direction once the estimate is
// the closest pair. So the bound is always valid and exact for facing or converged rectangles, at a fraction
// of an exact rectangle–rectangle distance's cost.
#pragma once

#include <Eigen/Core>

#include <cstddef>
#include <limits>

namespace unidist::mesh {

struct Rss {
  Eigen::Vector3d center = Eigen::Vector3d::Zero();    ///< the rectangle's centre
  Eigen::Matrix3d axes = Eigen::Matrix3d::Identity();  ///< columns: side directions e0, e1, normal e2 (orthonormal)
  double half[2] = {0, 0};                             ///< half side lengths along e0, e1
  double radius = 0;
};

/// Orthonormal right-handed axes of a covariance matrix, largest variance first (identity when degenerate).
Eigen::Matrix3d principalAxes(const Eigen::Matrix3d& covariance);

/// The same approximately, by Jacobi rotations started from the orthonormal axes `guess` (columns): a few
/// rotations when the guess is near (a child's axes for its parent), at a fraction of a direct solve's cost.
/// The result is orthonormal to a few ε whatever the guess; only how principal it is depends on the guess.
Eigen::Matrix3d principalAxesFrom(const Eigen::Matrix3d& covariance, const Eigen::Matrix3d& guess);

/// Fits an RSS holding every point given (count > 0), on the points' principal axes.
Rss fitRss(const Eigen::Vector3d* points, std::size_t count);

/// The same on given orthonormal axes (columns: sides, normal).
Rss fitRss(const Eigen::Matrix3d& axes, const Eigen::Vector3d* points, std::size_t count);

/// An RSS on the given axes holding the boxes [±half0, ±half1, ±radius] of both (which hold their points):
/// looser than a fit to their points, but O(1).
Rss mergeRss(const Eigen::Matrix3d& axes, const Rss& a, const Rss& b);

/// A lower bound on the distance between volume a and volume b posed in a's frame by (R, t) (0 or negative
/// when they may touch). Returns as soon as the bound reaches `enough` (a caller's pruning threshold). Up to
/// rounding of the coordinates, which callers absorb in their slack.
double rssLowerBound(const Rss& a, const Rss& b, const Eigen::Matrix3d& R, const Eigen::Vector3d& t,
                     double enough = std::numeric_limits<double>::infinity());

/// The same for b given in a's frame already (a search that meets one volume many times poses it once).
double rssLowerBound(const Rss& a, const Rss& b, double enough = std::numeric_limits<double>::infinity());

/// b moved by the rotation R and translation t.
Rss posedRss(const Rss& b, const Eigen::Matrix3d& R, const Eigen::Vector3d& t);

}  // namespace unidist::mesh
