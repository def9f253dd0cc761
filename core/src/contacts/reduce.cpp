#include "contacts/reduce.h"

#include <algorithm>
#include <limits>
#include <tuple>

namespace unidist::contact {
namespace {

bool deeperFirst(const Contact& x, const Contact& y) {
  if (x.distance != y.distance) return x.distance < y.distance;
  return std::make_tuple(x.pointA.x(), x.pointA.y(), x.pointA.z(), x.pointB.x(), x.pointB.y(), x.pointB.z()) <
         std::make_tuple(y.pointA.x(), y.pointA.y(), y.pointA.z(), y.pointB.x(), y.pointB.y(), y.pointB.z());
}

Eigen::Vector3d middle(const Contact& c) { return 0.5 * (c.pointA + c.pointB); }

}  // namespace

void mergeDuplicates(std::vector<Contact>& cs, double eps) {
  std::sort(cs.begin(), cs.end(), deeperFirst);
  // Compacted in place (the kept ones are a prefix): the simulation merges a few contacts per pair every step.
  std::size_t kept = 0;
  for (std::size_t i = 0; i < cs.size(); ++i) {
    const Contact& c = cs[i];
    const bool duplicate = std::any_of(cs.begin(), cs.begin() + long(kept), [&](const Contact& k) {
      return (k.pointA - c.pointA).norm() <= eps && (k.pointB - c.pointB).norm() <= eps;
    });
    if (!duplicate) cs[kept++] = c;
  }
  cs.resize(kept);
}

void reduceContacts(std::vector<Contact>& cs, int maxContacts) {
  const std::size_t n = static_cast<std::size_t>(maxContacts);
  if (cs.size() <= n) return;
  std::sort(cs.begin(), cs.end(), deeperFirst);
  std::vector<double> gap(cs.size(), std::numeric_limits<double>::infinity());
  std::vector<char> taken(cs.size(), 0);
  std::size_t next = 0;  // the deepest
  for (std::size_t k = 0; k < n; ++k) {
    taken[next] = 1;
    std::size_t far = next;
    double farGap = -1;
    for (std::size_t i = 0; i < cs.size(); ++i) {
      if (taken[i]) continue;
      gap[i] = std::min(gap[i], (middle(cs[i]) - middle(cs[next])).norm());
      if (gap[i] > farGap) farGap = gap[i], far = i;
    }
    next = far;
  }
  std::vector<Contact> kept;
  for (std::size_t i = 0; i < cs.size(); ++i)
    if (taken[i]) kept.push_back(cs[i]);
  cs.swap(kept);
}

}  // namespace unidist::contact
