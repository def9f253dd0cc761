// Analytic primitives: exact closest point, outward normal and signed distance for every finite query
// point, in the primitive's own frame. Every size must be finite and > 0 (also a capsule's half-length, as the
// contract asks); otherwise the constructor throws InputError naming the field and value.
//
// Defined answers where the closest point is not unique (never NaN):
//  * sphere centre: the point (0, 0, r), normal +z;
//  * box: ties between faces go to the face of lowest axis index, the positive side first (+x, -x, +y, ...);
//  * capsule / cylinder on the axis: the direction +x is taken as the radial direction;
//  * cone apex region and axis: radial direction +x; the apex itself answers with the side normal at +x;
//  * torus: on the axis (centre line) the tube point toward +x; on the centre circle the point at +z of the tube.
#pragma once

#include "unidist/model.h"

#include <atomic>
#include <memory>
#include <mutex>

namespace unidist {

class TriangleMesh;
class NurbsModel;

/// A structure a primitive makes on first use, once, thread-safely; a copy of the primitive starts without one.
template <class T>
class LazyStandIn {
 public:
  LazyStandIn() = default;
  LazyStandIn(const LazyStandIn&) {}
  LazyStandIn& operator=(const LazyStandIn&) { return *this; }
  /// The structure, made by make() (a std::shared_ptr<const T>) on the first call.
  template <class Make>
  const T& get(Make&& make) const {
    std::call_once(once_, [&] {
      value_ = make();
      ready_.store(value_.get(), std::memory_order_release);
    });
    return *value_;
  }
  /// Built or not and its bytes, without building it (T complete where this is called).
  StructureReport report(const char* name) const {
    const T* t = ready_.load(std::memory_order_acquire);
    return {name, t != nullptr, t ? t->memoryBytes() : 0};
  }

 private:
  mutable std::once_flag once_;
  mutable std::shared_ptr<const T> value_;
  mutable std::atomic<const T*> ready_{nullptr};
};

/// Shared pieces of every primitive (no acceleration structure, constant memory).
class Primitive : public Model {
 public:
  bool isSolid() const override { return true; }
  bool isConvex() const override { return true; }
  std::size_t memoryBytes() const override;
};

/// Solid ball of radius r centred at the origin.
class Sphere final : public Primitive {
 public:
  explicit Sphere(double r);
  double radius() const { return r_; }
  ModelType type() const override { return ModelType::Sphere; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q) const override;
  Aabb localBounds() const override;
  bool inside(const Eigen::Vector3d& q) const override;
  Eigen::Vector3d support(const Eigen::Vector3d& dir) const override;
  std::vector<SurfaceCell> surfaceCells() const override;
  void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const override;
  std::string describe() const override;
  std::size_t memoryBytes() const override;

  /// The same solid as an exact rational NURBS model (the meridian's rational quadratic half circle revolved
  /// about z: 8 biquadratic patches, on the sphere to rounding), built on first use, once, thread-safely: a ball
  /// sunk into a non-convex solid NURBS model meets it through the NURBS–NURBS search on it.
  const NurbsModel& asNurbs() const;
  /// "exact-nurbs" (asNurbs() and the patch tree its queries have refined).
  std::vector<StructureReport> structures() const override;

 private:
  double r_;
  LazyStandIn<NurbsModel> nurbs_;
};

/// Solid box [-hx,hx]x[-hy,hy]x[-hz,hz] (half extents).
class Box final : public Primitive {
 public:
  explicit Box(const Eigen::Vector3d& halfExtents);
  const Eigen::Vector3d& halfExtents() const { return h_; }
  ModelType type() const override { return ModelType::Box; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q) const override;
  Aabb localBounds() const override;
  bool inside(const Eigen::Vector3d& q) const override;
  Eigen::Vector3d support(const Eigen::Vector3d& dir) const override;
  std::vector<SurfaceCell> surfaceCells() const override;
  void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const override;
  std::string describe() const override;
  std::size_t memoryBytes() const override;

  /// The same solid as 12 outward triangles (its point queries agree with the box's), built on first use, once,
  /// thread-safely: the contact search works on it, and a simulation asks every step.
  const TriangleMesh& asMesh() const;
  /// "contact-mesh" (asMesh(), for contact sets only).
  std::vector<StructureReport> structures() const override;
  void buildStructures() const override { asMesh(); }

