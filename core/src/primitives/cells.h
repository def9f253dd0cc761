// Private helpers for surface cells (see SurfaceCell in model.h). A cell is a parameter rectangle on one
// face; its centre is the surface point at the mid parameter and its radius a proved bound on how far any
// point of the rectangle lies from that centre, built from the triangle inequality
//   |p(u,v) - p(um,vm)| <= |p(u,v) - p(um,v)| + |p(um,v) - p(um,vm)|,
// each term being a straight segment or a circular arc whose chord is bounded exactly.
#pragma once

#include "unidist/model.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace unidist::prim {

/// Farthest a point of a circular arc of radius rho and opening `angle` (<= 2π) lies from the arc's
/// midpoint: the chord 2ρ·sin(angle/4).
inline double arcReach(double rho, double angle) { return 2.0 * rho * std::sin(0.25 * angle); }

/// max cos over [a0, a1] ⊂ [-π, π]: cos rises up to 0 and falls after, so it is 1 when the interval
/// holds 0 and the larger end value otherwise.
inline double maxCos(double a0, double a1) {
  return (a0 <= 0.0 && a1 >= 0.0) ? 1.0 : std::max(std::cos(a0), std::cos(a1));
}

/// A cell centred (and sampled) at `mid`, the surface point at the mid parameter. `reach` is the proved
/// bound in exact arithmetic; the padding covers rounding in the centre, the angles and the bound itself,
/// all a few ulps of `scale` (the primitive's size).
inline SurfaceCell makeCell(int face, double u0, double u1, double v0, double v1, const Eigen::Vector3d& mid,
                            double reach, double scale) {
  constexpr double kEps = std::numeric_limits<double>::epsilon();
  SurfaceCell c;
  c.center = mid;
  c.sample = mid;
  c.radius = reach * (1.0 + 16.0 * kEps) + 16.0 * kEps * scale;
  c.face = face;
  c.u0 = u0;
  c.u1 = u1;
  c.v0 = v0;
  c.v1 = v1;
  return c;
}

/// Appends the four quarters of `c` (both parameters halved), each built by make(face, u0, u1, v0, v1).
/// The halves share the same computed midpoint, so they cover the parent exactly.
template <class Make>
void splitInFour(const SurfaceCell& c, std::vector<SurfaceCell>& out, const Make& make) {
  const double um = 0.5 * (c.u0 + c.u1), vm = 0.5 * (c.v0 + c.v1);
  out.push_back(make(c.face, c.u0, um, c.v0, vm));
  out.push_back(make(c.face, um, c.u1, c.v0, vm));
  out.push_back(make(c.face, c.u0, um, vm, c.v1));
  out.push_back(make(c.face, um, c.u1, vm, c.v1));
}

/// Four quarter turns of the angle u ∈ [-π, π] times the given v range, appended to out.
template <class Make>
void quarterTurns(int face, double v0, double v1, std::vector<SurfaceCell>& out, const Make& make) {
  constexpr double kPi = 3.14159265358979323846;
  const double cuts[5] = {-kPi, -0.5 * kPi, 0.0, 0.5 * kPi, kPi};
  for (int i = 0; i < 4; ++i) out.push_back(make(face, cuts[i], cuts[i + 1], v0, v1));
}

}  // namespace unidist::prim
