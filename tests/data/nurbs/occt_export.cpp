// Writes the OpenCASCADE fixtures of this folder: a torus (R = 1, a = 0.25) and a sphere (radius 0.5 about
// (1, 2, 3)) made by BRepPrimAPI, converted to NURBS geometry and written by OpenCASCADE 7.6's IGES writer, as a
// CAD kernel writes them (entity 128 surfaces with 120° arcs on unclamped knot vectors, trimmed by 144/142/126).
// torus_occt_faces.igs and sphere_occt_faces.igs: the writer's face mode; torus_occt_brep.igs: its B-rep mode
// (186/514/510/508/504/502 around the same 128). Not part of the build; to regenerate (Debian
// libocct-data-exchange-dev):
//   g++ -std=c++17 -I/usr/include/opencascade occt_export.cpp -o occt_export -lTKIGES -lTKTopAlgo -lTKPrim \
//       -lTKBRep -lTKG3d -lTKG2d -lTKGeomBase -lTKMath -lTKernel -lTKXSBase -lTKShHealing
//   ./occt_export faces && ./occt_export brep
#include <BRepBuilderAPI_NurbsConvert.hxx>
#include <BRepPrimAPI_MakeSphere.hxx>
#include <BRepPrimAPI_MakeTorus.hxx>
#include <IGESControl_Controller.hxx>
#include <IGESControl_Writer.hxx>
#include <TopoDS_Shape.hxx>

#include <cstdio>
#include <string>

int main(int argc, char** argv) {
  const std::string mode = argc > 1 ? argv[1] : "faces";
  IGESControl_Controller::Init();
  const TopoDS_Shape shapes[2] = {BRepPrimAPI_MakeTorus(1.0, 0.25).Shape(),
                                  BRepPrimAPI_MakeSphere(gp_Pnt(1, 2, 3), 0.5).Shape()};
  const char* names[2] = {"torus", "sphere"};
  for (int k = 0; k < 2; ++k) {
    IGESControl_Writer writer("MM", mode == "brep" ? 1 : 0);
    writer.AddShape(BRepBuilderAPI_NurbsConvert(shapes[k], Standard_True).Shape());
    writer.ComputeModel();
    const std::string file = std::string(names[k]) + "_occt_" + mode + ".igs";
    if (!writer.Write(file.c_str())) return std::fprintf(stderr, "could not write %s\n", file.c_str()), 1;
  }
  return 0;
}
