// A NURBS model's level of detail: a triangle mesh proved to lie within a given Hausdorff distance of the
// surfaces (docs/dial.md, "Level of detail"). Internal.
#pragma once

#include "lod/stand_in_cache.h"
#include "unidist/nurbs.h"

namespace unidist::lod {

/// Most triangles a tessellation may have; a finer level gets no stand-in (the exact model answers).
constexpr std::size_t kMaxTessellationTriangles = 4'000'000;

/// Proved bounds on sup |S(x, y) − T(x, y)| over [0,1]^2, where S is the rational Bézier patch and T the two
/// triangles on its corners (split along the (0,0)–(1,1) diagonal, or along (1,0)–(0,1)), each parametrised
/// affinely by (x, y) over its half of the square. Each bounds the Hausdorff distance both ways.
struct CellDeviations {
  double mainDiagonal = 0, otherDiagonal = 0;
};
CellDeviations cellDeviations(const RationalBezierPatch& cell);

/// Per surface, a tensor grid in the NURBS parameters (every knot span cut into equal parts, refined until
/// every cell's cellDeviation meets the level), evaluated exactly, seams and poles welded. Null model when no
/// such mesh fits kMaxTessellationTriangles, or when a solid's tessellation is not closed (surfaces whose
/// shared edges are cut differently) or a cell collapses to a segment no other triangle holds.
Built tessellate(const NurbsModel& model, double maxDeviation);

}  // namespace unidist::lod