 private:
  Eigen::Vector3d h_;
  LazyStandIn<TriangleMesh> mesh_;
};

/// Segment from (0,0,-h) to (0,0,+h) swept by a ball of radius r.
class Capsule final : public Primitive {
 public:
  Capsule(double r, double halfLength);
  double radius() const { return r_; }
  double halfLength() const { return h_; }
  ModelType type() const override { return ModelType::Capsule; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q) const override;
  Aabb localBounds() const override;
  bool inside(const Eigen::Vector3d& q) const override;
  Eigen::Vector3d support(const Eigen::Vector3d& dir) const override;
  std::vector<SurfaceCell> surfaceCells() const override;
  void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const override;
  std::string describe() const override;

 private:
  double r_, h_;
};

/// Solid cylinder of radius r about z, from z=-h to z=+h.
class Cylinder final : public Primitive {
 public:
  Cylinder(double r, double halfHeight);
  double radius() const { return r_; }
  double halfHeight() const { return h_; }
  ModelType type() const override { return ModelType::Cylinder; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q) const override;
  Aabb localBounds() const override;
  bool inside(const Eigen::Vector3d& q) const override;
  Eigen::Vector3d support(const Eigen::Vector3d& dir) const override;
  std::vector<SurfaceCell> surfaceCells() const override;
  void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const override;
  std::string describe() const override;

 private:
  double r_, h_;
};

/// Solid cone about z: base disc of radius r at z=-h, apex at z=+h.
class Cone final : public Primitive {
 public:
  Cone(double r, double halfHeight);
  double radius() const { return r_; }
  double halfHeight() const { return h_; }
  ModelType type() const override { return ModelType::Cone; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q) const override;
  Aabb localBounds() const override;
  bool inside(const Eigen::Vector3d& q) const override;
  Eigen::Vector3d support(const Eigen::Vector3d& dir) const override;
  std::vector<SurfaceCell> surfaceCells() const override;
  void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const override;
  std::string describe() const override;

 private:
  double r_, h_;
};

/// Solid torus about z: the points within tubeRadius of the circle of radius majorRadius in the z=0 plane.
/// Requires 0 < tubeRadius < majorRadius. Not convex: it is the centre circle swept by a ball.
class Torus final : public Primitive {
 public:
  Torus(double majorRadius, double tubeRadius);
  double majorRadius() const { return R_; }
  double tubeRadius() const { return r_; }
  ModelType type() const override { return ModelType::Torus; }
  bool isConvex() const override { return false; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q) const override;
  Aabb localBounds() const override;
  bool inside(const Eigen::Vector3d& q) const override;
  Eigen::Vector3d support(const Eigen::Vector3d& dir) const override;
  std::vector<SurfaceCell> surfaceCells() const override;
  void splitCell(const SurfaceCell& cell, std::vector<SurfaceCell>& out) const override;
  std::string describe() const override;
  /// Point of the centre circle at angle theta: (R cos θ, R sin θ, 0).
  Eigen::Vector3d circlePoint(double theta) const;
  std::size_t memoryBytes() const override;

  /// The same solid as an exact rational NURBS model (the tube's rational quadratic circle revolved about z:
  /// 16 biquadratic patches, on the torus to rounding), built on first use, once, thread-safely: a solid NURBS
  /// model meets the torus through the NURBS–NURBS search on it.
  const NurbsModel& asNurbs() const;
  /// "exact-nurbs" (asNurbs() and the patch tree its queries have refined).
  std::vector<StructureReport> structures() const override;

 private:
  double R_, r_;
  LazyStandIn<NurbsModel> nurbs_;
};

/// Solid half-space n·x <= d (n unit after construction; d scaled by 1/|n|). Unbounded: its AABB is infinite,
/// it has no surface cells, and its support map is only finite along +n (elsewhere a far point is returned).
class Plane final : public Primitive {
 public:
  Plane(const Eigen::Vector3d& normal, double offset);
  const Eigen::Vector3d& normal() const { return n_; }
  double offset() const { return d_; }
  ModelType type() const override { return ModelType::Plane; }
  SurfacePoint closestPoint(const Eigen::Vector3d& q) const override;
  Aabb localBounds() const override;
  BoundingSphere localBoundingSphere() const override;
  bool inside(const Eigen::Vector3d& q) const override;
  Eigen::Vector3d support(const Eigen::Vector3d& dir) const override;
  std::vector<SurfaceCell> surfaceCells() const override { return {}; }
  void splitCell(const SurfaceCell&, std::vector<SurfaceCell>&) const override {}
  std::string describe() const override;

 private:
  Eigen::Vector3d n_;
  double d_;
};

}  // namespace unidist
