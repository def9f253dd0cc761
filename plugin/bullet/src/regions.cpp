#include "regions.h"

#include <algorithm>

namespace unidist::bullet {
namespace {

Eigen::Vector3d middle(const Contact& c) { return 0.5 * (c.pointA + c.pointB); }

/// Cuts a group of indices (into cs) in two at the widest gap along its longest axis.
std::pair<std::vector<int>, std::vector<int>> cut(const std::vector<Contact>& cs, std::vector<int> group) {
  Aabb box;
  for (int i : group) box.extend(middle(cs[std::size_t(i)]));
  int axis = 0;
  (box.max - box.min).maxCoeff(&axis);
  std::sort(group.begin(), group.end(), [&](int x, int y) {
    return middle(cs[std::size_t(x)])[axis] < middle(cs[std::size_t(y)])[axis];
  });
  std::size_t at = 1;
  double widest = -1;
  for (std::size_t k = 1; k < group.size(); ++k) {
    const double gap = middle(cs[std::size_t(group[k])])[axis] - middle(cs[std::size_t(group[k - 1])])[axis];
    if (gap > widest) widest = gap, at = k;
  }
  return {std::vector<int>(group.begin(), group.begin() + long(at)), std::vector<int>(group.begin() + long(at), group.end())};
}

}  // namespace

std::vector<std::vector<Contact>> contactRegions(const std::vector<Contact>& deepestFirst, int maxGroups) {
  std::vector<std::vector<int>> groups;
  std::vector<int> all(deepestFirst.size());
  for (std::size_t i = 0; i < all.size(); ++i) all[i] = int(i);
  if (!all.empty()) groups.push_back(all);
  for (bool split = true; split;) {
    split = false;
    for (std::size_t g = 0; g < groups.size(); ++g) {
      if (groups[g].size() <= 4) continue;
      auto [left, right] = cut(deepestFirst, groups[g]);
      groups[g] = left;
      groups.push_back(right);
      split = true;
      break;
    }
  }
  for (auto& g : groups) std::sort(g.begin(), g.end());  // indices ascending = deepest first
  std::sort(groups.begin(), groups.end(), [](const std::vector<int>& x, const std::vector<int>& y) { return x[0] < y[0]; });
  if (int(groups.size()) > maxGroups) groups.resize(std::size_t(maxGroups));
  std::vector<std::vector<Contact>> out;
  for (const auto& g : groups) {
    out.emplace_back();
    for (int i : g) out.back().push_back(deepestFirst[std::size_t(i)]);
  }
  return out;
}

}  // namespace unidist::bullet
