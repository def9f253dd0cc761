#include "contacts/point_contacts.h"

#include "cloud/point_tree.h"
#include "mesh/bvh.h"

#include <algorithm>
#include <cmath>
#include <unordered_map>
#include <utility>
#include <vector>

namespace unidist::contact {
namespace {

/// Point queries of the other model from points of the mesh / cloud frame M, memoised by index.
class Field {
 public:
  Field(const Eigen::Isometry3d& X_WM, const Model& o, const Eigen::Isometry3d& X_WO)
      : X_OM_(X_WO.inverse() * X_WM), o_(o) {}
  SurfacePoint at(const Eigen::Vector3d& p_M) const { return o_.closestPoint(X_OM_ * p_M); }
  const SurfacePoint& vertex(std::uint32_t v, const Eigen::Vector3d& p_M) {
    auto it = memo_.find(v);
    if (it == memo_.end()) it = memo_.emplace(v, at(p_M)).first;
    return it->second;
  }

 private:
  Eigen::Isometry3d X_OM_;
  const Model& o_;
  std::unordered_map<std::uint32_t, SurfacePoint> memo_;
};

/// The contact between point p_M of the mesh / cloud and its closest point on the other model.
Contact makeContact(const Eigen::Vector3d& p_M, const SurfacePoint& sp, const Eigen::Isometry3d& X_WM,
                    const Eigen::Isometry3d& X_WO, bool isA, int feature) {
  // p = q + s·n_O both outside and inside (inside, the query's normal points from p to the surface).
  const Eigen::Vector3d p = X_WM * p_M, q = X_WO * sp.point, n = X_WO.linear() * sp.normal;
  Contact c;
  c.distance = sp.signedDistance;
  c.errorBound = sp.error;
  if (isA) {
    c.pointA = p, c.pointB = q, c.normal = -n;
    c.featureA = feature, c.featureB = sp.feature;
  } else {
    c.pointA = q, c.pointB = p, c.normal = n;
    c.featureA = sp.feature, c.featureB = feature;
  }
  return c;
}

/// Depth-first descent of a hierarchy, skipping nodes whose ball is beyond `limit` from the other model.
template <class LeafFn>
void descend(const mesh::Bvh& tree, const mesh::BigVector<BoundingSphere>& spheres, const Field& field, double limit,
             LeafFn&& leaf) {
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const std::uint32_t i = stack.back();
    stack.pop_back();
    if (field.at(spheres[i].center).signedDistance - spheres[i].radius > limit) continue;
    const mesh::BvhNode& n = tree.nodes[i];
    if (n.leaf()) {
      leaf(n);
    } else {
      stack.push_back(n.first + 1);
      stack.push_back(n.first);
    }
  }
}

}  // namespace

void meshVertexContacts(const TriangleMesh& m, const MeshFeatures& mf, const Eigen::Isometry3d& X_WM, const Model& o,
                        const Eigen::Isometry3d& X_WO, double margin, double tol, bool isA, bool onlyInside,
                        std::vector<Contact>& out) {
  if (onlyInside && !o.isSolid()) return;
  Field field(X_WM, o, X_WO);
  const double limit = onlyInside ? 0.0 : margin + tol;
  const mesh::MeshBvh& bvh = m.bvh();
  std::unordered_map<std::uint32_t, bool> done;
  descend(bvh.tree, bvh.spheres, field, limit, [&](const mesh::BvhNode& n) {
    for (std::uint32_t s = n.first; s < n.first + n.count; ++s)
      for (std::uint32_t v : m.triangles()[bvh.tree.order[s]]) {
        if (!done.emplace(v, true).second) continue;
        const SurfacePoint sp = field.vertex(v, m.vertices()[v]);
        const double d = sp.signedDistance;
        if (onlyInside ? !(d < 0) : d > limit) continue;
        bool minimum = true, level = false;
        for (const std::uint32_t w : mf.neighbours(v)) {
          if (!minimum) break;
          const double dw = field.vertex(w, m.vertices()[w]).signedDistance;
          minimum = d <= dw + tol;
          level = level || std::abs(d - dw) <= tol;
        }
        if (!minimum) continue;
        // The mesh's outward direction toward the other model is −n_O (in the mesh's frame).
        const Eigen::Vector3d toward = -(X_WM.linear().transpose() * (X_WO.linear() * sp.normal));
        const Feature f{Feature::Vertex, v, 0};
        // Inside a plateau, or on a straight side of it: the plateau's corners speak for it.
        if (level && (isFlat(m, mf, f, toward, 1e-6) || onStraightCrease(m, mf, f, toward, 1e-6))) continue;
        out.push_back(makeContact(m.vertices()[v], sp, X_WM, X_WO, isA, someTriangle(mf, f)));
      }
  });
}

void cloudPointContacts(const PointCloud& c, const Eigen::Isometry3d& X_WC, const Model& o,
                        const Eigen::Isometry3d& X_WO, double margin, double tol, bool isA, std::vector<Contact>& out) {
  Field field(X_WC, o, X_WO);
  const cloud::PointTree& tree = c.tree();
  std::vector<std::pair<std::uint32_t, SurfacePoint>> near;  // one leaf's points within the margin
  descend(tree.tree, tree.spheres, field, margin + tol, [&](const mesh::BvhNode& n) {
    // The leaf's nearest point, and every other point as near within tol (ties, as for mesh vertices): keeping
    // one of equals let rounding pick which, so a ball cradled by four equally near points got two of them, on a
    // diagonal, a different two from step to step, and rocked about it.
    near.clear();
    double nearest = margin + tol;
    for (std::uint32_t s = n.first; s < n.first + n.count; ++s) {
      const std::uint32_t i = tree.tree.order[s];
      const SurfacePoint sp = field.at(c.points()[i]);
      if (sp.signedDistance > margin + tol) continue;
      nearest = std::min(nearest, sp.signedDistance);
      near.emplace_back(i, sp);
    }
    for (const auto& [i, sp] : near)
      if (sp.signedDistance <= nearest + tol)
        out.push_back(makeContact(c.points()[i], sp, X_WC, X_WO, isA, static_cast<int>(i)));
  });
}

}  // namespace unidist::contact
