#include "contacts/snch.h"

#include "convex/segments.h"
#include "mesh/point_triangle.h"
#include "mesh/triangle_triangle.h"

#include <algorithm>
#include <cmath>
#include <unordered_set>

namespace unidist::contact {
namespace {

struct PairHash {
  std::size_t operator()(const std::pair<std::uint64_t, std::uint64_t>& p) const {
    return std::hash<std::uint64_t>()(p.first * 0x9E3779B97F4A7C15ull ^ p.second);
  }
};

/// Everything the leaf test needs, in A's frame.
class LeafTester {
 public:
  LeafTester(const TriangleMesh& a, const MeshFeatures& fa, const TriangleMesh& b, const MeshFeatures& fb,
             const Eigen::Isometry3d& X_AB, double margin, double tol, double dirEps, std::vector<Contact>& out)
      : a_(a), fa_(fa), b_(b), fb_(fb), X_AB_(X_AB), X_BA_(X_AB.inverse()), limit_(margin + tol), dirEps_(dirEps),
        out_(out) {}

  void test(std::uint32_t ta, std::uint32_t tb) {
    const auto& triA = a_.triangles()[ta];
    const auto& triB = b_.triangles()[tb];
    Eigen::Vector3d va[3], vb[3];
    for (int k = 0; k < 3; ++k) {
      va[k] = a_.vertices()[triA[k]];
      vb[k] = X_AB_ * b_.vertices()[triB[k]];
    }
    // Triangles whose boxes are farther apart than the limit hold no candidate.
    const Eigen::Vector3d loA = va[0].cwiseMin(va[1]).cwiseMin(va[2]), hiA = va[0].cwiseMax(va[1]).cwiseMax(va[2]);
    const Eigen::Vector3d loB = vb[0].cwiseMin(vb[1]).cwiseMin(vb[2]), hiB = vb[0].cwiseMax(vb[1]).cwiseMax(vb[2]);
    if ((loB - hiA).cwiseMax(loA - hiB).cwiseMax(0.0).squaredNorm() > limit_ * limit_) return;
    const Eigen::Vector3d na = a_.faceNormal(static_cast<int>(ta));
    const Eigen::Vector3d nb = X_AB_.linear() * b_.faceNormal(static_cast<int>(tb));
    // A vertex farther than the limit from the other triangle's plane or box is skipped before the exact test.
    const auto near = [&](const Eigen::Vector3d& v, const Eigen::Vector3d* t, const Eigen::Vector3d& n,
                          const Eigen::Vector3d& lo, const Eigen::Vector3d& hi) {
      return std::abs(n.dot(v - t[0])) <= limit_ &&
             (lo - v).cwiseMax(v - hi).cwiseMax(0.0).squaredNorm() <= limit_ * limit_;
    };
    for (int k = 0; k < 3; ++k) {
      if (near(va[k], vb, nb, loB, hiB)) {
        const mesh::TriangleClosest c = mesh::closestOnTriangle(va[k], vb[0], vb[1], vb[2], nb);
        if (c.squaredDistance <= limit_ * limit_)
          consider(va[k], c.point, {Feature::Vertex, triA[k], 0}, featureOf(b_, static_cast<int>(tb), c.feature));
      }
      if (near(vb[k], va, na, loA, hiA)) {
        const mesh::TriangleClosest d = mesh::closestOnTriangle(vb[k], va[0], va[1], va[2], na);
        if (d.squaredDistance <= limit_ * limit_)
          consider(d.point, vb[k], featureOf(a_, static_cast<int>(ta), d.feature), {Feature::Vertex, triB[k], 0});
      }
    }
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const Eigen::Vector3d &p1 = va[i], &q1 = va[(i + 1) % 3], &p2 = vb[j], &q2 = vb[(j + 1) % 3];
        const Eigen::Vector3d gap =
            (p2.cwiseMin(q2) - p1.cwiseMax(q1)).cwiseMax(p1.cwiseMin(q1) - p2.cwiseMax(q2)).cwiseMax(0.0);
        if (gap.squaredNorm() > limit_ * limit_) continue;
        const Eigen::Vector3d e1 = q1 - p1, e2 = q2 - p2;
        if (e1.cross(e2).norm() <= 1e-9 * e1.norm() * e2.norm()) continue;  // parallel: the end vertices cover it
        const detail::SegmentSegmentClosest s = detail::closestSegmentSegment(p1, q1, p2, q2);
        if (s.distance > limit_ || !(s.s > 0 && s.s < 1 && s.t > 0 && s.t < 1)) continue;
        const Feature fA{Feature::Edge, std::min(triA[i], triA[(i + 1) % 3]), std::max(triA[i], triA[(i + 1) % 3])};
        const Feature fB{Feature::Edge, std::min(triB[j], triB[(j + 1) % 3]), std::max(triB[j], triB[(j + 1) % 3])};
        consider(s.point1, s.point2, fA, fB);
      }
  }

