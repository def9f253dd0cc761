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

/// Halves one line of n + 1 coefficients (`stride` apart) at its middle by de Casteljau. N: n where known at
/// compile time (the triangle then stays in registers: the halvings are a third of a circle of minima's time).
template <int N>
void halveLine(const double* c, int n, int stride, double* left, double* right) {
  if constexpr (N >= 0) n = N;
  double row[(N >= 0 ? N : kMaxNurbsDegree) + 1] = {};
  for (int k = 0; k <= n; ++k) row[k] = c[k * stride];
  left[0] = row[0];
  right[n * stride] = row[n];
  for (int r = 1; r <= n; ++r) {
    for (int k = 0; k + r <= n; ++k) row[k] = 0.5 * (row[k] + row[k + 1]);
    left[r * stride] = row[0];
    right[(n - r) * stride] = row[n - r];
  }
}

/// Degree 4 (a biquadratic patch's distance form) written out: the loop's row, kept on the stack and read back
/// two lanes at a time, stalled on every store it had just made (a third of a circle of minima's time). The same
/// operations in the same order, so the same bits.
template <>
void halveLine<4>(const double* c, int, int stride, double* left, double* right) {
  const double b0 = c[0], b1 = c[stride], b2 = c[2 * stride], b3 = c[3 * stride], b4 = c[4 * stride];
  const double c0 = 0.5 * (b0 + b1), c1 = 0.5 * (b1 + b2), c2 = 0.5 * (b2 + b3), c3 = 0.5 * (b3 + b4);
  const double d0 = 0.5 * (c0 + c1), d1 = 0.5 * (c1 + c2), d2 = 0.5 * (c2 + c3);
  const double e0 = 0.5 * (d0 + d1), e1 = 0.5 * (d1 + d2);
  const double f0 = 0.5 * (e0 + e1);
  left[0] = b0, left[stride] = c0, left[2 * stride] = d0, left[3 * stride] = e0, left[4 * stride] = f0;
  right[0] = f0, right[stride] = e1, right[2 * stride] = d2, right[3 * stride] = c3, right[4 * stride] = b4;
}

/// Halves the coefficients c (degree (p, q), u-major) at the middle of `direction`, line by line.
template <int N>
void halveLines(const double* c, int p, int q, int direction, double* left, double* right) {
  const int n = direction == 0 ? p : q;
  const int lines = direction == 0 ? q + 1 : p + 1;
  const int along = direction == 0 ? q + 1 : 1, across = direction == 0 ? 1 : q + 1;
  for (int l = 0; l < lines; ++l)
    halveLine<N>(c + l * across, n, along, left + l * across, right + l * across);
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
  switch (direction == 0 ? p : q) {
    case 4: return halveLines<4>(c, p, q, direction, left, right);
    case 6: return halveLines<6>(c, p, q, direction, left, right);
    default: return halveLines<-1>(c, p, q, direction, left, right);
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
  // is asked of several nodes per query and usually ends within a dozen splits. A slot holds a piece's a, w and
  // ratios (the ratios kept for the piece's split: no second division).
  std::array<std::byte, 16384> stack;
  std::pmr::monotonic_buffer_resource memory(stack.data(), stack.size());
  const auto stride = static_cast<std::size_t>(3 * terms);
  std::pmr::vector<double> pool(&memory);
  pool.reserve(stride * 20);
  pool.insert(pool.end(), a, a + terms);
  pool.insert(pool.end(), w, w + terms);
  pool.resize(stride);
  const auto ratiosAt = [&](int slot) {
    double* pa = pool.data() + stride * static_cast<std::size_t>(slot);
    ratiosOf(pa, pa + terms, terms, pa + 2 * terms);
    return pa + 2 * terms;
  };
  const double* rootRatios = ratiosAt(0);
  // Not worth splitting when a corner of the square is above `enough` already (g there is its coefficient ratio),
  // or when the ratios curve both ways about as much: halving across one direction at a time then does what the
  // patch tree's quadrants do, at least as many pieces for the same bound.
  double cornerHigh = -std::numeric_limits<double>::infinity();
  for (int k : {0, q, terms - 1 - q, terms - 1}) cornerHigh = std::max(cornerHigh, rootRatios[k]);
  const auto [alongU, alongV] = curvature(rootRatios, p, q);
  if (cornerHigh > refine.enough || std::min(alongU, alongV) > kAnisotropic * std::max(alongU, alongV))
    return {*std::max_element(rootRatios, rootRatios + terms) + refine.allowance, cornerHigh, 0};
  const int budget = std::max(0, refine.budget);
  int slots = 1;
  double reached = -std::numeric_limits<double>::infinity();
  // A piece's bound from its ratios: the largest, its corners (exact values of g) noted; rounding of the halvings
  // (each level moves a coefficient by at most (p + q)·ε of the largest) on top of the given allowance.
  const auto bound = [&](int slot, int depth, const double* ratios) {
    const double upper = *std::max_element(ratios, ratios + terms);
    for (int k : {0, q, terms - 1 - q, terms - 1}) reached = std::max(reached, ratios[k]);
    const double halving = 2 * depth * (p + q) * kEps * (maxA + std::abs(upper) * maxW) / minW;
    return Piece{upper + refine.allowance + halving, slot, depth};
  };
  std::priority_queue<Piece, std::pmr::vector<Piece>> open{std::less<Piece>(), std::pmr::vector<Piece>(&memory)};
  open.push(bound(0, 0, rootRatios));
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
    open.push(bound(top.slot, top.depth + 1, ratiosAt(top.slot)));
    open.push(bound(slots, top.depth + 1, ratiosAt(slots)));
    ++slots;
  }
}

}  // namespace unidist::nurbs
