// The patch forest: its roots, the poles (patch edges collapsed to a point) and distinct corners found with them,
// and how a node is cut into its children (quadrants, or strips along a pole).
#include "nurbs/patch_tree.h"

#include <algorithm>

namespace unidist::nurbs {
namespace {

// An edge whose control points lie within this fraction of the patch's ball radius of each other is a pole.
constexpr double kCollapsedEdge = 1e-9;

std::array<bool, 4> collapsedEdgesOf(const PatchNode& root) {
  const int p = root.net.degreeU, q = root.net.degreeV;
  const auto at = [&](int i, int j) { return root.points[static_cast<std::size_t>(i * (q + 1) + j)]; };
  const double negligible = kCollapsedEdge * root.ball.radius;
  std::array<bool, 4> out{true, true, true, true};
  for (int j = 0; j <= q; ++j) {
    out[0] = out[0] && (at(0, j) - at(0, 0)).norm() <= negligible;
    out[1] = out[1] && (at(p, j) - at(p, 0)).norm() <= negligible;
  }
  for (int i = 0; i <= p; ++i) {
    out[2] = out[2] && (at(i, 0) - at(0, 0)).norm() <= negligible;
    out[3] = out[3] && (at(i, q) - at(0, q)).norm() <= negligible;
  }
  return out;
}

/// A piece of a node: [a0, a1] x [b0, b1] of its local parameters, along the pole or not.
struct Piece {
  double a0, a1, b0, b1;
  bool pole;
};

/// The four pieces of n (see PatchForest::children), in n's local parameters; poleOfEdge: its patch's.
std::array<Piece, 4> piecesOf(const PatchNode& n, const std::array<int, 4>& poleOfEdge) {
  const bool sLow = n.s0 == 0 && poleOfEdge[0] >= 0, sHigh = n.s1 == 1 && poleOfEdge[1] >= 0;
  const bool tLow = n.t0 == 0 && poleOfEdge[2] >= 0, tHigh = n.t1 == 1 && poleOfEdge[3] >= 0;
  std::array<Piece, 4> out;
  if (!sLow && !sHigh && !tLow && !tHigh) {
    for (int k = 0; k < 4; ++k) {
      const bool right = k & 1, upper = k & 2;
      out[static_cast<std::size_t>(k)] = {right ? 0.5 : 0.0, right ? 1.0 : 0.5, upper ? 0.5 : 0.0, upper ? 1.0 : 0.5,
                                          false};
    }
    return out;
  }
  // Across the pole (s when the pole is at s = 0, s = 1 or both): the strip(s) along it keep the node's whole
  // range along it; the far half (or the middle, between two poles) is halved along it.
  const bool alongS = sLow || sHigh;
  const bool low = alongS ? sLow : tLow, high = alongS ? sHigh : tHigh;
  using Intervals = std::array<std::array<double, 2>, 4>;
  constexpr Intervals kBothPoles{{{0, 0.25}, {0.75, 1}, {0.25, 0.75}, {0.25, 0.75}}};
  constexpr Intervals kLowPole{{{0, 0.25}, {0.25, 0.5}, {0.5, 1}, {0.5, 1}}};
  constexpr Intervals kHighPole{{{0.75, 1}, {0.5, 0.75}, {0, 0.5}, {0, 0.5}}};
  constexpr Intervals kAlong{{{0, 1}, {0, 1}, {0, 0.5}, {0.5, 1}}};
  const Intervals& across = low && high ? kBothPoles : low ? kLowPole : kHighPole;
  for (std::size_t k = 0; k < 4; ++k) {
    const bool pole = k == 0 || (k == 1 && low && high);
    out[k] = alongS ? Piece{across[k][0], across[k][1], kAlong[k][0], kAlong[k][1], pole}
                    : Piece{kAlong[k][0], kAlong[k][1], across[k][0], across[k][1], pole};
  }
  return out;
}

}  // namespace

namespace {

/// The distinct corners of the roots, first occurrences in (root, corner) order (PatchForest::distinctCorners).
std::vector<PatchForest::Corner> distinctCornersOf(const std::vector<std::unique_ptr<PatchNode>>& roots) {
  std::vector<PatchForest::Corner> all;
  for (std::size_t k = 0; k < roots.size(); ++k)
    for (int i = 0; i < 4; ++i) all.push_back({roots[k]->corners[static_cast<std::size_t>(i)], static_cast<int>(k), i});
  const auto byPoint = [](const PatchForest::Corner& a, const PatchForest::Corner& b) {
    if (a.point.x() != b.point.x()) return a.point.x() < b.point.x();
    if (a.point.y() != b.point.y()) return a.point.y() < b.point.y();
    if (a.point.z() != b.point.z()) return a.point.z() < b.point.z();
    return std::make_pair(a.root, a.corner) < std::make_pair(b.root, b.corner);
  };
  std::sort(all.begin(), all.end(), byPoint);
  std::vector<PatchForest::Corner> out;
  for (const PatchForest::Corner& c : all)
    if (out.empty() || out.back().point != c.point) out.push_back(c);  // the first of equal points comes first
  std::sort(out.begin(), out.end(), [](const PatchForest::Corner& a, const PatchForest::Corner& b) {
    return std::make_pair(a.root, a.corner) < std::make_pair(b.root, b.corner);
  });
  return out;
}

}  // namespace

PatchForest::PatchForest(const std::vector<RationalBezierPatch>& patches) {
  for (std::size_t k = 0; k < patches.size(); ++k) {
    roots.push_back(makeNode(patches[k], static_cast<int>(k), 0, 0, 1, 0, 1));
    roots.back()->kept = true;
    maxTerms = std::max(maxTerms, patches[k].net.size());
  }
  nodes = roots.size();
  distinctCorners = distinctCornersOf(roots);
  double size = 0;
  for (const auto& r : roots) size = std::max(size, r->ball.radius);
  constexpr std::array<int, 4> kCornerOfEdge{0, 1, 0, 2};  // a corner on each edge s = 0, s = 1, t = 0, t = 1
  for (std::size_t k = 0; k < roots.size(); ++k) {
    const std::array<bool, 4> collapsed = collapsedEdgesOf(*roots[k]);
    std::array<int, 4>& at = poleOfEdge.emplace_back(std::array<int, 4>{-1, -1, -1, -1});
    for (int e = 0; e < 4; ++e) {
      if (!collapsed[static_cast<std::size_t>(e)]) continue;
      const Eigen::Vector3d& point = roots[k]->corners[static_cast<std::size_t>(kCornerOfEdge[static_cast<std::size_t>(e)])];
      auto same = std::find_if(poles.begin(), poles.end(),
                               [&](const Pole& p) { return (p.point - point).norm() <= kCollapsedEdge * size; });
      if (same == poles.end()) same = poles.insert(poles.end(), Pole{point, {}});
      same->edges.emplace_back(static_cast<int>(k), e);
      at[static_cast<std::size_t>(e)] = static_cast<int>(same - poles.begin());
      roots[k]->fromPole = 0;
    }
  }
}

std::array<const PatchNode*, 4> PatchForest::children(const PatchNode& n,
                                                      std::vector<std::unique_ptr<PatchNode>>& arena) const {
  auto make = [&](std::array<std::unique_ptr<PatchNode>, 4>& out) {
    const std::array<Piece, 4> pieces = piecesOf(n, poleOfEdge[static_cast<std::size_t>(n.patch)]);
    const double ws = n.s1 - n.s0, wt = n.t1 - n.t0;
    for (std::size_t k = 0; k < 4; ++k) {
      const Piece& c = pieces[k];
      RationalBezierPatch piece = restrict(restrict(n.net, 0, c.a0, c.a1), 1, c.b0, c.b1);
      out[k] = makeNode(std::move(piece), n.patch, n.depth + 1, n.s0 + c.a0 * ws, n.s0 + c.a1 * ws, n.t0 + c.b0 * wt,
                        n.t0 + c.b1 * wt);
      out[k]->fromPole = c.pole ? 0 : std::min(n.fromPole + 1, kFarFromPole);
    }
  };
  std::array<const PatchNode*, 4> out{};
  if (keepsChildren(n)) {
    std::call_once(n.childrenOnce, [&] {
      make(n.cached);
      for (auto& c : n.cached) c->kept = true;
      nodes += 4;
      bytes += 4 * (sizeof(PatchNode) + n.net.net.size() * (sizeof(Eigen::Vector4d) + sizeof(Eigen::Vector3d)));
    });
    for (int k = 0; k < 4; ++k) out[static_cast<std::size_t>(k)] = n.cached[static_cast<std::size_t>(k)].get();
    return out;
  }
  std::array<std::unique_ptr<PatchNode>, 4> made;
  make(made);
  for (int k = 0; k < 4; ++k) {
    out[static_cast<std::size_t>(k)] = made[static_cast<std::size_t>(k)].get();
    arena.push_back(std::move(made[static_cast<std::size_t>(k)]));
  }
  return out;
}

}  // namespace unidist::nurbs
