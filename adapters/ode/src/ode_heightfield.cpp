// ODE heightfield numbers → closed TriangleMesh (unidist/adapters/ode_heightfield.h).
#include "unidist/adapters/ode_heightfield.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace unidist {
namespace {

using Vec = Eigen::Vector3d;
using Tri = TriangleMesh::Triangle;

bool positiveFinite(double v) { return std::isfinite(v) && v > 0; }

void validate(const OdeHeightfieldSpec& s) {
  const std::string where = "unidist::ode::describeHeightfield: ";
  if (!s.heights) throw InputError(where + "null height data");
  if (s.widthSamples < 2 || s.depthSamples < 2)
    throw InputError(where + "widthSamples and depthSamples must be >= 2 (got " + std::to_string(s.widthSamples) +
                     " x " + std::to_string(s.depthSamples) + ")");
  if (!positiveFinite(s.width) || !positiveFinite(s.depth))
    throw InputError(where + "width and depth must be finite and > 0");
  if (!positiveFinite(s.thickness))
    throw InputError(where +
                     "thickness must be finite and > 0 (the solid's bottom lies that far below the lowest sample)");
  if (!std::isfinite(s.scale) || !std::isfinite(s.offset)) throw InputError(where + "scale and offset must be finite");
  if (s.wrap)
    throw InputError(where +
                     "wrapped (infinitely tiled) heightfields are not supported; build the data with bWrap = 0");
  const long n = static_cast<long>(s.widthSamples) * s.depthSamples;
  for (long k = 0; k < n; ++k)
    if (!std::isfinite(s.heights[k]))
      throw InputError(where + "height sample " + std::to_string(k) + " (x index " +
                       std::to_string(k % s.widthSamples) + ", z index " + std::to_string(k / s.widthSamples) +
                       ") is NaN or infinite");
}

}  // namespace

std::shared_ptr<const TriangleMesh> odeHeightfieldMesh(const OdeHeightfieldSpec& s) {
  validate(s);
  const int W = s.widthSamples, D = s.depthSamples;
  const auto top = [W](int i, int j) { return static_cast<std::uint32_t>(i + j * W); };
  std::vector<Vec> v;
  v.reserve(static_cast<std::size_t>(W) * D + 2 * (W + D) + 1);
  double lowest = std::numeric_limits<double>::infinity();
  for (int j = 0; j < D; ++j)
    for (int i = 0; i < W; ++i) {
      const double x = -0.5 * s.width + s.width * i / (W - 1);
      const double z = -0.5 * s.depth + s.depth * j / (D - 1);
      const double y = s.heights[i + static_cast<long>(j) * W] * s.scale + s.offset;
      lowest = std::min(lowest, y);
      v.emplace_back(x, y, z);
    }
  const double bottom = lowest - s.thickness;

  std::vector<Tri> t;
  t.reserve(2 * static_cast<std::size_t>(W - 1) * (D - 1) + 4 * static_cast<std::size_t>(W + D));
  // Surface, normals +y: (A, C, B) and (D', B, C) with A = (i, j), B = (i+1, j), C = (i, j+1), D' = (i+1, j+1).
  for (int j = 0; j + 1 < D; ++j)
    for (int i = 0; i + 1 < W; ++i) {
      t.push_back({top(i, j), top(i, j + 1), top(i + 1, j)});
      t.push_back({top(i + 1, j + 1), top(i + 1, j), top(i, j + 1)});
    }

  // The boundary loop of surface vertices (its direction does not matter: each wall triangle is oriented by its
  // side's outward direction), the same loop at the bottom height, and a fan from the bottom's centre.
  std::vector<std::uint32_t> loop;
  for (int i = 0; i + 1 < W; ++i) loop.push_back(top(i, 0));
  for (int j = 0; j + 1 < D; ++j) loop.push_back(top(W - 1, j));
  for (int i = W - 1; i > 0; --i) loop.push_back(top(i, D - 1));
  for (int j = D - 1; j > 0; --j) loop.push_back(top(0, j));
  std::vector<std::uint32_t> below;
  for (std::uint32_t k : loop) {
    below.push_back(static_cast<std::uint32_t>(v.size()));
    v.emplace_back(v[k].x(), bottom, v[k].z());
  }
  const auto centre = static_cast<std::uint32_t>(v.size());
  v.emplace_back(0, bottom, 0);

  // Oriented so that the normal points along `out` (the side's outward direction).
  const auto add = [&](std::uint32_t a, std::uint32_t b, std::uint32_t c, const Vec& out) {
    if ((v[b] - v[a]).cross(v[c] - v[a]).dot(out) >= 0)
      t.push_back({a, b, c});
    else
      t.push_back({a, c, b});
  };
  const std::size_t n = loop.size();
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t l = (k + 1) % n;
    const Vec mid = 0.5 * (v[loop[k]] + v[loop[l]]);
    const Vec out(mid.x(), 0, mid.z());  // from the vertical centre axis outward: right for every side
    add(loop[k], loop[l], below[l], out);
    add(loop[k], below[l], below[k], out);
    add(centre, below[l], below[k], Vec(0, -1, 0));
  }
  return std::make_shared<const TriangleMesh>(std::move(v), std::move(t));
}

}  // namespace unidist
