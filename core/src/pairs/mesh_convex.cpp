#include "pairs/mesh_convex.h"

#include "convex/gjk.h"
#include "generic/generic_distance.h"
#include "generic/translation_depth.h"
#include "mesh/bvh.h"
#include "unidist/mesh.h"

#include <algorithm>
#include <queue>
#include <vector>

namespace unidist::detail {

namespace {

// GJK on a triangle and a primitive converges in a few iterations; the cap only guards degenerate input.
constexpr int kTriangleGjkCap = 200;

struct OpenNode {
  double lower;
  std::uint32_t node;
  bool operator>(const OpenNode& o) const { return lower > o.lower; }
};

struct Closest {
  double distance = std::numeric_limits<double>::infinity();
  double lowerOfClosed = std::numeric_limits<double>::infinity();  // min proved lower bound over measured triangles
  Eigen::Vector3d pA = Eigen::Vector3d::Zero(), pB = Eigen::Vector3d::Zero();  // A's frame
  int iterations = 0;
};

/// Best-first search in A's frame; stops early once the surfaces meet (distance <= 0).
Closest closestTriangle(const TriangleMesh& mesh, const PosedModel& bInA, double tolerance, double& lowerOpen) {
  const mesh::MeshBvh& h = mesh.bvh();
  const auto& vertices = mesh.vertices();
  const auto& triangles = mesh.triangles();
  const SupportFn supportB = [&bInA](const Eigen::Vector3d& d) { return bInA.supportWorld(d); };
  auto nodeLower = [&](std::uint32_t n) {
    const BoundingSphere& s = h.spheres[n];
    return bInA.closestWorld(s.center).signedDistance - s.radius;
  };
  Closest best;
  std::priority_queue<OpenNode, std::vector<OpenNode>, std::greater<OpenNode>> open;
  open.push({nodeLower(0), 0});
  while (!open.empty()) {
    const OpenNode top = open.top();
    if (top.lower >= best.distance - 0.5 * tolerance || best.distance <= 0) break;
    open.pop();
    ++best.iterations;
    const mesh::BvhNode& n = h.tree.nodes[top.node];
    if (!n.leaf()) {
      for (std::uint32_t c : {n.first, n.first + 1}) open.push({nodeLower(c), c});
      continue;
    }
    for (std::uint32_t slot = n.first; slot < n.first + n.count; ++slot) {
      const auto& t = triangles[h.tree.order[slot]];
      const Eigen::Vector3d p[3] = {vertices[t[0]], vertices[t[1]], vertices[t[2]]};
      const SupportFn supportT = [&p](const Eigen::Vector3d& d) {
        const double d0 = d.dot(p[0]), d1 = d.dot(p[1]), d2 = d.dot(p[2]);
        return d0 >= d1 ? (d0 >= d2 ? p[0] : p[2]) : (d1 >= d2 ? p[1] : p[2]);
      };
      const ConvexDistance c = convexDistance(supportT, supportB, 0.25 * tolerance, kTriangleGjkCap);
      best.iterations += c.iterations;
      best.lowerOfClosed = std::min(best.lowerOfClosed, std::min(c.lowerBound, c.distance));
      if (c.distance < best.distance) {
        best.distance = c.distance;
        best.pA = c.pointA;
        best.pB = c.pointB;
      }
    }
  }
  lowerOpen = open.empty() ? std::numeric_limits<double>::infinity() : open.top().lower;
  return best;
}

}  // namespace

DistanceResult meshConvex(const PosedModel& a, const PosedModel& b, const QueryContext& ctx, PairFn convexOverlap) {
  const auto& mesh = static_cast<const TriangleMesh&>(a.model);
  const PosedModel bInA{b.model, a.X_WM.inverse() * b.X_WM};
  double lowerOpen = 0;
  const Closest c = closestTriangle(mesh, bInA, ctx.tolerance, lowerOpen);

  // Apart surfaces overlap only by containment: of B in A (any point of B) or of A in B (any vertex of A).
  const bool meet = c.distance <= 0;
  const bool contained = !meet && ((mesh.isSolid() && mesh.inside(bInA.supportWorld(Eigen::Vector3d::UnitX()))) ||
                                   bInA.model.inside(bInA.toLocal(mesh.vertices().front())));
  if (meet || contained) {
    if (ctx.overlapVerdictOnly) return overlapVerdict();
    if (a.model.isConvex()) return convexOverlap(a, b, ctx);
    if (!mesh.isSolid()) return genericPair(a, b, ctx);
    DistanceResult r = translationalDepth(a, b, ctx, seedOverlap(a, b, ctx));
    r.iterations += c.iterations;
    if (meet) capAtContact(r, ctx.tolerance);
    return r;
  }
  return separationFromPoints(a, c.pA, c.pB, Eigen::Vector3d::UnitZ(), std::min(lowerOpen, c.lowerOfClosed),
                              c.iterations, "mesh-convex-bvh-gjk", ctx.tolerance);
}

}  // namespace unidist::detail
