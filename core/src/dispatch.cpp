#include "dispatch.h"

#include "generic/generic_distance.h"
#include "pairs/analytic.h"
#include "pairs/box_box.h"
#include "pairs/convex_pair.h"
#include "pairs/mesh_convex.h"
#include "pairs/mesh_mesh.h"
#include "pairs/nurbs_cloud.h"
#include "pairs/nurbs_convex.h"
#include "pairs/nurbs_mesh.h"
#include "pairs/nurbs_nurbs.h"
#include "pairs/torus_pairs.h"
#include "unidist/nurbs.h"
#include "unidist/primitives.h"

#include <algorithm>
#include <array>

namespace unidist::detail {
namespace {

DistanceResult boxPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  const auto& ba = static_cast<const Box&>(a.model);
  const auto& bb = static_cast<const Box&>(b.model);
  const ConvexDistance c = boxBox(ba.halfExtents(), a.X_WM, bb.halfExtents(), b.X_WM, ctx.tolerance);
  DistanceResult r = fromConvex(c, "box-box-sat");
  settleStatus(r, ctx.tolerance);
  if (!c.converged) r.status = Status::Bounded;
  return r;
}

DistanceResult planePair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) { return planeAny(a, b, ctx); }

DistanceResult capsulePair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  return capsuleCapsule(a, b, ctx);
}

DistanceResult torusPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  return torusSolid(a, b, ctx);
}

DistanceResult meshPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  if (b.model.type() == ModelType::Mesh)
    return meshMesh(a, b, ctx, a.model.isConvex() && b.model.isConvex() ? &convexPair : nullptr);
  if (a.model.type() == ModelType::PointCloud) return cloudCloud(a, b, ctx);
  return meshCloud(a, b, ctx);
}

/// NURBS (a) against a mesh (b): a convex mesh against a solid NURBS keeps the NURBS–convex routine (GJK on the
/// mesh's support map); every other pair walks both hierarchies.
DistanceResult nurbsMeshPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  if (a.model.isSolid() && b.model.isConvex()) return nurbsConvex(a, b, ctx);
  return nurbsMesh(a, b, ctx);
}

/// A torus (a) against a NURBS model (b): a solid NURBS model meets the torus's exact NURBS form in the
/// NURBS–NURBS search (a certified separation in microseconds, where the generic routine takes milliseconds to
/// seconds); an open one goes to the generic routine.
DistanceResult torusNurbsPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  if (!b.model.isSolid()) return genericPair(a, b, ctx);
  const PosedModel exact{static_cast<const Torus&>(a.model).asNurbs(), a.X_WM};
  return nurbsNurbs(exact, b, ctx);
}

DistanceResult dispatchByShape(const PosedModel& a, const PosedModel& b, const QueryContext& ctx);

/// Sphere first: one point query is exact against any convex solid and for any separation; a penetration
/// into a non-convex model goes on to that model's own routine.
DistanceResult spherePair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  bool exact = false;
  DistanceResult r = sphereAny(a, b, ctx, exact);
  if (exact || b.model.type() == ModelType::Sphere) return r;
  // Sunk into a solid that is not convex: often the way out along the contact normal is free, which one more
  // point query proves.
  if (!ctx.overlapVerdictOnly)
    if (std::optional<DistanceResult> out = sphereEscapeAlongNormal(a, b, ctx, r)) return *out;
  // The way along the contact normal is blocked (or the surface curves round the ball). Sunk into a solid NURBS
  // model that is not convex: the ball's exact NURBS form meets it in the NURBS–NURBS search, whose separation
  // tests hold along circles of contact (a ball resting in a ring's hole took 5–40 s through the point queries of
  // the NURBS–convex route, and ~70 ms this way). Into a torus primitive, both exact forms likewise (its own
  // direction search took 0.4–1.6 s there and stayed bounded, its value up to 5× the depth); where they are not
  // certified either, the narrower answer.
  const auto exactSphere = [&] { return PosedModel{static_cast<const Sphere&>(a.model).asNurbs(), a.X_WM}; };
  if (b.model.type() == ModelType::Nurbs && b.model.isSolid()) return nurbsNurbs(exactSphere(), b, ctx);
  if (b.model.type() != ModelType::Torus || ctx.overlapVerdictOnly || ctx.apartProofOnly)
    return dispatchByShape(a, b, ctx);
  const DistanceResult n = nurbsNurbs(exactSphere(), {static_cast<const Torus&>(b.model).asNurbs(), b.X_WM}, ctx);
  if (n.status == Status::Certified) return n;
  r = dispatchByShape(a, b, ctx);
  return n.upperBound - n.lowerBound < r.upperBound - r.lowerBound ? n : r;
}

