// Box–box contact manifold: separating axes, then face clipping or the edge–edge closest pair (see the header).
// Everything is computed from B's pose in A's frame (the same numbers the separating-axis test used), so the
// checks below compare like with like; only the final contacts are moved to the world.
#include "contacts/box_box_contacts.h"

#include "contacts/reduce.h"
#include "contacts/rounding.h"
#include "convex/segments.h"
#include "pairs/box_box.h"

#include <array>
#include <cmath>
#include <limits>
#include <utility>

namespace unidist::contact {
namespace {

using detail::BoxAxes;
using detail::BoxAxis;
using Eigen::Isometry3d;
using Eigen::Matrix3d;
using Eigen::Vector3d;

/// A convex polygon: a quadrilateral clipped by four planes gains at most one corner per plane (room is left for
/// rounding).
struct Polygon {
  static constexpr int kCapacity = 16;
  std::array<Vector3d, kCapacity> corner;
  int count = 0;
  void add(const Vector3d& p) {
    if (count < kCapacity) corner[std::size_t(count++)] = p;
  }
};

/// Facing sides within this angle (rad) of the contact normal are resting on each other (see contactsInA).
constexpr double kRestingAngle = 0.05;

double signOf(double x) { return x >= 0 ? 1.0 : -1.0; }

/// The part of the polygon where side · x[axis] <= limit (one Sutherland–Hodgman step). Corners within `onPlane` of
/// the plane count as on it and are kept once: a crossing is added only where the two ends lie clearly on opposite
/// sides (an incident edge lying along the plane would otherwise gain a crossing anywhere along it by rounding).
Polygon clip(const Polygon& in, int axis, double side, double limit, double onPlane) {
  Polygon out;
  for (int k = 0; k < in.count; ++k) {
    const Vector3d& p = in.corner[std::size_t(k)];
    const Vector3d& q = in.corner[std::size_t((k + 1) % in.count)];
    const double dp = side * p[axis] - limit, dq = side * q[axis] - limit;
    if (dp <= onPlane) out.add(p);
    if ((dp < -onPlane && dq > onPlane) || (dp > onPlane && dq < -onPlane)) out.add(p + (dp / (dp - dq)) * (q - p));
  }
  return out;
}

/// The two axes other than `axis`, in increasing order.
int firstOther(int axis) { return axis == 0 ? 1 : 0; }
int secondOther(int axis) { return axis == 2 ? 1 : 2; }

/// A face contact set up in the reference box's frame R: the reference face is x[axis] = side · halfR[axis] (outward
/// normal side · e_axis, toward the incident box I, whose pose in R is X_RI).
struct Reference {
  Vector3d halfR, halfI;
  int axis = 0;
  double side = 1;
  Isometry3d X_RI = Isometry3d::Identity();
  Isometry3d X_AR = Isometry3d::Identity();  ///< R in A's frame (identity when the reference box is A)
  bool isA = true;
};

/// The face of I whose outward normal is most opposite to the reference normal (it holds I's deepest points
/// toward R), as a polygon in R's frame.
Polygon incidentFace(const Reference& ref) {
  const Matrix3d& R = ref.X_RI.linear();
  int m = 0;
  R.row(ref.axis).cwiseAbs().maxCoeff(&m);
  Vector3d local;
  local[m] = -signOf(ref.side * R(ref.axis, m)) * ref.halfI[m];  // outward normal · reference normal < 0
  const int u = firstOther(m), v = secondOther(m);
  constexpr double kCycle[4][2] = {{1, 1}, {-1, 1}, {-1, -1}, {1, -1}};  // the corners in order around the face
  Polygon face;
  for (const auto& signs : kCycle) {
    local[u] = signs[0] * ref.halfI[u];
    local[v] = signs[1] * ref.halfI[v];
    face.add(ref.X_RI * local);
  }
  return face;
}

/// The incident face clipped to the reference face's four side planes, in R's frame.
Polygon clippedIncidentFace(const Reference& ref, double slack) {
  Polygon p = incidentFace(ref);
  for (const int k : {firstOther(ref.axis), secondOther(ref.axis)})
    for (const double side : {1.0, -1.0}) p = clip(p, k, side, ref.halfR[k], slack);
  return p;
}

/// A contact from a point q of I and its foot on the reference face (R's frame), in A's frame.
Contact faceContact(const Reference& ref, const Vector3d& q) {
  Vector3d foot = q;
  foot[ref.axis] = ref.side * ref.halfR[ref.axis];
  const Vector3d n = ref.side * Vector3d::Unit(ref.axis);  // reference → incident
  Contact c;
  c.distance = ref.side * q[ref.axis] - ref.halfR[ref.axis];
  c.pointA = ref.X_AR * (ref.isA ? foot : q);
  c.pointB = ref.X_AR * (ref.isA ? q : foot);
  c.normal = ref.X_AR.linear() * (ref.isA ? n : Vector3d(-n));
  return c;
}

/// The face contact set of a face axis; returns the smallest distance of the clipped polygon (every clipped corner,
/// in the margin or not), which the caller compares with the axis overlap.
double faceContacts(const Reference& ref, double margin, double slack, std::vector<Contact>& out) {
  const Polygon p = clippedIncidentFace(ref, slack);
  double nearest = std::numeric_limits<double>::infinity();
  for (int k = 0; k < p.count; ++k) {
    const Contact c = faceContact(ref, p.corner[std::size_t(k)]);
    nearest = std::min(nearest, c.distance);
    if (c.distance <= margin) out.push_back(c);
  }
  return nearest;
}

Reference referenceFor(const BoxAxis& axis, const Vector3d& hA, const Vector3d& hB, const Isometry3d& X_AB) {
  Reference ref;
  ref.isA = axis.kind == BoxAxis::Kind::FaceOfA;
  if (ref.isA) {
    ref.halfR = hA, ref.halfI = hB, ref.axis = axis.i;
    ref.side = signOf(axis.direction[axis.i]);
    ref.X_RI = X_AB;
  } else {
    // B's outward normal toward A is −direction.
    ref.halfR = hB, ref.halfI = hA, ref.axis = axis.j;
    ref.side = -signOf(axis.direction.dot(X_AB.linear().col(axis.j)));
    ref.X_RI = X_AB.inverse();
    ref.X_AR = X_AB;
  }
  return ref;
}

/// The edge of a box (half extents h, its own frame) along `along` that supports the box in direction d.
std::pair<Vector3d, Vector3d> supportingEdge(const Vector3d& h, int along, const Vector3d& d) {
  Vector3d mid;
  for (int k = 0; k < 3; ++k) mid[k] = signOf(d[k]) * h[k];
  mid[along] = 0;
  const Vector3d half = h[along] * Vector3d::Unit(along);
  return {mid - half, mid + half};
}

/// The closest-point pair of A's and B's edges along an edge–edge axis (A's frame); false when the pair does not
/// realise the axis overlap (the nearest features are not these two edges' interiors).
bool edgeContact(const BoxAxis& axis, const Vector3d& hA, const Vector3d& hB, const Isometry3d& X_AB, double slack,
                 Contact& c) {
  const auto [a0, a1] = supportingEdge(hA, axis.i, axis.direction);
  const auto [b0, b1] = supportingEdge(hB, axis.j, -(X_AB.linear().transpose() * axis.direction));
  const detail::SegmentSegmentClosest s = detail::closestSegmentSegment(a0, a1, X_AB * b0, X_AB * b1);
  c.distance = -axis.overlap;
  c.pointA = s.point1;
  c.pointB = s.point2;
  c.normal = axis.direction;
  return (s.point2 - s.point1 - c.distance * axis.direction).norm() <= slack;
}

/// The exact closest pair (or minimum translation) of the two boxes, A's frame.
Contact exactContact(const Vector3d& hA, const Vector3d& hB, const Isometry3d& X_AB, double tolerance) {
  const detail::ConvexDistance d = detail::boxBox(hA, Isometry3d::Identity(), hB, X_AB, tolerance);
  Contact c;
  c.pointA = d.pointA, c.pointB = d.pointB, c.normal = d.normal, c.distance = d.distance;
  c.errorBound = d.upperBound - d.lowerBound;
  return c;
}

void toWorld(const Isometry3d& X_WA, std::vector<Contact>& cs) {
  for (Contact& c : cs) {
    c.pointA = X_WA * c.pointA;
    c.pointB = X_WA * c.pointB;
    c.normal = X_WA.linear() * c.normal;
  }
}

/// Whether an edge–edge axis decides (clearly shallower than every face axis): near-parallel edges give
/// rounding-blurred axes whose overlap ties a face's.
bool edgesDecide(const BoxAxes& axes, double slack) {
  return axes.smallest.kind == BoxAxis::Kind::EdgePair && axes.smallest.overlap < axes.smallestFace.overlap - slack;
}

/// The contact realising the distance (A's frame) where the face axis does not: the edge pair's closest points,
/// or the exact query's pair (apart with a vertex or parallel edges nearest).
Contact nearestPair(const BoxAxes& axes, const Vector3d& hA, const Vector3d& hB, const Isometry3d& X_AB,
                    double tolerance, double slack) {
  Contact c;
  if (edgesDecide(axes, slack) && edgeContact(axes.smallest, hA, hB, X_AB, slack, c)) return c;
  return exactContact(hA, hB, X_AB, tolerance);
}

/// The contacts in A's frame: the clipped face polygon when the face axis realises the distance; otherwise the
/// nearest pair, plus the polygon's corners no deeper than it when the two boxes' facing sides are nearly
/// parallel (a box resting on another across an edge: the edges' crossing is deepest by a hair, and the solver
/// needs the whole patch, not a point).
std::vector<Contact> contactsInA(const BoxAxes& axes, const Vector3d& hA, const Vector3d& hB, const Isometry3d& X_AB,
                                 double margin, double tolerance, double slack) {
  std::vector<Contact> face;
  const Reference ref = referenceFor(axes.smallestFace, hA, hB, X_AB);
  const double nearest = faceContacts(ref, margin, slack, face);
  // The face axis's overlap bounds every clipped corner's depth; a corner reaching it is a pair at that distance.
  if (!edgesDecide(axes, slack) && nearest <= -axes.smallestFace.overlap + slack) return face;

  const Contact pair = nearestPair(axes, hA, hB, X_AB, tolerance, slack);
  std::vector<Contact> out;
  if (pair.distance <= margin) out.push_back(pair);
  const Vector3d faceNormal = ref.X_AR.linear() * Vector3d::Unit(ref.axis);
  if (std::abs(pair.normal.dot(faceNormal)) >= std::cos(kRestingAngle))
    for (const Contact& c : face)
      if (c.distance >= pair.distance - slack) out.push_back(c);
  return out;
}

}  // namespace

std::vector<Contact> boxBoxContacts(const Box& a, const Isometry3d& X_WA, const Box& b, const Isometry3d& X_WB,
                                    double margin, double tolerance, int maxContacts) {
  const Vector3d& hA = a.halfExtents();
  const Vector3d& hB = b.halfExtents();
  const Isometry3d X_AB = X_WA.inverse() * X_WB;
  const BoxAxes axes = detail::boxSeparatingAxes(hA, hB, X_AB.linear(), X_AB.translation());
  if (-axes.smallest.overlap > margin) return {};  // an axis gap is a lower bound on the distance

  // Rounding of the quantities compared (coordinates of the two boxes in A's frame), far below any tolerance.
  const double slack = 1e-12 * (hA.norm() + hB.norm() + X_AB.translation().norm());
  std::vector<Contact> out = contactsInA(axes, hA, hB, X_AB, margin, tolerance, slack);
  toWorld(X_WA, out);
  const Isometry3d X_AW = X_WA.inverse(), X_BW = X_WB.inverse();
  for (Contact& c : out) {
    c.featureA = a.closestPoint(X_AW * c.pointA).feature;
    c.featureB = b.closestPoint(X_BW * c.pointB).feature;
    c.errorBound += roundingBound(c);
  }
  mergeDuplicates(out, 16 * slack);
  if (maxContacts > 0) reduceContacts(out, maxContacts);
  return out;
}

}  // namespace unidist::contact
