// A NURBS surface as triangles for the peers that only take meshes or point hulls (Bullet, FCL): the surface
// evaluated on a uniform n × n/2 parameter grid. The dial of such a peer is n; its geometric tolerance is the
// chordal deflection, measured at every cell centre (surface point against the mean of the cell's corners).
// Benchmark-only.
#pragma once

#include "core/mesh_fixtures.h"
#include "unidist/nurbs.h"

#include <algorithm>
#include <cstdint>

namespace dial {

struct Tessellation {
  meshfix::Soup soup;
  double deflection = 0;  // largest cell-centre chordal deflection (absolute)
};

inline Tessellation tessellate(const unidist::NurbsSurface& s, int n) {
  const int nu = n, nv = std::max(2, n / 2);
  Tessellation t;
  auto param = [&](int i, int j) {
    return Eigen::Vector2d(s.uMin() + (s.uMax() - s.uMin()) * i / nu, s.vMin() + (s.vMax() - s.vMin()) * j / nv);
  };
  for (int i = 0; i <= nu; ++i)
    for (int j = 0; j <= nv; ++j) {
      const Eigen::Vector2d p = param(i, j);
      t.soup.vertices.push_back(s.evaluate(p[0], p[1]));
    }
  auto id = [&](int i, int j) { return static_cast<std::uint32_t>(i * (nv + 1) + j); };
  for (int i = 0; i < nu; ++i)
    for (int j = 0; j < nv; ++j) {
      t.soup.triangles.push_back({id(i, j), id(i + 1, j), id(i + 1, j + 1)});
      t.soup.triangles.push_back({id(i, j), id(i + 1, j + 1), id(i, j + 1)});
      const Eigen::Vector2d c = 0.5 * (param(i, j) + param(i + 1, j + 1));
      const Eigen::Vector3d mean = 0.25 * (t.soup.vertices[id(i, j)] + t.soup.vertices[id(i + 1, j)] +
                                           t.soup.vertices[id(i, j + 1)] + t.soup.vertices[id(i + 1, j + 1)]);
      t.deflection = std::max(t.deflection, (s.evaluate(c[0], c[1]) - mean).norm());
    }
  return t;
}

/// Resolutions the tessellating peers sweep.
inline std::vector<int> tessellationSteps() { return {8, 16, 32, 64, 128, 256}; }

}  // namespace dial
