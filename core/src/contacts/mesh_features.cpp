#include "contacts/mesh_features.h"

#include <algorithm>
#include <cmath>

namespace unidist::contact {

const std::vector<std::uint32_t>& MeshFeatures::trianglesAt(std::uint32_t v) const {
  auto it = trianglesAt_.find(v);
  if (it != trianglesAt_.end()) return it->second;
  std::vector<std::uint32_t> found;
  const Eigen::Vector3d& p = m_.vertices()[v];
  std::vector<std::uint32_t> stack{0};
  while (!stack.empty()) {
    const mesh::BvhNode& n = bvh_.tree.nodes[stack.back()];
    stack.pop_back();
    if (!n.contains(p)) continue;  // boxes are exact, so a triangle at v lies in boxes holding v
    if (!n.leaf()) {
      stack.push_back(n.first + 1);
      stack.push_back(n.first);
      continue;
    }
    for (std::uint32_t s = n.first; s < n.first + n.count; ++s) {
      const std::uint32_t t = bvh_.tree.order[s];
      const auto& tri = m_.triangles()[t];
      if (tri[0] == v || tri[1] == v || tri[2] == v) found.push_back(t);
    }
  }
  std::sort(found.begin(), found.end());  // the traversal order must not matter to the callers
  return trianglesAt_.emplace(v, std::move(found)).first->second;
}

std::vector<std::uint32_t> MeshFeatures::neighbours(std::uint32_t v) const {
  std::vector<std::uint32_t> out;
  for (const std::uint32_t t : trianglesAt(v))
    for (const std::uint32_t w : m_.triangles()[t])
      if (w != v) out.push_back(w);
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

const DirCone& MeshFeatures::cone(std::uint32_t i) const {
  auto it = cones_.find(i);
  if (it != cones_.end()) return it->second;
  const mesh::BvhNode& n = bvh_.tree.nodes[i];
  DirCone c;
  if (!n.leaf()) {
    const DirCone left = cone(n.first);  // copies: the recursive calls may rehash the map
    c = merge(left, cone(n.first + 1));
  } else {
    bool first = true;
    for (std::uint32_t s = n.first; s < n.first + n.count; ++s)
      for (const std::uint32_t v : m_.triangles()[bvh_.tree.order[s]])
        for (const std::uint32_t t : trianglesAt(v)) {
          const Eigen::Vector3d& normal = m_.faceNormal(static_cast<int>(t));
          if (first) {
            c = {normal, 0.0};
            first = false;
          } else {
            grow(c, normal);
          }
        }
  }
  return cones_.emplace(i, c).first->second;
}

Feature featureOf(const TriangleMesh& m, int t, TriangleFeature f) {
  const auto& tri = m.triangles()[static_cast<std::size_t>(t)];
  auto edge = [&](int i, int j) {
    return Feature{Feature::Edge, std::min(tri[i], tri[j]), std::max(tri[i], tri[j])};
  };
  switch (f) {
    case TriangleFeature::Face: return {Feature::Face, static_cast<std::uint32_t>(t), 0};
    case TriangleFeature::Edge01: return edge(0, 1);
    case TriangleFeature::Edge12: return edge(1, 2);
    case TriangleFeature::Edge20: return edge(2, 0);
    case TriangleFeature::Vertex0: return {Feature::Vertex, tri[0], 0};
    case TriangleFeature::Vertex1: return {Feature::Vertex, tri[1], 0};
    case TriangleFeature::Vertex2: return {Feature::Vertex, tri[2], 0};
  }
  return {Feature::Face, static_cast<std::uint32_t>(t), 0};
}

bool inNormalSet(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f, const Eigen::Vector3d& p,
                 const Eigen::Vector3d& u, double slack) {
  // A vertex is tested from its own exact position (p may be it after a round trip through another frame);
  // the absolute term covers the rounding of p's coordinates.
  const Eigen::Vector3d at = f.kind == Feature::Vertex ? m.vertices()[f.a] : p;
  const double rounding = 8e-16 * at.cwiseAbs().maxCoeff();
  bool ok = true;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  forIncident(m, mf, f, [&](std::uint32_t t) {
    sum += m.faceNormal(static_cast<int>(t));
    for (std::uint32_t v : m.triangles()[t]) {
      const Eigen::Vector3d d = m.vertices()[v] - at;
      if (d.dot(u) > slack * d.norm() + rounding) ok = false;
    }
  });
  // A solid's normal set at a reflex edge points inward (and a flat feature's is both sides): keep the outer.
  return ok && (!m.isSolid() || sum.dot(u) > 0);
}

namespace {

/// Whether the feature lies on the boundary of an open surface (then it bounds any flat region it is in).
bool onBoundary(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f) {
  if (m.isSolid() || f.kind == Feature::Face) return false;
  int count = 0;
  forIncident(m, mf, f, [&](std::uint32_t) { ++count; });
  if (f.kind == Feature::Edge) return count < 2;
  return static_cast<std::size_t>(count) != mf.neighbours(f.a).size();  // an open fan
}

bool faces(const TriangleMesh& m, std::uint32_t t, const Eigen::Vector3d& u, double minCos) {
  const double c = m.faceNormal(static_cast<int>(t)).dot(u);
  return (m.isSolid() ? c : std::abs(c)) >= minCos;
}

}  // namespace

bool isFlat(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f, const Eigen::Vector3d& u, double slack) {
  bool flat = true;
  const double minCos = std::cos(std::max(slack, 1e-6));
  forIncident(m, mf, f, [&](std::uint32_t t) { flat = flat && faces(m, t, u, minCos); });
  return flat && !onBoundary(m, mf, f);
}

bool onStraightCrease(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f, const Eigen::Vector3d& u,
                      double slack) {
  if (f.kind != Feature::Vertex || onBoundary(m, mf, f)) return false;
  const double minCos = std::cos(std::max(slack, 1e-6));
  bool facing = false, straight = true, haveOther = false;
  Eigen::Vector3d other = Eigen::Vector3d::Zero();
  forIncident(m, mf, f, [&](std::uint32_t t) {
    if (faces(m, t, u, minCos)) {
      facing = true;
    } else if (!haveOther) {
      other = m.faceNormal(static_cast<int>(t));
      haveOther = true;
    } else {
      straight = straight && m.faceNormal(static_cast<int>(t)).dot(other) >= minCos;
    }
  });
  return facing && haveOther && straight;
}

Eigen::Vector3d normalSum(const TriangleMesh& m, const MeshFeatures& mf, const Feature& f) {
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  forIncident(m, mf, f, [&](std::uint32_t t) { sum += m.faceNormal(static_cast<int>(t)); });
  return sum;
}

int someTriangle(const MeshFeatures& mf, const Feature& f) {
  return static_cast<int>(f.kind == Feature::Face ? f.a : mf.trianglesAt(f.a).front());
}

}  // namespace unidist::contact
