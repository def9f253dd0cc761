// The mass routine of each representation (core/src/mass/*.cpp); massProperties() picks one by model type.
#pragma once

#include "unidist/mass.h"
#include "unidist/mesh.h"
#include "unidist/nurbs.h"
#include "unidist/primitives.h"

namespace unidist::mass {

/// Closed forms. Returns false for a primitive without a finite solid (a half-space).
bool primitiveMass(const Model& m, MassProperties& out);

/// Divergence theorem over the triangles of a closed mesh (signed tetrahedra from the bounds centre; the
/// mesh is outward-oriented after construction).
MassProperties meshMass(const TriangleMesh& mesh);

/// Divergence theorem by Gauss–Legendre quadrature over the rational Bézier patches of a NURBS solid.
MassProperties nurbsMass(const NurbsModel& model);

/// The solid box of the model's bounds, exact = false: the stand-in for models without an inside.
MassProperties boundsBoxMass(const Model& m);

}  // namespace unidist::mass