struct Cell {
  PairFn fn = nullptr;
  bool swap = false;  // call fn(b, a) and swap the answer back
  const char* name = nullptr;
};

constexpr int kTypes = static_cast<int>(ModelType::Nurbs) + 1;  // the last ModelType

class DispatchTable {
 public:
  DispatchTable() {
    using T = ModelType;
    const T all[] = {T::Sphere, T::Box, T::Capsule, T::Cylinder, T::Cone, T::Torus, T::Mesh, T::PointCloud, T::Nurbs};
    for (T t : all) add(T::Plane, t, &planePair, "plane-support");
    for (T t : all) add(T::Sphere, t, &spherePair, "sphere-point-query");
    for (T t : {T::Box, T::Capsule, T::Cylinder, T::Cone, T::Torus}) add(T::Torus, t, &torusPair, "torus-circle-search");
    add(T::Capsule, T::Capsule, &capsulePair, "capsule-segments");
    add(T::Box, T::Box, &boxPair, "box-box-sat");
    add(T::Mesh, T::Mesh, &meshPair, "mesh-mesh-bvh");
    add(T::Mesh, T::PointCloud, &meshPair, "mesh-cloud-bvh");
    add(T::PointCloud, T::PointCloud, &meshPair, "cloud-cloud-bvh");
    add(T::Nurbs, T::Mesh, &nurbsMeshPair, "nurbs-mesh-bvh");
    add(T::Torus, T::Nurbs, &torusNurbsPair, "torus-as-nurbs");
    add(T::Nurbs, T::PointCloud, &nurbsCloud, "nurbs-cloud-bvh");
  }
  const Cell& at(ModelType a, ModelType b) const { return cells_[index(a)][index(b)]; }

 private:
  static int index(ModelType t) { return static_cast<int>(t); }
  void add(ModelType a, ModelType b, PairFn fn, const char* name) {
    cells_[index(a)][index(b)] = {fn, false, name};
    if (a != b) cells_[index(b)][index(a)] = {fn, true, name};
  }
  std::array<std::array<Cell, kTypes>, kTypes> cells_{};
};

const DispatchTable& table() {
  static const DispatchTable instance;  // immutable after construction (thread-safe static init)
  return instance;
}

/// The routine after the sphere shortcut: everything but the sphere row.
DistanceResult dispatchByShape(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  if (a.model.type() == ModelType::Sphere && b.model.type() == ModelType::Torus) return swapped(torusSolid(b, a, ctx));
  if (a.model.isConvex() && b.model.isConvex()) return convexPair(a, b, ctx);
  if (a.model.type() == ModelType::Mesh && b.model.isConvex()) return meshConvex(a, b, ctx, &convexPair);
  if (b.model.type() == ModelType::Mesh && a.model.isConvex()) return swapped(meshConvex(b, a, ctx, &convexPair));
  const bool nurbsA = a.model.type() == ModelType::Nurbs && a.model.isSolid();
  const bool nurbsB = b.model.type() == ModelType::Nurbs && b.model.isSolid();
  if (nurbsA && nurbsB) return nurbsNurbs(a, b, ctx);
  if (nurbsA && b.model.isConvex()) return nurbsConvex(a, b, ctx);
  if (nurbsB && a.model.isConvex()) return swapped(nurbsConvex(b, a, ctx));
  return genericPair(a, b, ctx);
}

}  // namespace

DistanceResult dispatchPair(const PosedModel& a, const PosedModel& b, const QueryContext& ctx) {
  if (a.model.type() == ModelType::Plane && b.model.type() == ModelType::Plane)
    throw InputError("plane-plane pairs are not supported");
  const Cell& cell = table().at(a.model.type(), b.model.type());
  if (cell.fn) return cell.swap ? swapped(cell.fn(b, a, ctx)) : cell.fn(a, b, ctx);
  return dispatchByShape(a, b, ctx);
}

const char* routineName(ModelType a, ModelType b) {
  const Cell& cell = table().at(a, b);
  return cell.name ? cell.name : "gjk-epa or generic";
}

}  // namespace unidist::detail
