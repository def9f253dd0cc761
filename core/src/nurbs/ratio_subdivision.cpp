#include "nurbs/ratio_subdivision.h"

#include "unidist/nurbs.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cmath>
#include <limits>
#include <memory_resource>
#include <queue>
#include <utility>
#include <vector>

namespace unidist::nurbs {
namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();
constexpr double kAnisotropic = 1.0 / 16;  // one direction's ratios curving at most this fraction of the other's

/// The forms of one piece, stored at `slot` of the pool (a then w), with their bound.
struct Piece {
  double upper;
  int slot, depth;
  bool operator<(const Piece& o) const { return upper < o.upper; }
};

/// Halves the coefficients c (degree (p, q), u-major) at the middle of `direction` by de Casteljau. P, Q: p and q
/// where known at compile time (the loops unrolled), else -1.
template <int P, int Q>
void halveOf(const double* c, int p, int q, int direction, double* left, double* right) {
  if constexpr (P >= 0) p = P;
  if constexpr (Q >= 0) q = Q;
  const int n = direction == 0 ? p : q;
  const int lines = direction == 0 ? q + 1 : p + 1;
  const int along = direction == 0 ? q + 1 : 1, across = direction == 0 ? 1 : q + 1;
  double row[kMaxNurbsDegree + 1];
  for (int l = 0; l < lines; ++l) {
    for (int k = 0; k <= n; ++k) row[k] = c[l * across + k * along];
    left[l * across] = row[0];
    right[l * across + n * along] = row[n];
    for (int r = 1; r <= n; ++r) {
      for (int k = 0; k + r <= n; ++k) row[k] = 0.5 * (row[k] + row[k + 1]);
      left[l * across + r * along] = row[0];
      right[l * across + (n - r) * along] = row[n - r];
    }
  }
}

/// How much the coefficient ratios r (u-major) curve along u and along v: the largest second difference times
/// the degree squared, the bound's slack from that direction.
template <int P, int Q>
std::pair<double, double> curvatureOf(const double* r, int p, int q) {
  if constexpr (P >= 0) p = P;
  if constexpr (Q >= 0) q = Q;
  const auto at = [&](int i, int j) { return r[i * (q + 1) + j]; };
  double alongU = 0, alongV = 0;
  for (int i = 0; i <= p; ++i)
    for (int j = 0; j <= q; ++j) {
      if (i + 2 <= p) alongU = std::max(alongU, std::abs(at(i + 2, j) - 2 * at(i + 1, j) + at(i, j)));
      if (j + 2 <= q) alongV = std::max(alongV, std::abs(at(i, j + 2) - 2 * at(i, j + 1) + at(i, j)));
    }
  return {alongU * p * p, alongV * q * q};
}

// The distance forms of biquadratic and bicubic patches (degrees 4 and 6) are nearly all that is subdivided.
void halve(const double* c, int p, int q, int direction, double* left, double* right) {
  switch (p == q ? p : -1) {
    case 4: return halveOf<4, 4>(c, p, q, direction, left, right);
    case 6: return halveOf<6, 6>(c, p, q, direction, left, right);
    default: return halveOf<-1, -1>(c, p, q, direction, left, right);
  }
}

std::pair<double, double> curvature(const double* r, int p, int q) {
  switch (p == q ? p : -1) {
    case 4: return curvatureOf<4, 4>(r, p, q);
    case 6: return curvatureOf<6, 6>(r, p, q);
    default: return curvatureOf<-1, -1>(r, p, q);
  }
}

/// The coefficient ratios a / w into r.
void ratiosOf(const double* a, const double* w, int terms, double* r) {
  for (int k = 0; k < terms; ++k) r[k] = a[k] / w[k];
}

}  // namespace

