// The speed/accuracy dial every query takes: distance() (DistanceOptions), contacts() (ContactOptions),
// manifoldContacts() (ManifoldOptions) and both engine plugins derive their options from QueryOptions, so one
// setting means the same thing everywhere. docs/dial.md measures what each setting costs and gives.
#pragma once

#include <algorithm>
#include <cmath>

namespace unidist {

struct QueryOptions {
  /// Absolute accuracy (unit: model length): the answer is within the larger of `tolerance` and
  /// `relativeTolerance` × |true distance| of the truth. Negative (the default) → the query's default (1e-9 × the
  /// larger posed bounding-box diagonal for distance() and contacts(), 1e-4 × the smaller one for the simulation
  /// contacts of manifoldContacts() and the plugins); 0 → as exact as double precision allows.
  double tolerance = -1;
  /// Accuracy relative to the distance (>= 0; 0 = off): far pairs may be answered more coarsely. Used only where
  /// a proved lower bound on |distance| (the bounding spheres' gap) allows it, so the guarantee always holds.
  double relativeTolerance = 0;
  /// Cap on the work of iterative methods (GJK/EPA iterations, alternating steps, branch-and-bound rounds); the
  /// answer reports honest bounds (status Bounded) when the cap stops it.
  int maxIterations = 100000;
  /// Level of detail of model A / B: the largest deviation (Hausdorff distance, model length; 0 = exact) the
  /// query accepts between a model and a cheaper stand-in answered in its place (Model::atDetail: a NURBS
  /// tessellation, a decimated point cloud). Results are about the stand-ins (points on their surfaces,
  /// features theirs); distance() widens its proved bounds by the deviations actually used, so they still hold
  /// for the models themselves. An engine shape's own dial (Bullet ShapeOptions, ODE setQueryOptions) uses
  /// detailA for that shape; its detailB is ignored.
  double detailA = 0, detailB = 0;
};

/// The stricter of two dials, for a pair whose models carry their own (the engine plugins): the smaller explicit
/// tolerance (a negative one defers to the other), the smaller relative tolerance, the larger iteration cap;
/// each model keeps its own level of detail (a's detailA as detailA, b's detailA as detailB).
inline QueryOptions stricter(const QueryOptions& a, const QueryOptions& b) {
  QueryOptions s;
  s.detailA = a.detailA;
  s.detailB = b.detailA;
  s.tolerance = a.tolerance < 0 ? b.tolerance : b.tolerance < 0 ? a.tolerance : std::min(a.tolerance, b.tolerance);
  s.relativeTolerance = std::min(a.relativeTolerance, b.relativeTolerance);
  s.maxIterations = std::max(a.maxIterations, b.maxIterations);
  return s;
}

/// The dial of an engine pair: its first model's dial `a` and its second's `b`, or null for a model without one
/// (an engine's own shape: exact, default dial).
inline QueryOptions dialOfPair(const QueryOptions& a, const QueryOptions* b) {
  if (b) return stricter(a, *b);
  QueryOptions s = a;
  s.detailB = 0;
  return s;
}

/// What is wrong with a level of detail (null when nothing): it must be finite and >= 0.
inline const char* invalidLevelOfDetail(double d) {
  return std::isfinite(d) && d >= 0 ? nullptr : "level of detail (largest deviation) must be finite and >= 0";
}

/// What is wrong with the dial's relativeTolerance or maxIterations (null when nothing): the checks every owner
/// of a dial makes (their tolerance rules differ: a geom refuses 0, a query takes it as "exact").
inline const char* invalidDialSetting(const QueryOptions& o) {
  if (!std::isfinite(o.relativeTolerance) || o.relativeTolerance < 0) return "relative tolerance must be finite and >= 0";
  if (o.maxIterations < 1) return "maxIterations must be >= 1";
  for (double d : {o.detailA, o.detailB})
    if (const char* why = invalidLevelOfDetail(d)) return why;
  return nullptr;
}

}  // namespace unidist
