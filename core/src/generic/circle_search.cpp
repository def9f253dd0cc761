#include "generic/circle_search.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <queue>
#include <vector>

namespace unidist::detail {
namespace {

constexpr double kTwoPi = 6.283185307179586476925286766559;
// Enough root intervals that the coarse level already separates the basins of a torus pair.
constexpr int kRootIntervals = 64;
// Below this half-width rounding in θ dominates any bound: such intervals are not split further.
constexpr double kMinHalfWidth = 1e-15;

struct Interval {
  double mid, halfWidth;
  AngleSample at;
  double lower;
  bool operator>(const Interval& o) const { return lower > o.lower; }
};

/// Best-first interval search shared by both queries; `done(best, top)` decides when to stop.
class AngleSearch {
 public:
  AngleSearch(const AngleFunction& g, double lipschitz) : g_(g), lipschitz_(lipschitz) {
    for (int i = 0; i < kRootIntervals; ++i) push((i + 0.5) * kTwoPi / kRootIntervals, 0.5 * kTwoPi / kRootIntervals);
  }

  /// Splits the lowest interval until `prune(lowest bound)` holds or the budget is spent; true if pruned.
  template <class Prune>
  bool run(Prune prune, int maxEvaluations) {
    while (!open_.empty()) {
      const Interval top = open_.top();
      if (prune(top.lower)) return true;
      if (evaluations_ + 2 > maxEvaluations || top.halfWidth < kMinHalfWidth) return false;
      open_.pop();
      const double h = 0.5 * top.halfWidth;
      push(top.mid - h, h);
      push(top.mid + h, h);
    }
    return true;
  }

  double lowest() const { return open_.empty() ? bestValue_ : std::min(bestValue_, open_.top().lower); }
  double bestValue() const { return bestValue_; }
  double bestTheta() const { return bestTheta_; }
  int evaluations() const { return evaluations_; }

 private:
  void push(double mid, double h) {
    const AngleSample s = g_(mid, h);
    ++evaluations_;
    double lower = s.value - lipschitz_ * h;
    if (s.curvature >= 0) lower = std::max(lower, s.value - std::abs(s.slope) * h - 0.5 * s.curvature * h * h);
    if (s.value < bestValue_) {
      bestValue_ = s.value;
      bestTheta_ = mid;
    }
    open_.push({mid, h, s, lower});
  }

  const AngleFunction& g_;
  double lipschitz_;
  std::priority_queue<Interval, std::vector<Interval>, std::greater<Interval>> open_;
  double bestValue_ = std::numeric_limits<double>::infinity();
  double bestTheta_ = 0;
  int evaluations_ = 0;
};

}  // namespace

AngleMinimum minimizeOverAngle(const AngleFunction& g, double lipschitz, double tolerance, int maxEvaluations) {
  AngleSearch search(g, lipschitz);
  search.run([&](double lower) { return lower >= search.bestValue() - tolerance; }, maxEvaluations);
  AngleMinimum m;
  m.theta = search.bestTheta();
  m.value = search.bestValue();
  m.lowerBound = search.lowest();
  m.evaluations = search.evaluations();
  m.certified = m.value - m.lowerBound <= tolerance;
  return m;
}

bool provesAbove(const AngleFunction& g, double lipschitz, double threshold, int maxEvaluations) {
  AngleSearch search(g, lipschitz);
  if (search.bestValue() < threshold) return false;
  return search.run([&](double lower) { return lower >= threshold || search.bestValue() < threshold; },
                    maxEvaluations) &&
         search.bestValue() >= threshold;
}

}  // namespace unidist::detail
