#include "nurbs/point_cells.h"
#include "nurbs/gradient_sign.h"
#include "nurbs/objectives.h"
#include "nurbs/point_convexity.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace unidist::nurbs {
namespace {

constexpr int kMaxCandidates = 32;  // more surviving nodes than this: the cell is left to the full search
constexpr int kMaxBuildNodes = 600;  // nodes a cell's proofs may visit
// Nodes below this depth are not tried: their forms (made once per node) would cost the first queries of a
// model more than the cells save them.
constexpr int kCellDepth = 4;

Eigen::Vector2d clampInto(const PatchNode& n, double s, double t) {
  return {std::clamp(s, n.s0, n.s1), std::clamp(t, n.t0, n.t1)};
}

/// The gradient vanishes at h to within a few times its rounding, but where it points out of the node's box.
bool stationary(const PatchNode& n, const PatchHit& h) {
  const double lo[2] = {n.s0, n.t0}, hi[2] = {n.s1, n.t1}, at[2] = {h.s, h.t};
  for (int c = 0; c < 2; ++c) {
    const double g = h.gradient[c];
    const bool outward = (at[c] <= lo[c] && g >= 0) || (at[c] >= hi[c] && g <= 0);
    if (!outward && !(std::abs(g) <= 64 * h.gradientError)) return false;
  }
  return true;
}

}  // namespace

/// Where a node's run (or single evaluation) starts: for the first node searched, the cell centre's answer moved
/// by the predicted step; for a later one its point nearest the best so far (beside it the gradient there points
/// out of the node and no run is needed): the best's parameters kept to the node, or in another patch the node's
/// corner nearest the best point.
Eigen::Vector2d PointCells::runStart(const Cell& cell, const PatchNode& n, const PatchHit* best, const Eigen::Vector3d& q) {
  if (!best && n.patch == cell.patch) {
    const Eigen::Vector2d predicted = cell.foot + cell.follow * (q - cell.centre);
    return clampInto(n, predicted[0], predicted[1]);
  }
  if (!best) return {0.5 * (n.s0 + n.s1), 0.5 * (n.t0 + n.t1)};
  if (n.patch == best->patch) return clampInto(n, best->s, best->t);
  std::size_t nearest = 0;
  for (std::size_t corner = 1; corner < 4; ++corner)
    if ((n.corners[corner] - best->point).squaredNorm() < (n.corners[nearest] - best->point).squaredNorm()) nearest = corner;
  return {nearest & 1 ? n.s1 : n.s0, nearest & 2 ? n.t1 : n.t0};
}

PointCells::PointCells(const Eigen::Vector3d& lo, const Eigen::Vector3d& hi, double cell) : lo_(lo), size_(cell) {
  for (int a = 0; a < 3; ++a) count_[a] = std::max(1, static_cast<int>(std::ceil((hi[a] - lo[a]) / cell)));
}

PointCells::~PointCells() {
  if (!cells_) return;
  for (std::size_t k = 0; k < static_cast<std::size_t>(count_.prod()); ++k) {
    delete cells_[k].load();
  }
}

