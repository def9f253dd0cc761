// The patch forest: its roots, the poles (patch edges collapsed to a point) and distinct corners found with them,
// and how a node is cut into its children (quadrants, or strips along a pole).
#include "nurbs/patch_tree.h"

#include <algorithm>
#include <stdexcept>

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

/// The four pieces of n (see PatchForest::children), in n's local parameters.
std::array<Piece, 4> piecesOf(const PatchNode& n, const std::array<bool, 4>& collapsed) {
  const bool sLow = n.s0 == 0 && collapsed[0], sHigh = n.s1 == 1 && collapsed[1];
  const bool tLow = n.t0 == 0 && collapsed[2], tHigh = n.t1 == 1 && collapsed[3];
  std::array<Piece, 4> out;
  if (!sLow && !sHigh && !tLow && !tHigh) {
    for (int k = 0; k < 4; ++k) {
      const bool right = k & 1, upper = k & 2;
      out[static_cast<std::size_t>(k)] = {right ? 0.5 : 0.0, right ? 1.0 : 0.5, upper ? 0.5 : 0.0, upper ? 1.0 : 0.5,
                                          false};
    }
    return out;
  }
  // Along s (the pole at s = 0, s = 1 or both): the strip(s) along the pole keep the node's whole t range.
  const bool alongS = sLow || sHigh;
  const bool low = alongS ? sLow : tLow, high = alongS ? sHigh : tHigh;
  std::array<std::array<double, 2>, 4> cut;  // the pieces' intervals across the pole, then along it
  std::array<std::array<double, 2>, 4> along;
  std::array<bool, 4> pole;
  if (low && high) {
    cut = {{{0, 0.25}, {0.75, 1}, {0.25, 0.75}, {0.25, 0.75}}};
    along = {{{0, 1}, {0, 1}, {0, 0.5}, {0.5, 1}}};
    pole = {true, true, false, false};
  } else if (low) {
    cut = {{{0, 0.25}, {0.25, 0.5}, {0.5, 1}, {0.5, 1}}};
    along = {{{0, 1}, {0, 1}, {0, 0.5}, {0.5, 1}}};
    pole = {true, false, false, false};
  } else {
    cut = {{{0.75, 1}, {0.5, 0.75}, {0, 0.5}, {0, 0.5}}};
    along = {{{0, 1}, {0, 1}, {0, 0.5}, {0.5, 1}}};
    pole = {true, false, false, false};
  }
  for (std::size_t k = 0; k < 4; ++k)
    out[k] = alongS ? Piece{cut[k][0], cut[k][1], along[k][0], along[k][1], pole[k]}
                    : Piece{along[k][0], along[k][1], cut[k][0], cut[k][1], pole[k]};
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
    collapsedEdges.push_back(collapsedEdgesOf(*roots.back()));
    const std::array<bool, 4>& c = collapsedEdges.back();
    roots.back()->pole = c[0] || c[1] || c[2] || c[3];
    if (roots.back()->pole) roots.back()->fromPole = 0;
  }
  nodes = roots.size();
  distinctCorners = distinctCornersOf(roots);
  double size = 0;
  for (const auto& r : roots) size = std::max(size, r->ball.radius);
  constexpr std::array<int, 4> kCornerOfEdge{0, 1, 0, 2};  // a corner on each edge s = 0, s = 1, t = 0, t = 1
  for (std::size_t k = 0; k < roots.size(); ++k)
    for (int e = 0; e < 4; ++e) {
      if (!collapsedEdges[k][static_cast<std::size_t>(e)]) continue;
      const auto corner = static_cast<std::size_t>(kCornerOfEdge[static_cast<std::size_t>(e)]);
      const Eigen::Vector3d& at = roots[k]->corners[corner];
      auto same = std::find_if(poles.begin(), poles.end(),
                               [&](const Pole& p) { return (p.point - at).norm() <= kCollapsedEdge * size; });
      if (same == poles.end()) same = poles.insert(poles.end(), Pole{at, {}});
      same->edges.emplace_back(static_cast<int>(k), e);
    }
}

const PatchForest::Pole& PatchForest::poleOf(int patch, int edge) const {
  for (const Pole& p : poles)
    if (std::find(p.edges.begin(), p.edges.end(), std::make_pair(patch, edge)) != p.edges.end()) return p;
  throw std::logic_error("PatchForest::poleOf: not a collapsed edge");
}

std::array<const PatchNode*, 4> PatchForest::children(const PatchNode& n,
                                                      std::vector<std::unique_ptr<PatchNode>>& arena) const {
  auto make = [&](std::array<std::unique_ptr<PatchNode>, 4>& out) {
    const std::array<Piece, 4> pieces = piecesOf(n, collapsedEdges[static_cast<std::size_t>(n.patch)]);
    const double ws = n.s1 - n.s0, wt = n.t1 - n.t0;
    for (std::size_t k = 0; k < 4; ++k) {
      const Piece& c = pieces[k];
      RationalBezierPatch piece = restrict(restrict(n.net, 0, c.a0, c.a1), 1, c.b0, c.b1);
      out[k] = makeNode(std::move(piece), n.patch, n.depth + 1, n.s0 + c.a0 * ws, n.s0 + c.a1 * ws, n.t0 + c.b0 * wt,
                        n.t0 + c.b1 * wt);
      out[k]->pole = c.pole;
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
