#include "nurbs/start_set.h"

namespace unidist::nurbs {
namespace {

std::shared_ptr<const StartSet> makeStartSet(const PatchForest& forest) {
  auto out = std::make_shared<StartSet>();
  std::size_t count = forest.roots.size();
  while (out->depth < kCachedDepth && 4 * count <= kMaxStartNodes) {
    ++out->depth;
    count *= 4;
  }
  const int cells = 1 << out->depth, side = cells + 1;
  std::vector<std::unique_ptr<PatchNode>> arena;  // stays empty: the cut is within the cached depth
  const std::size_t samples = forest.roots.size() * static_cast<std::size_t>(side * side);
  out->samples.reserve(samples);
  out->nodes.reserve(count);
  for (std::vector<double>* v : {&out->px, &out->py, &out->pz}) v->reserve(samples);
  for (std::vector<double>* v : {&out->cx, &out->cy, &out->cz, &out->radius}) v->reserve(count);
  std::vector<Eigen::Vector3d> points;
  for (const auto& root : forest.roots) {
    const std::size_t first = out->samples.size();
    for (int i = 0; i < side; ++i)
      for (int j = 0; j < side; ++j) out->samples.push_back({root->patch, double(i) / cells, double(j) / cells});
    // The grid is evaluated on the patch itself: next to a pole the cut's nodes are strips, not grid cells.
    for (std::size_t k = first; k < out->samples.size(); ++k)
      points.push_back(root->net.evaluate(out->samples[k].s, out->samples[k].t));
    std::vector<const PatchNode*> stack{root.get()};
    while (!stack.empty()) {
      const PatchNode* n = stack.back();
      stack.pop_back();
      if (n->depth < out->depth) {
        for (const PatchNode* c : forest.children(*n, arena)) stack.push_back(c);
        continue;
      }
      out->nodes.push_back(n);
    }
  }
  for (const Eigen::Vector3d& p : points) {
    out->px.push_back(p.x());
    out->py.push_back(p.y());
    out->pz.push_back(p.z());
  }
  for (const PatchNode* n : out->nodes) {
    out->cx.push_back(n->ball.center.x());
    out->cy.push_back(n->ball.center.y());
    out->cz.push_back(n->ball.center.z());
    out->radius.push_back(n->ball.radius);
  }
  forest.bytes += out->bytes();
  return out;
}

}  // namespace

const StartSet& startSet(const PatchForest& forest) {
  std::call_once(forest.startOnce, [&forest] { forest.start = makeStartSet(forest); });
  return *forest.start;
}

}  // namespace unidist::nurbs