std::unique_ptr<PointCells::Cell> PointCells::build(const PatchForest& forest,
                                                    const std::vector<RationalBezierPatch>& patches,
                                                    const Eigen::Vector3d& centre, double reach, double modelSize,
                                                    double tolerance) const {
  auto cell = std::make_unique<Cell>();
  const PointObjective objective(centre, modelSize);
  const SearchResult foot = minimise(forest, patches, objective, tolerance, 0);
  if (foot.exhausted) return cell;
  // Every query within reach of the centre is within this of the centre's nearest point.
  const double upper = foot.best.value + reach;
  cell->centre = centre;
  // How the nearest point's parameters follow q (implicit function theorem on the gradient (S − q)·S_a = 0:
  // H dx = Jᵀ dq), so that a query's run starts a second-order step from its answer.
  cell->patch = foot.best.patch;
  cell->foot = {foot.best.s, foot.best.t};
  Eigen::Matrix<double, 2, 3>& follow = cell->follow;
  {
    const SurfaceDerivatives d = patches[static_cast<std::size_t>(foot.best.patch)].derivatives(foot.best.s, foot.best.t);
    Eigen::Vector2d g;
    Eigen::Matrix2d H;
    objective.derivatives(d, g, H);
    Eigen::Matrix<double, 2, 3> Jt;
    Jt.row(0) = d.du.transpose();
    Jt.row(1) = d.dv.transpose();
    if (H.determinant() > 1e-12 * H.squaredNorm()) follow = H.inverse() * Jt;
    if (!follow.allFinite()) follow.setZero();
  }
  const auto addCorners = [&](const PatchNode& n) {
    const double s[4] = {n.s0, n.s1, n.s0, n.s1}, t[4] = {n.t0, n.t0, n.t1, n.t1};
    for (int k = 0; k < 4; ++k) {
      if ((s[k] != 0 && s[k] != 1) || (t[k] != 0 && t[k] != 1)) continue;
      const Eigen::Vector3d& c = n.corners[static_cast<std::size_t>(k)];
      if ((c - centre).norm() - reach > upper) continue;
      if (std::none_of(cell->corners.begin(), cell->corners.end(), [&](const PatchHit& h) { return h.point == c; }))
        cell->corners.push_back({n.patch, s[k], t[k], 0, c});
    }
  };
  std::vector<const PatchNode*> stack;
  for (const auto& root : forest.roots) stack.push_back(root.get());
  std::vector<std::unique_ptr<PatchNode>> arena;  // stays empty: the proofs stop above the cached depth
  GradientScratch scratch;
  int visited = 0;
  while (!stack.empty()) {
    const PatchNode& n = *stack.back();
    stack.pop_back();
    if (++visited > kMaxBuildNodes) return std::make_unique<Cell>();
    // Farther than the centre's nearest point can be from any query of the cell.
    const double near = std::max((centre - n.ball.center).norm() - n.ball.radius, boxDistance(n, centre)) - reach;
    if (near > upper) continue;
    // No critical point for any query of the cell (its corners aside).
    if (!mayHoldCritical(n, coneTowards(centre, n.ball.center, n.ball.radius + reach), false) ||
        pointHoldsNoMinimum(n, forest, centre, scratch, 0.5 * tolerance, reach)) {
      addCorners(n);
      continue;
    }
    const double curvature = n.depth <= kCellDepth && convexAtMiddle(n, centre)
                                 ? leastCurvature(curvatureForm(n, forest), centre, reach)
                                 : 0;
    if (curvature > 0) {
      // At a pole Newton's parameters are ill-conditioned (S_s vanishes): its points are left to the search.
      if (collapsedCorner(n, forest, 0.5 * tolerance)) return std::make_unique<Cell>();
      cell->candidates.push_back({&n, curvature});
      if (static_cast<int>(cell->candidates.size()) > kMaxCandidates) return std::make_unique<Cell>();
      continue;
    }
    if (n.depth >= kCellDepth) return std::make_unique<Cell>();
    for (const PatchNode* c : forest.children(n, arena)) stack.push_back(c);
  }
  cell->settled = true;
  return cell;
}

const PointCells::Cell* PointCells::cellAt(const PatchForest& forest, const std::vector<RationalBezierPatch>& patches,
                                           int index, double modelSize, double tolerance) const {
  std::call_once(cellsOnce_, [this] {
    const std::size_t total = static_cast<std::size_t>(count_.prod());
    cells_ = std::make_unique<std::atomic<const Cell*>[]>(total);
    for (std::size_t k = 0; k < total; ++k) cells_[k].store(nullptr, std::memory_order_relaxed);
    bytes_ += total * sizeof(std::atomic<const Cell*>);
  });
  std::atomic<const Cell*>& slot = cells_[static_cast<std::size_t>(index)];
  const Cell* cell = slot.load(std::memory_order_acquire);
  if (cell) return cell;
  const int i = index % count_[0], j = (index / count_[0]) % count_[1], k = index / (count_[0] * count_[1]);
  const Eigen::Vector3d centre = lo_ + size_ * Eigen::Vector3d(i + 0.5, j + 0.5, k + 0.5);
  // The ball around the cube, widened for the rounding of the centre and of a query's cell index.
  const double reach = 0.5 * std::sqrt(3.0) * size_ * (1 + 1e-9) + 1e-12 * (centre.cwiseAbs().maxCoeff() + size_);
  std::unique_ptr<Cell> made = build(forest, patches, centre, reach, modelSize, tolerance);
  std::size_t bytes = sizeof(Cell) + made->candidates.capacity() * sizeof(Candidate) + made->corners.capacity() * sizeof(PatchHit);
  const Cell* expected = nullptr;
  if (slot.compare_exchange_strong(expected, made.get(), std::memory_order_acq_rel)) {
    bytes_ += bytes;
    ++made_;
    return made.release();
  }
  return expected;  // another thread made it first
}

