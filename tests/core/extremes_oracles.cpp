// Independent truth for the extremes suite, written without the library's queries: support maps and signed
// distances of the bodies (analytic, or long-double brute force over a mesh's triangles and a cloud's points), the
// support-plane placement, and the signed distance of overlapping pairs (ball in convex solid, polytope SAT, clouds).
#include "core/extremes_models.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <map>

namespace extremes {
namespace {

/// The body's exact shape as the distance tests' oracle writes it (tests/core/oracles.h): a flat square sheet is a
/// box of zero thickness (its unsigned distance is the box's).
oracle::Shape exactShape(const Body& b) {
  switch (b.kind) {
    case Kind::Ball: return {"sphere", b.radius};
    case Kind::Box: return {"box", b.half.x(), b.half.y(), b.half.z()};
    case Kind::Sheet: return {"box", b.radius, b.radius, 0};
    case Kind::Capsule: return {"capsule", b.radius, b.half.z()};
    case Kind::Point: break;  // only a cloud: its points are its shape
  }
  return {};
}

/// The convex polytope data SAT needs, in the world frame.
struct Polytope {
  std::vector<Vec> vertices, faceNormals, edges;
};

Polytope worldPolytope(const Body& b, const Pose& X) {
  Polytope p;
  if (b.kind == Kind::Box && b.family != Family::Mesh && b.family != Family::Cloud) {
    for (int i = 0; i < 8; ++i)
      p.vertices.push_back(X * Vec((i & 1 ? 1 : -1) * b.half.x(), (i & 2 ? 1 : -1) * b.half.y(), (i & 4 ? 1 : -1) * b.half.z()));
    for (int k = 0; k < 3; ++k) p.faceNormals.push_back(X.linear().col(k)), p.edges.push_back(X.linear().col(k));
    return p;
  }
  for (const Vec& v : b.points) p.vertices.push_back(X * v);
  // Directions de-duplicated up to sign and rounding (a grid box has hundreds of edges along a few directions).
  std::map<std::array<long, 3>, Vec> normals, edges;
  auto key = [](const Vec& d) {
    Vec u = d.normalized();
    if (u.x() < 0 || (u.x() == 0 && u.y() < 0)) u = -u;
    return std::array<long, 3>{std::lround(u.x() * 1e12), std::lround(u.y() * 1e12), std::lround(u.z() * 1e12)};
  };
  for (const meshfix::Tri& t : b.soup.triangles) {
    const Vec a = b.soup.vertices[t[0]], c = b.soup.vertices[t[1]], d = b.soup.vertices[t[2]];
    const Vec n = (c - a).cross(d - a);
    if (n.norm() == 0) continue;
    normals.emplace(key(n), X.linear() * n.normalized());
    for (const Vec& e : {Vec(c - a), Vec(d - c), Vec(a - d)})
      if (e.norm() > 0) edges.emplace(key(e), X.linear() * e.normalized());
  }
  for (const auto& [k, n] : normals) p.faceNormals.push_back(n);
  for (const auto& [k, e] : edges) p.edges.push_back(e);
  return p;
}

bool isPolytope(const Body& b) {
  return b.family != Family::Cloud && ((b.kind == Kind::Box) || (b.kind == Kind::Ball && b.family == Family::Mesh));
}

/// The ball oracle needs a convex solid or a model without an inside (every kind here is one of the two; the
/// mesh check keeps a non-convex tessellation from slipping through).
bool isConvexOrOpen(const Body& b) { return !b.solid() || b.family != Family::Mesh || b.model->isConvex(); }

/// Minus the penetration depth of two overlapping convex polytopes (SAT over all candidate axes, both signs).
double polytopeSignedDistance(const Polytope& A, const Polytope& B) {
  std::vector<Vec> axes = A.faceNormals;
  axes.insert(axes.end(), B.faceNormals.begin(), B.faceNormals.end());
  for (const Vec& ea : A.edges)
    for (const Vec& eb : B.edges) {
      const Vec c = ea.cross(eb);
      if (c.norm() > 1e-9) axes.push_back(c.normalized());
    }
  double depth = std::numeric_limits<double>::infinity();
  for (const Vec& axis : axes)
    for (double s : {1.0, -1.0}) {
      const Vec u = s * axis;
      double maxA = -std::numeric_limits<double>::infinity(), minB = std::numeric_limits<double>::infinity();
      for (const Vec& a : A.vertices) maxA = std::max(maxA, u.dot(a));
      for (const Vec& b : B.vertices) minB = std::min(minB, u.dot(b));
      depth = std::min(depth, maxA - minB);
    }
  return -depth;
}

}  // namespace

Vec Body::support(const Vec& u) const {
  if (family == Family::Mesh || family == Family::Cloud) {
    Vec best = points.front();
    for (const Vec& p : points)
      if (u.dot(p) > u.dot(best)) best = p;
    return best;
  }
  if (kind == Kind::Sheet && family == Family::Prim) return Vec::Zero();  // the half-space z <= 0
  return exactShape(*this).support(u);
}

double Body::signedDistance(const Vec& q) const {
  if (family == Family::Cloud) {
    double best = std::numeric_limits<double>::infinity();
    for (const Vec& p : points) best = std::min(best, (q - p).norm());
    return best;
  }
  if (family == Family::Mesh) {
    const double d = meshfix::bruteDistance(soup, q);
    return solid() && meshfix::bruteWinding(soup, q) > 0.5 ? -d : d;
  }
  if (kind == Kind::Sheet && family == Family::Prim) return q.z();  // the half-space z <= 0
  return exactShape(*this).signedDistance(q);
}

Vec worldSupport(const Body& b, const Pose& X, const Vec& u_W) { return X * b.support(X.linear().transpose() * u_W); }

void placeAtGap(const Body& a, const Pose& XA, const Body& b, Pose& XB, const Vec& n, double gap) {
  XB.translation().setZero();
  const Vec top = worldSupport(a, XA, n), bottom = worldSupport(b, XB, -n);
  XB.translation() = top + gap * n - bottom;
}

std::optional<double> signedDistanceOracle(const Body& a, const Pose& XA, const Body& b, const Pose& XB) {
  if (a.family == Family::Cloud || b.family == Family::Cloud) {
    const bool aIsCloud = a.family == Family::Cloud;
    const Body& cloud = aIsCloud ? a : b;
    const Body& other = aIsCloud ? b : a;
    const Pose toOther = (aIsCloud ? XB : XA).inverse() * (aIsCloud ? XA : XB);
    double best = std::numeric_limits<double>::infinity();
    for (const Vec& p : cloud.points) best = std::min(best, other.signedDistance(toOther * p));
    return best;
  }
  if (a.exactBall() && isConvexOrOpen(b)) return b.signedDistance(XB.inverse() * XA.translation()) - a.radius;
  if (b.exactBall() && isConvexOrOpen(a)) return a.signedDistance(XA.inverse() * XB.translation()) - b.radius;
  if (isPolytope(a) && isPolytope(b)) {
    const double d = polytopeSignedDistance(worldPolytope(a, XA), worldPolytope(b, XB));
    if (d <= 0) return d;  // SAT gives the depth of an overlap only
  }
  return std::nullopt;
}

}  // namespace extremes
