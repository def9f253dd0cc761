// OpenCASCADE 7.6 on the dial's NURBS cases: BRepExtrema_DistShapeShape, its dial being the deflection (the
// precision of the minimum, default 1e-7), set to the tolerance we are asked for. Our NURBS surfaces become
// Geom_BSplineSurface faces knot for knot (occt_surface.h); primitives become the compound of their boundary faces
// on analytic surfaces (Debian's 7.6 headers cannot include BRepPrimAPI: NCollection_AliasedArray.hxx is missing),
// which is all a distance between apart shapes sees. Shapes that overlap measure 0 here, so apart cases only;
// no capsule, torus solid, mesh or cloud.
#include "bench/dial_peers.h"
#include "bench/occt_surface.h"

#include <BRepBuilderAPI_MakeEdge.hxx>
#include <BRepBuilderAPI_MakeFace.hxx>
#include <BRepBuilderAPI_MakePolygon.hxx>
#include <BRepBuilderAPI_MakeWire.hxx>
#include <BRepExtrema_DistShapeShape.hxx>
#include <Geom_ConicalSurface.hxx>
#include <Geom_CylindricalSurface.hxx>
#include <Geom_SphericalSurface.hxx>
#include <TopLoc_Location.hxx>
#include <TopoDS_Builder.hxx>
#include <TopoDS_Compound.hxx>
#include <gp_Circ.hxx>
#include <gp_Pln.hxx>
#include <gp_Trsf.hxx>

#include <cmath>
#include <optional>

namespace dial {
namespace {

gp_Trsf occtPose(const Pose& X) {
  const Eigen::Matrix3d R = X.linear();
  const Vec t = X.translation();
  gp_Trsf T;
  T.SetValues(R(0, 0), R(0, 1), R(0, 2), t.x(), R(1, 0), R(1, 1), R(1, 2), t.y(), R(2, 0), R(2, 1), R(2, 2), t.z());
  return T;
}

TopoDS_Shape compound(const std::vector<TopoDS_Shape>& faces) {
  TopoDS_Builder builder;
  TopoDS_Compound c;
  builder.MakeCompound(c);
  for (const TopoDS_Shape& f : faces) builder.Add(c, f);
  return c;
}

/// The disk of radius r at height z, facing along ±z.
TopoDS_Shape disk(double r, double z) {
  const gp_Circ circle(gp_Ax2(gp_Pnt(0, 0, z), gp::DZ()), r);
  return BRepBuilderAPI_MakeFace(gp_Pln(gp_Pnt(0, 0, z), gp::DZ()), BRepBuilderAPI_MakeWire(BRepBuilderAPI_MakeEdge(circle)).Wire()).Face();
}

TopoDS_Shape boxFaces(double hx, double hy, double hz) {
  std::vector<TopoDS_Shape> faces;
  const double h[3] = {hx, hy, hz};
  for (int axis = 0; axis < 3; ++axis)
    for (double side : {-1.0, 1.0}) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      auto corner = [&](double su, double sv) {
        double p[3];
        p[axis] = side * h[axis];
        p[u] = su * h[u];
        p[v] = sv * h[v];
        return gp_Pnt(p[0], p[1], p[2]);
      };
      BRepBuilderAPI_MakePolygon square(corner(-1, -1), corner(1, -1), corner(1, 1), corner(-1, 1), Standard_True);
      faces.push_back(BRepBuilderAPI_MakeFace(square.Wire(), Standard_True).Face());
    }
  return compound(faces);
}

/// The posed model as an OpenCASCADE shape, when there is one.
std::optional<TopoDS_Shape> occtShape(const Geometry& g, const Pose& X) {
  if (g.kind == Geometry::Kind::Nurbs) return TopoDS_Shape(occt_bench::faceOf(occt_bench::toOcct(g.surfaces.front(), X)));
  if (g.kind != Geometry::Kind::Primitive) return std::nullopt;
  const oracle::Shape& s = g.shape;
  const gp_Ax3 base(gp_Pnt(0, 0, -s.p1), gp::DZ());
  TopoDS_Shape shape;
  if (s.kind == "box") {
    shape = boxFaces(s.p0, s.p1, s.p2);
  } else if (s.kind == "cylinder") {
    const Handle(Geom_CylindricalSurface) side = new Geom_CylindricalSurface(gp_Ax3(gp::Origin(), gp::DZ()), s.p0);
    shape = compound({BRepBuilderAPI_MakeFace(side, 0, 2 * M_PI, -s.p1, s.p1, 1e-12).Face(), disk(s.p0, -s.p1), disk(s.p0, s.p1)});
  } else if (s.kind == "cone") {
    // Radius p0 at the base (z = −p1) shrinking to the apex at z = +p1: a negative semi-angle, v along the slant.
    const double slant = std::hypot(s.p0, 2 * s.p1);
    const Handle(Geom_ConicalSurface) side = new Geom_ConicalSurface(base, -std::atan2(s.p0, 2 * s.p1), s.p0);
    shape = compound({BRepBuilderAPI_MakeFace(side, 0, 2 * M_PI, 0, slant, 1e-12).Face(), disk(s.p0, -s.p1)});
  } else if (s.kind == "sphere") {
    shape = BRepBuilderAPI_MakeFace(new Geom_SphericalSurface(gp_Ax3(), s.p0), 1e-12).Face();
  } else {
    return std::nullopt;
  }
  return shape.Moved(TopLoc_Location(occtPose(X)));
}

}  // namespace

void occtPeers(const Family& f) {
  if (f.name != "prim-nurbs" && f.name != "nurbs-nurbs") return;
  const std::vector<double> tolerances = decades();
  peerRows(f, "OCCT DistShapeShape (apart only)", static_cast<int>(tolerances.size()), [&](const Case& c, int k) -> Prepared {
    if (c.penetrating) return {};
    const std::optional<TopoDS_Shape> a = occtShape(*c.a, c.Xa), b = occtShape(*c.b, c.Xb);
    if (!a || !b) return {};
    const double relative = tolerances[static_cast<std::size_t>(k)], deflection = relative * c.size;
    return {[a, b, deflection] {
              BRepExtrema_DistShapeShape d(*a, *b, deflection);
              return d.IsDone() && d.NbSolution() > 0 ? d.Value() : std::nan("");
            },
            relative};
  });
}

}  // namespace dial