 private:
  /// Normal-set tests of both ends for direction u (A toward B, A's frame).
  bool accepts(const Feature& fA, const Eigen::Vector3d& p, const Feature& fB, const Eigen::Vector3d& qB,
               const Eigen::Vector3d& u, double slack) const {
    const Eigen::Vector3d uB = X_BA_.linear() * u;
    if (!inNormalSet(a_, fa_, fA, p, u, slack) || !inNormalSet(b_, fb_, fB, qB, -uB, slack)) return false;
    // Inside a face-on-face contact: only the corners of the contact polygon are kept.
    const bool flatA = isFlat(a_, fa_, fA, u, slack), flatB = isFlat(b_, fb_, fB, -uB, slack);
    if (fA.kind == Feature::Edge && fB.kind == Feature::Edge) return !flatA && !flatB;
    if (flatA && flatB) return false;
    // A vertex in the middle of a straight side of the contact region is not one of its corners either.
    if (flatB && onStraightCrease(a_, fa_, fA, u, slack)) return false;
    return !(flatA && onStraightCrease(b_, fb_, fB, -uB, slack));
  }

  void consider(const Eigen::Vector3d& p, const Eigen::Vector3d& q, const Feature& fA, const Feature& fB) {
    if (!seen_.insert({fA.key(), fB.key()}).second) return;
    const Eigen::Vector3d qB = X_BA_ * q;
    const double d = (q - p).norm();
    Eigen::Vector3d chosen;
    bool ok = false;
    if (d > dirEps_) {
      chosen = (q - p) / d;
      ok = accepts(fA, p, fB, qB, chosen, 1e-7 + 1e-6 * dirEps_ / d);
    } else {
      // Touching: the direction is the features' — a normal of a triangle holding either feature, the edges'
      // common perpendicular, or the difference of the normal sums; an open surface may be touched from either
      // side, so both signs are tried.
      std::vector<Eigen::Vector3d> tries;
      forIncident(b_, fb_, fB,
                  [&](std::uint32_t t) { tries.push_back(-(X_AB_.linear() * b_.faceNormal(static_cast<int>(t)))); });
      forIncident(a_, fa_, fA, [&](std::uint32_t t) { tries.push_back(a_.faceNormal(static_cast<int>(t))); });
      if (fA.kind == Feature::Edge && fB.kind == Feature::Edge)
        tries.push_back((a_.vertices()[fA.b] - a_.vertices()[fA.a])
                            .cross(X_AB_.linear() * (b_.vertices()[fB.b] - b_.vertices()[fB.a])));
      tries.push_back(normalSum(a_, fa_, fA) - X_AB_.linear() * normalSum(b_, fb_, fB));
      for (std::size_t k = 0; k < tries.size() && !ok; ++k) {
        if (!(tries[k].norm() > 0)) continue;
        const Eigen::Vector3d u = tries[k].normalized();
        for (const Eigen::Vector3d& cand : {u, Eigen::Vector3d(-u)}) {
          if (accepts(fA, p, fB, qB, cand, 1e-6)) {
            chosen = cand;
            ok = true;
            break;
          }
        }
      }
    }
    if (!ok) return;
    Contact c;
    c.pointA = p;
    c.pointB = q;
    c.normal = chosen;
    c.distance = d;
    c.featureA = someTriangle(fa_, fA);
    c.featureB = someTriangle(fb_, fB);
    out_.push_back(c);
  }

  const TriangleMesh &a_;
  const MeshFeatures& fa_;
  const TriangleMesh& b_;
  const MeshFeatures& fb_;
  Eigen::Isometry3d X_AB_, X_BA_;
  double limit_, dirEps_;
  std::vector<Contact>& out_;
  std::unordered_set<std::pair<std::uint64_t, std::uint64_t>, PairHash> seen_;
};

/// Most triangles below a node for its widened cone to be worth building: from the root, cones cost 4× the
/// search on torus 20k – 20k at gap 1e-2 and pruned nothing (docs/contacts.md).
constexpr std::uint32_t kConeSubtree = 16;

/// The cone of the directions of segments from a point of ball (c1, r1) to a point of ball (c2, r2).
DirCone segmentCone(const Eigen::Vector3d& c1, double r1, const Eigen::Vector3d& c2, double r2) {
  const Eigen::Vector3d d = c2 - c1;
  const double len = d.norm();
  if (!(len > r1 + r2)) return {Eigen::Vector3d::UnitZ(), kPi};
  return {d / len, std::asin(std::min(1.0, (r1 + r2) / len))};
}

/// Whether the (possibly two-sided, for an open mesh) cone can hold some direction of s.
bool holds(const DirCone& c, bool twoSided, const DirCone& s, double slack) {
  return intersects(c, s, slack) || (twoSided && intersects(negated(c), s, slack));
}

}  // namespace