bool PointCells::closest(const PatchForest& forest, const std::vector<RationalBezierPatch>& patches,
                         const Eigen::Vector3d& q, double modelSize, double tolerance, SearchResult& out) const {
  const Eigen::Vector3d x = (q - lo_) / size_;
  if (!(x.minCoeff() >= 0)) return false;
  Eigen::Vector3i at;
  for (int a = 0; a < 3; ++a) {
    if (!(x[a] < count_[a])) return false;
    at[a] = std::min(count_[a] - 1, static_cast<int>(x[a]));
  }
  const Cell& cell = *cellAt(forest, patches, at[0] + count_[0] * (at[1] + count_[1] * at[2]), modelSize, tolerance);
  if (!cell.settled) return false;
  const PointObjective f(q, modelSize);
  out = SearchResult{};
  PatchHit& best = out.best;
  best.value = std::numeric_limits<double>::infinity();
  for (PatchHit c : cell.corners) {
    c.value = f.value(c.point);
    if (c.value < best.value) best = c;
  }
  // Nearest nodes first (by their bounds), so that the others are settled by the bound or by one evaluation.
  std::array<std::pair<double, int>, kMaxCandidates + 1> order;
  const std::size_t count = cell.candidates.size();
  // By their balls (cheap); the frame box is asked only of a node the ball does not settle.
  for (std::size_t k = 0; k < count; ++k) {
    const BoundingSphere& ball = cell.candidates[k].node->ball;
    order[k] = {(q - ball.center).norm() - ball.radius, static_cast<int>(k)};
  }
  std::sort(order.begin(), order.begin() + static_cast<std::ptrdiff_t>(count));
  double lower = best.value;
  for (std::size_t k = 0; k < count; ++k) {
    const Candidate& c = cell.candidates[static_cast<std::size_t>(order[k].second)];
    const PatchNode& n = *c.node;
    const double near = order[k].first >= best.value ? order[k].first : std::max(order[k].first, boxDistance(n, q));
    if (near >= best.value) {
      lower = std::min(lower, near);
      continue;
    }
    const RationalBezierPatch& patch = patches[static_cast<std::size_t>(n.patch)];
    const bool first = !(best.value < std::numeric_limits<double>::infinity());
    const Eigen::Vector2d start = runStart(cell, n, first ? nullptr : &best, q);
    PatchHit hit;
    double bound = -std::numeric_limits<double>::infinity();
    if (!first) {
      hit = pointAt(patch, n.patch, f, start[0], start[1]);
      bound = convexDistanceBound(n, q, hit, c.curvature);
    }
    if (first || bound < std::min(best.value, hit.value) - tolerance) {
      hit = polish(patch, n.patch, f, start[0], start[1], ParamBox{n.s0, n.s1, n.t0, n.t1});
      bound = convexDistanceBound(n, q, hit, c.curvature);
      if (bound < std::min(best.value, hit.value) - tolerance) return false;
      // A run that stopped short of a stationary point (where the distance is nearly flat along the surface,
      // its value is proved but its point is not pinned down) is left to the full search, whose points callers
      // iterating on them (the alternating pair search) expect.
      if (hit.value < best.value && !stationary(n, hit)) return false;
    }
    ++out.convex;
    if (hit.value < best.value) best = hit;
    lower = std::min(lower, bound);
  }
  if (!(best.value < std::numeric_limits<double>::infinity())) return false;
  out.lowerBound = std::min(lower, best.value);
  return true;
}

}  // namespace unidist::nurbs
