// Box [-hx,hx]x[-hy,hy]x[-hz,hz].
//
// Feature ids:
//   faces    0..5   : +x, -x, +y, -y, +z, -z  (2·axis + 1 on the negative side)
//   edges    6..17  : 6 + 4·a + 2·s1 + s2, a = the edge's direction axis, s1 and s2 = 1 on the negative side
//                     of the other two axes (in increasing order)
//   vertices 18..25 : 18 + 4·sx + 2·sy + sz (1 = negative side)
// Edges and vertices are reported only for points strictly outside. A point inside or on the surface takes
// the nearest face, ties to the lowest face id (primitives.h), so a point exactly on an edge or corner
// answers with that face's id and normal.
// param: on a face the point's two other coordinates (increasing axis order), as in the surface cells;
// on an edge (coordinate along the edge, 0); at a vertex (0, 0).
#include "unidist/primitives.h"
#include "unidist/mesh.h"

#include "primitives/cells.h"
#include "primitives/common.h"

namespace unidist {
namespace {

// The two axes other than a, in increasing order.
int firstOther(int a) { return a == 0 ? 1 : 0; }
int secondOther(int a) { return a == 2 ? 1 : 2; }

// Faces are flat: the exact half diagonal of the parameter rectangle bounds every point.
SurfaceCell boxCell(const Eigen::Vector3d& h, int face, double u0, double u1, double v0, double v1) {
  const int a = face / 2;
  Eigen::Vector3d mid;
  mid[a] = (face % 2 == 0) ? h[a] : -h[a];
  mid[firstOther(a)] = 0.5 * (u0 + u1);
  mid[secondOther(a)] = 0.5 * (v0 + v1);
  return prim::makeCell(face, u0, u1, v0, v1, mid, 0.5 * std::hypot(u1 - u0, v1 - v0), h.norm());
}

}  // namespace

Box::Box(const Eigen::Vector3d& halfExtents) : h_(halfExtents) {
  prim::requirePositive("box", "hx", h_.x());
  prim::requirePositive("box", "hy", h_.y());
  prim::requirePositive("box", "hz", h_.z());
}

SurfacePoint Box::closestPoint(const Eigen::Vector3d& q) const {
  SurfacePoint s;
  const Eigen::Vector3d p = q.cwiseMax(-h_).cwiseMin(h_);
  const Eigen::Vector3d gap = q - p;  // exactly 0 on the axes where q is within the slab
  int outsideAxes = 0;
  for (int i = 0; i < 3; ++i) outsideAxes += gap[i] != 0.0;

  if (outsideAxes > 0) {
    s.point = p;
    s.normal = prim::unitOr(gap, Eigen::Vector3d::UnitX());
    s.signedDistance = prim::robustNorm(gap);
    const auto neg = [&](int i) { return q[i] < 0 ? 1 : 0; };
    if (outsideAxes == 1) {
      const int a = gap.x() != 0 ? 0 : (gap.y() != 0 ? 1 : 2);
      s.feature = 2 * a + neg(a);
      s.param = {p[firstOther(a)], p[secondOther(a)]};
    } else if (outsideAxes == 2) {
      const int a = gap.x() == 0 ? 0 : (gap.y() == 0 ? 1 : 2);  // the free axis runs along the edge
      s.feature = 6 + 4 * a + 2 * neg(firstOther(a)) + neg(secondOther(a));
      s.param = {p[a], 0.0};
    } else {
      s.feature = 18 + 4 * neg(0) + 2 * neg(1) + neg(2);
      s.param = {0.0, 0.0};
    }
    return s;
  }

  // Inside or on the surface: the nearest face; strict < keeps the lowest id on ties.
  int best = 0;
  double bestDepth = h_.x() - q.x();
  for (int f = 1; f < 6; ++f) {
    const int a = f / 2;
    const double depth = (f % 2 == 0) ? h_[a] - q[a] : h_[a] + q[a];
    if (depth < bestDepth) {
      best = f;
      bestDepth = depth;
    }
  }
  const int a = best / 2;
  const double side = (best % 2 == 0) ? 1.0 : -1.0;
  s.point = q;
  s.point[a] = side * h_[a];
  s.normal = Eigen::Vector3d::Zero();
  s.normal[a] = side;
  s.signedDistance = 0.0 - bestDepth;  // 0.0 - 0.0 is +0: a surface point is not "inside"
  s.feature = best;
  s.param = {q[firstOther(a)], q[secondOther(a)]};
  return s;
}

Aabb Box::localBounds() const {
  Aabb b;
  b.min = -h_;
  b.max = h_;
  return b;
}

bool Box::inside(const Eigen::Vector3d& q) const { return (q.cwiseAbs().array() < h_.array()).all(); }

Eigen::Vector3d Box::support(const Eigen::Vector3d& dir) const {
  return {dir.x() >= 0 ? h_.x() : -h_.x(), dir.y() >= 0 ? h_.y() : -h_.y(), dir.z() >= 0 ? h_.z() : -h_.z()};
}

std::vector<SurfaceCell> Box::surfaceCells() const {
  std::vector<SurfaceCell> cells;
  for (int f = 0; f < 6; ++f) {
    const int a = f / 2, b = firstOther(a), c = secondOther(a);
    cells.push_back(boxCell(h_, f, -h_[b], h_[b], -h_[c], h_[c]));
  }
  return cells;
}

void Box::splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const {
  prim::splitInFour(
      cell, out, [this](int f, double u0, double u1, double v0, double v1) { return boxCell(h_, f, u0, u1, v0, v1); });
}

std::string Box::describe() const {
  return "box hx=" + prim::exact(h_.x()) + " hy=" + prim::exact(h_.y()) + " hz=" + prim::exact(h_.z());
}

}  // namespace unidist

namespace unidist {

const TriangleMesh& Box::asMesh() const {
  return mesh_.get([this] {
    std::vector<Eigen::Vector3d> v;
    for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? h_.x() : -h_.x(), i & 2 ? h_.y() : -h_.y(), i & 4 ? h_.z() : -h_.z());
    std::vector<TriangleMesh::Triangle> t = {{0, 2, 3}, {0, 3, 1}, {4, 5, 7}, {4, 7, 6}, {0, 1, 5}, {0, 5, 4},
                                             {2, 6, 7}, {2, 7, 3}, {0, 4, 6}, {0, 6, 2}, {1, 3, 7}, {1, 7, 5}};
    return std::make_shared<const TriangleMesh>(std::move(v), std::move(t));
  });
}

std::vector<StructureReport> Box::structures() const { return {mesh_.report("contact-mesh")}; }

std::size_t Box::memoryBytes() const { return sizeof(*this) + mesh_.report("").bytes; }

}  // namespace unidist