SnchResult snchSearch(const TriangleMesh& a, const MeshFeatures& fa, const TriangleMesh& b, const MeshFeatures& fb,
                      const Eigen::Isometry3d& X_AB, double margin, double tol, double dirEps) {
  SnchResult r;
  LeafTester leaf(a, fa, b, fb, X_AB, margin, tol, dirEps, r.contacts);
  const mesh::MeshBvh& ba = a.bvh();
  const mesh::MeshBvh& bb = b.bvh();
  const Eigen::Matrix3d R = X_AB.linear(), absR = R.cwiseAbs();
  const double limit = margin + tol;
  const bool openA = !a.isSolid(), openB = !b.isSolid();

  std::vector<std::array<std::uint32_t, 2>> stack{{0, 0}};
  while (!stack.empty()) {
    const auto [i, j] = stack.back();
    stack.pop_back();
    ++r.nodePairs;
    const mesh::BvhNode &x = ba.tree.nodes[i], &y = bb.tree.nodes[j];
    const BoundingSphere& sa = ba.spheres[i];
    const Eigen::Vector3d cb = X_AB * bb.spheres[j].center;
    const double rb = bb.spheres[j].radius;
    // Lower bounds on the distance between the nodes' triangles: the balls', and the boxes' (B's turned).
    const double ballGap = (cb - sa.center).norm() - sa.radius - rb;
    const Eigen::Vector3d yc = X_AB * y.center();
    const Eigen::Vector3d yh = absR * y.halfExtent();
    double boxSq = 0;
    for (int k = 0; k < 3; ++k) {
      const double g = std::max({x.lo[k] - (yc[k] + yh[k]), (yc[k] - yh[k]) - x.hi[k], 0.0});
      boxSq += g * g;
    }
    const double lower = std::max(ballGap, std::sqrt(boxSq));
    if (lower > limit) continue;
    // Cone tests only where both nodes are small: a cone is built from every triangle below its node, which
    // near the root costs more than the pairs it would prune.
    const bool small =
        ba.ranges[i][1] - ba.ranges[i][0] <= kConeSubtree && bb.ranges[j][1] - bb.ranges[j][0] <= kConeSubtree;
    if (ballGap > dirEps && small) {
      // Apart: a local minimum's direction lies in the cone of segment directions between the balls, in A's
      // normal cone, and opposite to B's. The slack matches the leaf test's at this distance.
      const double slack = 2e-7 + 2e-6 * dirEps / ballGap;
      const DirCone s = segmentCone(sa.center, sa.radius, cb, rb);
      const DirCone ca = fa.cone(i);
      const DirCone cbj = fb.cone(j);
      const DirCone cbn{R * cbj.axis, cbj.halfAngle};
      if (!holds(ca, openA, s, slack) || !holds(negated(cbn), openB, s, slack)) continue;
      if (!openA && !openB && !intersects(ca, negated(cbn), slack)) continue;
    } else if (x.leaf() && y.leaf() && lower <= 0) {
      r.overlapping.push_back({i, j});
    }
    if (x.leaf() && y.leaf()) {
      ++r.leafPairs;
      for (std::uint32_t s = x.first; s < x.first + x.count; ++s)
        for (std::uint32_t t = y.first; t < y.first + y.count; ++t) leaf.test(ba.tree.order[s], bb.tree.order[t]);
      continue;
    }
    // Split the node with the larger ball (a leaf is never split).
    if (y.leaf() || (!x.leaf() && sa.radius >= rb)) {
      stack.push_back({x.first, j});
      stack.push_back({x.first + 1, j});
    } else {
      stack.push_back({i, y.first});
      stack.push_back({i, y.first + 1});
    }
  }
  return r;
}

bool leavesIntersect(const TriangleMesh& a, const TriangleMesh& b, const Eigen::Isometry3d& X_AB, std::uint32_t leafA,
                     std::uint32_t leafB) {
  const mesh::BvhNode& x = a.bvh().tree.nodes[leafA];
  const mesh::BvhNode& y = b.bvh().tree.nodes[leafB];
  for (std::uint32_t s = x.first; s < x.first + x.count; ++s)
    for (std::uint32_t t = y.first; t < y.first + y.count; ++t) {
      const std::uint32_t ta = a.bvh().tree.order[s], tb = b.bvh().tree.order[t];
      Eigen::Vector3d va[3], vb[3];
      for (int k = 0; k < 3; ++k) {
        va[k] = a.vertices()[a.triangles()[ta][k]];
        vb[k] = X_AB * b.vertices()[b.triangles()[tb][k]];
      }
      const auto c = mesh::closestTriangleTriangle(va, a.faceNormal(static_cast<int>(ta)), vb,
                                                   X_AB.linear() * b.faceNormal(static_cast<int>(tb)), 1e-300);
      if (c.intersecting) return true;
    }
  return false;
}

}  // namespace unidist::contact
