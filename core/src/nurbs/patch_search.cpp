#include "nurbs/patch_search.h"
#include "nurbs/gradient_sign.h"
#include "nurbs/start_set.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <cmath>
#include <functional>
#include <memory>
#include <memory_resource>
#include <queue>

namespace unidist::nurbs {
namespace {

constexpr int kTightBoundDepth = 4;  // pieces this deep get the Bernstein lower bound before a split
constexpr int kMaxDepth = 40;          // beyond this a node is a leaf whatever its size (subdivision has stalled)
constexpr double kLeafFraction = 0.5;  // leaf: radius below this fraction of the objective's scale...
constexpr double kLeafAngle = 0.5;    // ...and a normal cone narrower than this (rad): Newton converges there
constexpr int kNewtonSteps = 60;
constexpr int kNearPole = 4;        // levels below a pole's strip that still try proofs below the cached depth
constexpr double kDistinctTie = 1e-3;  // of the distance: Newton ends this far apart with one value are a tie
constexpr int kCertSplits = 3;        // levels a piece that fails its certificate is split before it is trusted
// The search's buffers: sized for an ordinary query (tens of nodes open, a few hits and runs).
constexpr std::size_t kStackBytes = 12 * 1024;
constexpr std::size_t kExpectedHits = 32, kExpectedRuns = 8, kExpectedOpen = 128;

struct Open {
  double lower;
  const PatchNode* node;
  int certSplits = 0;  // levels split since an ancestor failed its certificate (below)
  bool operator>(const Open& o) const { return lower > o.lower; }
};

}  // namespace

void Objective::startRanks(const StartSet& start, double* out) const {
  for (std::size_t k = 0; k < start.samples.size(); ++k) out[k] = rank(start.point(k));
}

void Objective::startBounds(const StartSet& start, double below, double* out) const {
  for (std::size_t k = 0; k < start.nodes.size(); ++k) {
    const double lb = lowerBound(*start.nodes[k]);
    out[k] = lb < below ? lb : std::numeric_limits<double>::infinity();
  }
}

namespace {

// What a hit keeps of its last evaluation: the normal (for the sign; left out at a pole) and the gradient with its
// rounding (basinBound's tangent plane).
void keepEvaluation(const Objective& f, const SurfaceDerivatives& d, PatchHit& hit) {
  if (!unitNormal(d, hit.normal)) hit.normal.setZero();
  Eigen::Matrix2d H;
  f.derivatives(d, hit.gradient, H);
  hit.gradientError = f.gradientError(d);
}

// Steps::AlongGradient: far from the surface (a probe 100 sizes away) the distance varies along it by less than
// its own rounding within 1e-4 of the minimum on a ball of radius 150; a step that leaves the value within these
// ulps and halves the gradient is taken.
constexpr double kValueUlps = 4;

bool smallerGradient(const Objective& f, const SurfaceDerivatives& at, const Eigen::Vector2d& than) {
  Eigen::Vector2d g;
  Eigen::Matrix2d H;
  f.derivatives(at, g, H);
  return g.norm() < 0.5 * than.norm();
}

}  // namespace

PatchHit pointAt(const RationalBezierPatch& patch, int index, const Objective& f, double s, double t) {
  const SurfaceDerivatives d = patch.derivatives(s, t);
  PatchHit hit{index, s, t, f.value(d.point), d.point};
  keepEvaluation(f, d, hit);
  return hit;
}

PatchHit polish(const RationalBezierPatch& patch, int index, const Objective& f, double s, double t, const ParamBox& box,
                Steps steps) {
  PatchHit hit;
  hit.patch = index;
  const Eigen::Vector2d lo(box.s0, box.t0), hi(box.s1, box.t1);
  Eigen::Vector2d x = Eigen::Vector2d(s, t).cwiseMax(lo).cwiseMin(hi);
  SurfaceDerivatives d = patch.derivatives(x[0], x[1]);
  double value = f.value(d.point);
  for (int step = 0; step < kNewtonSteps; ++step) {
    Eigen::Vector2d g;
    Eigen::Matrix2d H;
    f.derivatives(d, g, H);
    // Active set: a variable at its bound whose descent direction leaves the box stays fixed.
    const bool fixU = (x[0] <= box.s0 && g[0] > 0) || (x[0] >= box.s1 && g[0] < 0);
    const bool fixV = (x[1] <= box.t0 && g[1] > 0) || (x[1] >= box.t1 && g[1] < 0);
    if (fixU && fixV) break;
    Eigen::Matrix2d metric;  // first fundamental form: positive definite on a regular surface
    metric << d.du.dot(d.du), d.du.dot(d.dv), d.du.dot(d.dv), d.dv.dot(d.dv);
    auto solve = [&](const Eigen::Matrix2d& M, Eigen::Vector2d& out) {
      if (fixU || fixV) {
        const int k = fixU ? 1 : 0;
        if (!(M(k, k) > 0)) return false;
        out.setZero();
        out[k] = -g[k] / M(k, k);
        return true;
      }
      const double det = M.determinant();
      if (!(det > 1e-14 * M.squaredNorm()) || !(M(0, 0) > 0)) return false;
      out = -M.inverse() * g;
      return true;
    };
    Eigen::Vector2d delta;
    if (!solve(H, delta) && !solve(metric, delta)) {
      // Degenerate metric (a pole): a plain gradient step scaled by the metric's size.
      const double scale = std::max(metric.trace(), 1e-300);
      delta = -g / scale;
      if (fixU) delta[0] = 0;
      if (fixV) delta[1] = 0;
    }
    // A step below the parameter resolution changes nothing any more (and the line search below would only
    // burn evaluations on rounding noise).
    if (!delta.allFinite() || delta.cwiseAbs().maxCoeff() < 1e-13) break;
    // Backtracking: accept the first (halved) step that decreases the objective.
    bool accepted = false;
    double lambda = 1;
    // A short step that does not decrease the objective is at rounding level: converged, no halving.
    const int halvings = delta.cwiseAbs().maxCoeff() < 1e-6 ? 1 : 30;
    for (int h = 0; h < halvings && !accepted; ++h, lambda *= 0.5) {
      const Eigen::Vector2d trial = (x + lambda * delta).cwiseMax(lo).cwiseMin(hi);
      if (trial == x) break;
      const SurfaceDerivatives dt = patch.derivatives(trial[0], trial[1]);
      const double vt = f.value(dt.point);
      if (vt < value || (steps == Steps::AlongGradient && vt <= value + kValueUlps * std::numeric_limits<double>::epsilon() * std::abs(value) &&
                         smallerGradient(f, dt, g))) {
        accepted = true;
        const double moved = (trial - x).cwiseAbs().maxCoeff();
        x = trial;
        d = dt;
        value = vt;
        if (moved < 1e-15) step = kNewtonSteps;  // converged to the last bit
      }
    }
    if (!accepted) break;
  }
  hit.s = x[0];
  hit.t = x[1];
  hit.value = value;
  hit.point = d.point;
  keepEvaluation(f, d, hit);
  return hit;
}

SearchResult minimise(const PatchForest& forest, const std::vector<RationalBezierPatch>& patches, const Objective& f,
                      double requested, double tieTolerance, int skip, int only) {
  SearchResult out;
  double tolerance = requested;  // raised to the objective's resolution once the seed is known (below)
  const auto excluded = [skip, only](int patch) { return patch == skip || (only >= 0 && patch != only); };
  out.best.value = std::numeric_limits<double>::infinity();
  // The query's buffers on the stack, spilling to the heap only in a long search.
  std::array<std::byte, kStackBytes> stack;
  std::pmr::monotonic_buffer_resource memory(stack.data(), stack.size());
  std::pmr::vector<PatchHit> hits(&memory), polished(&memory);
  hits.reserve(kExpectedHits);
  polished.reserve(kExpectedRuns);
  double keep = std::numeric_limits<double>::infinity();  // rank below which a point ties with the best
  // A Newton end tying with the best far from it: a continuum of minima (a ring's axis seen by a point on it),
  // along which no bound of a piece holding the tie prunes it, and pieces get split down to the premise.
  bool tiesSeen = false, closingFailed = false;
  auto offer = [&](const PatchHit& h) {
    hits.push_back(h);
    if (!tiesSeen && std::abs(h.value - out.best.value) <= tolerance &&
        (h.point - out.best.point).norm() > kDistinctTie * std::max(h.value, tolerance))
      tiesSeen = true;
    if (h.value < out.best.value) {
      out.best = h;
      keep = f.rankOf(out.best.value + tieTolerance);
    }
  };
  auto offerCorners = [&](const PatchNode& n) {
    const double s[4] = {n.s0, n.s1, n.s0, n.s1}, t[4] = {n.t0, n.t0, n.t1, n.t1};
    for (int k = 0; k < 4; ++k) {
      const Eigen::Vector3d& c = n.corners[static_cast<std::size_t>(k)];
      if (f.rank(c) < keep) offer({n.patch, s[k], t[k], f.value(c), c});
    }
  };

  double closedBound = std::numeric_limits<double>::infinity();  // of the pieces closed without a proof
  std::pmr::vector<Open> heap(&memory);
  heap.reserve(kExpectedOpen);
  std::priority_queue<Open, std::pmr::vector<Open>, std::greater<Open>> open(std::greater<Open>(), std::move(heap));
  std::vector<std::unique_ptr<PatchNode>> arena;  // nodes below the cached depth, freed after the search
  // Seed: every point of the start grid is offered (patch corners among them), and Newton runs from the best,
  // so that the bound prunes from the start. Only a start: the search below proves or improves it.
  const StartSet& start = startSet(forest);
  const std::size_t samples = start.samples.size();
  std::pmr::vector<double> values(std::max(samples, start.nodes.size()), &memory);
  f.startRanks(start, values.data());
  if (skip >= 0 || only >= 0)
    for (std::size_t k = 0; k < samples; ++k)
      if (excluded(start.samples[k].patch)) values[k] = std::numeric_limits<double>::infinity();
  // Plain locals in the loops (the offers write `keep` and the buffers through references the compiler must
  // otherwise reload).
  const double* ranks = values.data();
  std::size_t seed = 0;
  double least = samples > 0 ? ranks[0] : std::numeric_limits<double>::infinity();
  for (std::size_t k = 1; k < samples; ++k)
    if (ranks[k] < least) {
      least = ranks[k];
      seed = k;
    }
  if (least < std::numeric_limits<double>::infinity()) {
    const auto offerSample = [&](std::size_t k) {
      const Eigen::Vector3d p = start.point(k);
      offer({start.samples[k].patch, start.samples[k].s, start.samples[k].t, f.value(p), p});
    };
    offerSample(seed);
    const double ties = keep;  // no other sample is better than the seed, so the threshold stays
    for (std::size_t k = 0; k < samples; ++k)
      if (ranks[k] < ties && k != seed) offerSample(k);
    const StartSet::Sample& at = start.samples[seed];
    polished.push_back(polish(patches[static_cast<std::size_t>(at.patch)], at.patch, f, at.s, at.t));
    offer(polished.back());
  }
  if (out.best.value < std::numeric_limits<double>::infinity())
    tolerance = std::max(tolerance, f.resolution(out.best.value, forest.maxTerms));
  f.startBounds(start, out.best.value - tolerance, values.data());
  for (std::size_t k = 0; k < start.nodes.size(); ++k)
    if (values[k] < out.best.value - tolerance && !excluded(start.nodes[k]->patch)) open.push({values[k], start.nodes[k], 0});
  while (!open.empty()) {
    const Open top = open.top();
    if (top.lower >= out.best.value - tolerance) break;
    open.pop();
    const PatchNode& n = *top.node;
    if (++out.nodes > kNurbsSearchBudget) {
      out.exhausted = true;
      out.lowerBound = std::min(top.lower, out.best.value);
      break;
    }
    // Its minimum is on its border (a neighbour's) or at a patch corner (evaluated as nodes appear).
    if (!mayHoldCritical(n, f.criticalDirections(n.ball), false)) continue;
    // Deep pieces that cannot improve on the best by the tolerance (a Bernstein bound: every piece ties at the
    // centre of a sphere, where balls never prune, and the search would split them all down to the tolerance),
    // except around the best point, whose neighbours hold the ties a caller may ask for (the point query no
    // longer does: NurbsModel finds the faces at an edge itself). Shallow pieces are left to the balls: pruning
    // them early measured slower overall (the depth search's witnesses change), and an ordinary query is done
    // before this depth. Next to a pole the pieces around the best point are bounded too (unless ties are asked
    // for): far from the model every one of them ties with it to rounding, and would be split on.
    if (n.depth >= kTightBoundDepth &&
        ((out.best.point - n.ball.center).norm() > n.ball.radius + tieTolerance ||
         (tieTolerance == 0 && n.fromPole <= kNearPole)) &&
        f.tightLowerBound(n) >= out.best.value - tolerance)
      continue;
    // Along a continuum of ties a piece away from the best is settled at once by its closing bound (for the
    // distance: its forms subdivided across the continuum only), instead of being split level by level and
    // closed piece by piece: a point on a ring's axis took 15M instructions. Not after one such bound fails:
    // then the continuum is not one it settles (a point on a torus's core circle, the tube's cross-section
    // all round it), and each try would cost its whole subdivision.
    if (tiesSeen && !closingFailed && f.provesBasins() && n.depth < kTightBoundDepth &&
        (out.best.point - n.ball.center).norm() > n.ball.radius + tieTolerance) {
      if (f.quickClosingBound(n, out.best.value - tolerance) >= out.best.value - tolerance) continue;
      closingFailed = true;
    }
    const bool flat = !n.normal.all && n.normal.angle <= kLeafAngle && n.ball.radius <= kLeafFraction * f.leafScale(n.ball);
    const bool tiny = n.depth >= kMaxDepth || n.ball.radius <= tolerance;
    if (flat || tiny) {
      // A piece whose gradient proves it holds no minimum of its own is closed without a run (gradient_sign.h).
      // Otherwise a Newton run from its centre. A run that ended inside the piece (or on one of its corners: at
      // a pole every s is the same point) found its minimum where the objective is proved convex over the piece,
      // or its least value is proved to be on the patch edge the run ended on; otherwise the piece's quarters are
      // searched, as when the run leaves it. Both prove nothing across a continuum of minima (a circle of them
      // around a torus's core circle, a sphere's centre or pole), where splitting would go on down to the
      // tolerance: such a piece is closed on the run after kCertSplits levels, or at once when it touches a pole
      // its run went to (the pieces around a pole double with every level), and counted as resting on the
      // premise that a small flat piece holds one minimum (SearchResult::premised) or as unproved.
      const auto inside = [&n, tolerance](const PatchHit& m) {
        if (m.patch != n.patch) return false;
        if (m.s >= n.s0 && m.s <= n.s1 && m.t >= n.t0 && m.t <= n.t1) return true;
        return std::any_of(n.corners.begin(), n.corners.end(),
                           [&](const Eigen::Vector3d& c) { return (c - m.point).norm() <= tolerance; });
      };
      // A piece closed without a proof that its run found its minimum keeps the result's lower bound honest: at
      // most its own proved bound (Objective::closingBound).
      const auto keepClosedBound = [&] {
        if (f.provesBasins()) closedBound = std::min(closedBound, std::max(top.lower, f.closingBound(n, out.best.value - tolerance)));
      };
      // A run that went to a pole the piece touches: there the chart degenerates and no piece is ever proved.
      const auto atPole = [&](const PatchHit& h) {
        const Eigen::Vector3d* pole = collapsedCorner(n, forest, 0.5 * tolerance);
        return pole && (*pole - h.point).norm() <= n.ball.radius;
      };
      // Next to a pole the pieces are far below the cached depth; their proofs are made per query there. A strip
      // along a pole is split on (the next strip of the pole's chain: one per level) until its bound prunes it or
      // it is tiny, never closed on the premise.
      const bool nearPole = n.fromPole <= kNearPole;
      const bool splitStrip = n.onPole() && !tiny && f.provesBasins();
      const auto settled = [&](const PatchHit& h) {
        const double enough = out.best.value - tolerance;
        const bool inBox = h.s >= n.s0 && h.s <= n.s1 && h.t >= n.t0 && h.t <= n.t1;
        const bool onEdge = h.s == 0 || h.s == 1 || h.t == 0 || h.t == 1;
        if ((n.kept || nearPole) && inBox &&
            ((onEdge && f.edgeBound(n, forest, h) >= enough) || f.basinBound(n, h, f.curvature(n, forest)) >= enough)) {
          ++out.convex;
          return true;
        }
        // Below the cached depth no proof is tried (a piece's forms would die with the query), so a split would
        // only go deeper.
        if (splitStrip) return false;
        if (tiny || !inBox || top.certSplits >= kCertSplits || !f.provesBasins() ||
            (!PatchForest::keepsChildren(n) && !nearPole) || atPole(h)) {
          ++out.premised;
          keepClosedBound();
          return true;
        }
        return false;
      };
      const bool closed = [&] {
        if (flat) {
          const auto end = std::find_if(polished.begin(), polished.end(), inside);
          if (end != polished.end()) return settled(*end);
          if (f.provesNoMinimum(n, forest, 0.5 * tolerance)) return true;
        }
        const RationalBezierPatch& patch = patches[static_cast<std::size_t>(n.patch)];
        polished.push_back(polish(patch, n.patch, f, 0.5 * (n.s0 + n.s1), 0.5 * (n.t0 + n.t1)));
        offer(polished.back());
        if (tiny || inside(polished.back())) return settled(polished.back());
        // The run left for another basin and the piece may hold one of its own (the wavy patch missed 2 of
        // 10,000 points by 3.1e-3 and 4.7e-6 when such pieces were closed): searched unless the Bernstein bound
        // proves it cannot improve by the tolerance.
        if (f.tightLowerBound(n) >= out.best.value - tolerance) return true;
        if (splitStrip) return false;
        if (top.certSplits >= kCertSplits || atPole(polished.back())) {
          ++out.unproved;
          keepClosedBound();
          return true;
        }
        return false;
      }();
      if (closed) continue;
    }
    const int certSplits = flat && !n.onPole() ? top.certSplits + 1 : top.certSplits;
    for (const PatchNode* c : forest.children(n, arena)) {
      // A child bounded above the best by more than the tie tolerance holds neither a better point nor a tie.
      const double lb = f.lowerBound(*c, out.best.value + tieTolerance);
      if (lb > out.best.value + tieTolerance) continue;
      offerCorners(*c);
      if (lb < out.best.value - tolerance) open.push({lb, c, certSplits});
    }
  }
  // The best may be a corner or a Newton run's end short of the minimum within the tolerance (a tangent contact
  // is flat there: a distance within 5e-11 of the least can be 1e-4 away from its point on a ball of radius 150);
  // a last run from it (unless it is where one ended) gives the point itself, where the engines want contacts
  // not to wander. A last run's end within rounding of the best value is the better answer where its gradient
  // is smaller: far away the values tie to rounding around the minimum, and only the gradient tells the point.
  const double searched = out.best.value;  // what the search's bounds were proved against
  const auto refine = [&](const PatchHit& h) {
    const double rounding = kValueUlps * std::numeric_limits<double>::epsilon() * std::abs(out.best.value);
    if (h.value < out.best.value || h.value > out.best.value + rounding) return offer(h);
    if (!(out.best.gradientError < std::numeric_limits<double>::infinity()) ||
        h.gradient.norm() < out.best.gradient.norm()) {
      hits.push_back(h);
      out.best = h;
    }
  };
  if (out.best.value < std::numeric_limits<double>::infinity()) {
    const PatchHit from = out.best;
    const RationalBezierPatch& patch = patches[static_cast<std::size_t>(from.patch)];
    const bool ranHere = std::any_of(polished.begin(), polished.end(), [&](const PatchHit& h) {
      return h.patch == from.patch && h.s == from.s && h.t == from.t;
    });
    if (!ranHere) refine(polish(patch, from.patch, f, from.s, from.t, {}, Steps::AlongGradient));
    // Where the tolerance was raised to the rounding (far from the model) every run stopped at its plateau: each
    // goes on along the gradient (the best may be on a patch edge, the minimum in the patch beside it).
    if (tolerance > requested)
      for (std::size_t k = 0, runs = polished.size(); k < runs; ++k) {
        const PatchHit end = polished[k];
        refine(polish(patches[static_cast<std::size_t>(end.patch)], end.patch, f, end.s, end.t, {},
                      Steps::AlongGradient));
      }
    // Next to a pole a run cannot leave its patch for the neighbour around the pole that holds the minimum (nor,
    // at the pole, pick a direction: its parameter there is any): runs from a ring about the pole in every patch
    // meeting there.
    constexpr double kRing = 1e-3;  // parameter distance of the ring from the pole
    const std::array<int, 4>& poleOfEdge = forest.poleOfEdge[static_cast<std::size_t>(from.patch)];
    const std::array<double, 4> away{from.s, 1 - from.s, from.t, 1 - from.t};
    for (std::size_t e = 0; e < 4; ++e) {
      if (poleOfEdge[e] < 0 || away[e] > kRing) continue;
      for (const auto& [other, edge] : forest.poles[static_cast<std::size_t>(poleOfEdge[e])].edges) {
        if (excluded(other)) continue;
        const double across = edge % 2 == 0 ? kRing : 1 - kRing;
        for (double along : {0.125, 0.375, 0.625, 0.875})
          refine(polish(patches[static_cast<std::size_t>(other)], other, f, edge < 2 ? across : along,
                        edge < 2 ? along : across, {}, Steps::AlongGradient));
      }
    }
  }
  for (const PatchHit& h : hits)
    if (h.value <= out.best.value + tieTolerance) out.ties.push_back(h);
  if (!out.exhausted) out.lowerBound = std::min(std::min(searched, out.best.value) - tolerance, closedBound);
  return out;
}

}  // namespace unidist::nurbs
