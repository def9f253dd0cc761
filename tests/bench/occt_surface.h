// The same NURBS surface for OpenCASCADE: a unidist::NurbsSurface (full knot vectors, Euclidean control points
// with weights) as a Geom_BSplineSurface (distinct knots with multiplicities), optionally moved by a rigid pose,
// and as a TopoDS face for BRepExtrema. Benchmark-only.
#pragma once

#include "unidist/nurbs.h"

#include <BRepBuilderAPI_MakeFace.hxx>
#include <Geom_BSplineSurface.hxx>
#include <TColStd_Array1OfInteger.hxx>
#include <TColStd_Array1OfReal.hxx>
#include <TColStd_Array2OfReal.hxx>
#include <TColgp_Array2OfPnt.hxx>
#include <TopoDS_Face.hxx>

#include <vector>

namespace occt_bench {

/// Distinct knots and their multiplicities, as OpenCASCADE stores a knot vector.
inline void splitKnots(const std::vector<double>& full, std::vector<double>& knots, std::vector<int>& mults) {
  for (double k : full) {
    if (!knots.empty() && k == knots.back()) {
      ++mults.back();
    } else {
      knots.push_back(k);
      mults.push_back(1);
    }
  }
}

inline TColStd_Array1OfReal reals(const std::vector<double>& v) {
  TColStd_Array1OfReal a(1, static_cast<int>(v.size()));
  for (int i = 0; i < static_cast<int>(v.size()); ++i) a(i + 1) = v[static_cast<std::size_t>(i)];
  return a;
}

inline TColStd_Array1OfInteger integers(const std::vector<int>& v) {
  TColStd_Array1OfInteger a(1, static_cast<int>(v.size()));
  for (int i = 0; i < static_cast<int>(v.size()); ++i) a(i + 1) = v[static_cast<std::size_t>(i)];
  return a;
}

/// The surface X·S (a rigid motion of a NURBS moves its control points; weights are unchanged).
inline Handle(Geom_BSplineSurface) toOcct(const unidist::NurbsSurface& s,
                                          const Eigen::Isometry3d& X = Eigen::Isometry3d::Identity()) {
  TColgp_Array2OfPnt poles(1, s.countU(), 1, s.countV());
  TColStd_Array2OfReal weights(1, s.countU(), 1, s.countV());
  for (int i = 0; i < s.countU(); ++i)
    for (int j = 0; j < s.countV(); ++j) {
      const Eigen::Vector4d c = s.controlPoint(i, j);
      const Eigen::Vector3d p = X * c.head<3>().eval();
      poles(i + 1, j + 1) = gp_Pnt(p.x(), p.y(), p.z());
      weights(i + 1, j + 1) = c[3];
    }
  std::vector<double> ku, kv;
  std::vector<int> mu, mv;
  splitKnots(s.knotsU(), ku, mu);
  splitKnots(s.knotsV(), kv, mv);
  return new Geom_BSplineSurface(poles, weights, reals(ku), reals(kv), integers(mu), integers(mv), s.degreeU(),
                                 s.degreeV());
}

inline TopoDS_Face faceOf(const Handle(Geom_BSplineSurface)& surface) {
  return BRepBuilderAPI_MakeFace(surface, 1e-9).Face();
}

}  // namespace occt_bench