RatioBound subdividedRatioBound(int p, int q, const double* a, const double* w, const RatioRefinement& refine) {
  const int terms = (p + 1) * (q + 1);
  double maxA = 0, maxW = 0, minW = std::numeric_limits<double>::infinity();
  for (int k = 0; k < terms; ++k) {
    maxA = std::max(maxA, std::abs(a[k]));
    maxW = std::max(maxW, w[k]);
    minW = std::min(minW, w[k]);
  }
  // The pieces' forms, the heap and the scratch rows on the stack while they fit (the heap beyond): a certificate
  // is asked of several nodes per query and usually ends within a dozen splits.
  std::array<std::byte, 16384> stack;
  std::pmr::monotonic_buffer_resource memory(stack.data(), stack.size());
  std::pmr::vector<double> ratios(static_cast<std::size_t>(terms), &memory);
  ratiosOf(a, w, terms, ratios.data());
  // Not worth splitting when a corner of the square is above `enough` already (g there is its coefficient ratio),
  // or when the ratios curve both ways about as much: halving across one direction at a time then does what the
  // patch tree's quadrants do, at least as many pieces for the same bound.
  double cornerHigh = -std::numeric_limits<double>::infinity();
  for (int k : {0, q, terms - 1 - q, terms - 1}) cornerHigh = std::max(cornerHigh, ratios[static_cast<std::size_t>(k)]);
  const auto [alongU, alongV] = curvature(ratios.data(), p, q);
  if (cornerHigh > refine.enough || std::min(alongU, alongV) > kAnisotropic * std::max(alongU, alongV))
    return {*std::max_element(ratios.begin(), ratios.end()) + refine.allowance, cornerHigh, 0};
  const int budget = std::max(0, refine.budget);
  // A slot holds a piece's a, w and ratios (the ratios kept for the piece's split: no second division).
  const auto stride = static_cast<std::size_t>(3 * terms);
  std::pmr::vector<double> pool(&memory);
  pool.reserve(stride * 20);
  pool.insert(pool.end(), a, a + terms);
  pool.insert(pool.end(), w, w + terms);
  pool.resize(stride);
  int slots = 1;
  double reached = -std::numeric_limits<double>::infinity();
  // A piece's bound: its largest ratio, its corners (exact values of g) noted; rounding of the halvings
  // (each level moves a coefficient by at most (p + q)·ε of the largest) on top of the given allowance.
  const auto bound = [&](int slot, int depth) {
    double* pa = pool.data() + stride * static_cast<std::size_t>(slot);
    const double* pw = pa + terms;
    double* pr = pa + 2 * terms;
    ratiosOf(pa, pw, terms, pr);
    const double upper = *std::max_element(pr, pr + terms);
    for (int k : {0, q, terms - 1 - q, terms - 1}) reached = std::max(reached, pr[k]);
    const double halving = 2 * depth * (p + q) * kEps * (maxA + std::abs(upper) * maxW) / minW;
    return Piece{upper + refine.allowance + halving, slot, depth};
  };
  std::priority_queue<Piece, std::pmr::vector<Piece>> open{std::less<Piece>(), std::pmr::vector<Piece>(&memory)};
  open.push(bound(0, 0));
  int splits = 0;
  std::pmr::vector<double> left(static_cast<std::size_t>(2 * terms), &memory);
  while (true) {
    const Piece top = open.top();
    // Done when enough, when a corner already shows the bound cannot get there, or when the pieces are exact
    // but for rounding.
    if (top.upper <= refine.enough || reached > refine.enough || splits >= budget ||
        top.upper - reached <= refine.allowance + 2 * top.depth * (p + q) * kEps * (maxA + std::abs(reached) * maxW) / minW)
      return {top.upper, reached, splits};
    open.pop();
    ++splits;
    pool.resize(stride * static_cast<std::size_t>(slots + 1));
    double* pa = pool.data() + stride * static_cast<std::size_t>(top.slot);
    double* pw = pa + terms;
    const auto [curvedU, curvedV] = curvature(pa + 2 * terms, p, q);
    const int direction = curvedU > curvedV ? 0 : 1;
    double* ra = pool.data() + stride * static_cast<std::size_t>(slots);
    double* rw = ra + terms;
    halve(pa, p, q, direction, left.data(), ra);
    halve(pw, p, q, direction, left.data() + terms, rw);
    std::copy(left.begin(), left.end(), pa);  // the left half reuses its parent's slot
    open.push(bound(top.slot, top.depth + 1));
    open.push(bound(slots++, top.depth + 1));
  }
}

}  // namespace unidist::nurbs
