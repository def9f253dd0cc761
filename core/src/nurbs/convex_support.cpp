#include "nurbs/convex_support.h"

#include "nurbs/patch_tree.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace unidist::nurbs {
namespace {

constexpr int kSteps = 30;
constexpr double kCornerUlps = 8;  // a corner this close to the highest control point is as high
constexpr std::size_t kPatchesTried = 3;  // patches the ascent is tried on before the global search
constexpr double kInterior = 1e-9;   // parameters this close to a patch edge: the maximum may be on the edge
constexpr double kConverged = 1e-9;  // a Newton step this short (parameters): the next is at the maximum to rounding

struct Local {
  double height;
  Eigen::Vector2d g;
  Eigen::Matrix2d H;
};

Local localAt(const RationalBezierPatch& patch, const Eigen::Vector3d& d, const Eigen::Vector2d& st) {
  const SurfaceDerivatives s = patch.derivatives(st[0], st[1]);
  Local l{d.dot(s.point), Eigen::Vector2d(d.dot(s.du), d.dot(s.dv)), Eigen::Matrix2d()};
  l.H << d.dot(s.duu), d.dot(s.duv), d.dot(s.duv), d.dot(s.dvv);
  return l;
}

bool negativeDefinite(const Eigen::Matrix2d& H) { return H(0, 0) < 0 && H.determinant() > 0; }

/// Levenberg–Newton ascent of d·S over [0,1]² from st (a step is kept only where the height rises); true when it
/// ends at an interior strict local maximum: a negative definite Hessian and a plain Newton step this short.
bool ascend(const RationalBezierPatch& patch, const Eigen::Vector3d& d, Eigen::Vector2d& st) {
  Local at = localAt(patch, d, st);
  for (int step = 0; step < kSteps; ++step) {
    const double scale = std::max(at.H.cwiseAbs().maxCoeff(), at.g.norm());
    if (!(scale > 0)) return false;
    bool moved = false;
    for (double mu = 0; mu <= 1e3 * scale && !moved; mu = mu == 0 ? 1e-3 * scale : 10 * mu) {
      const Eigen::Matrix2d M = at.H - mu * Eigen::Matrix2d::Identity();
      if (!negativeDefinite(M)) continue;
      const Eigen::Vector2d delta = -M.inverse() * at.g;
      if (!delta.allFinite()) return false;
      const Eigen::Vector2d next = (st + delta).cwiseMax(0.0).cwiseMin(1.0);
      if (mu == 0 && delta.cwiseAbs().maxCoeff() < kConverged) {
        // Newton converges quadratically: from here the height is exact to rounding after this step.
        st = next;
        return (st.array() > kInterior).all() && (st.array() < 1 - kInterior).all();
      }
      const Local there = localAt(patch, d, next);
      if (there.height >= at.height) {
        st = next;
        at = there;
        moved = true;
      }
    }
    if (!moved) break;
  }
  // Stopped without a rounding-size Newton step: not trusted.
  return false;
}

/// One pass over the patches' Euclidean control points (the forest roots'): the highest overall, the highest patch
/// corner, and, when asked (`withStarts`), the patches with the highest control points (their best one's
/// indices), highest first.
struct Scan {
  struct Start {
    double height;
    std::size_t patch;
    int i, j;
  };
  double top = -std::numeric_limits<double>::infinity(), corner = top, magnitude = 0;
  Eigen::Vector3d cornerPoint = Eigen::Vector3d::Zero();
  std::array<Start, kPatchesTried> starts;

  Scan(const PatchForest& forest, const Eigen::Vector3d& d, bool withStarts) {
    starts.fill({-std::numeric_limits<double>::infinity(), 0, 0, 0});
    const Eigen::Vector3d absD = d.cwiseAbs();
    for (std::size_t k = 0; k < forest.roots.size(); ++k) {
      const PatchNode& root = *forest.roots[k];
      const int p = root.net.degreeU, q = root.net.degreeV;
      Start best{-std::numeric_limits<double>::infinity(), k, 0, 0};
      for (int i = 0; i <= p; ++i)
        for (int j = 0; j <= q; ++j) {
          const Eigen::Vector3d& x = root.points[static_cast<std::size_t>(i * (q + 1) + j)];
          const double h = d.dot(x);
          magnitude = std::max(magnitude, absD.dot(x.cwiseAbs()));
          if (h > best.height) best = {h, k, i, j};
          if ((i == 0 || i == p) && (j == 0 || j == q) && h > corner) {
            corner = h;
            cornerPoint = x;
          }
        }
      top = std::max(top, best.height);
      if (!withStarts || best.height <= starts.back().height) continue;
      starts.back() = best;
      std::sort(starts.begin(), starts.end(), [](const Start& a, const Start& b) { return a.height > b.height; });
    }
  }
  /// Heights equal in exact arithmetic differ here by the rounding of the points and the dot products.
  bool cornerIsTop() const { return corner >= top - kCornerUlps * std::numeric_limits<double>::epsilon() * magnitude; }
};

}  // namespace

std::optional<Eigen::Vector3d> highestCornerIfTop(const PatchForest& forest, const Eigen::Vector3d& d) {
  const Scan scan(forest, d, false);
  if (scan.cornerIsTop()) return scan.cornerPoint;
  return std::nullopt;
}

Eigen::Vector3d convexSupport(const NurbsModel& model, const Eigen::Vector3d& d) {
  const Scan scan(model.forest(), d, true);
  if (scan.cornerIsTop()) return scan.cornerPoint;
  // The ascent on the highest few patches in turn: a maximum on a seam ends every one of them on its edge, and
  // the global search answers.
  for (const Scan::Start& s : scan.starts) {
    if (!std::isfinite(s.height)) break;
    const RationalBezierPatch& p = model.patches()[s.patch];
    // Start inside the patch: a corner control point is often a pole's.
    const Eigen::Vector2d inset(0.25 / p.degreeU, 0.25 / p.degreeV);
    Eigen::Vector2d st(static_cast<double>(s.i) / p.degreeU, static_cast<double>(s.j) / p.degreeV);
    st = st.cwiseMax(inset).cwiseMin(Eigen::Vector2d::Ones() - inset);
    if (ascend(p, d, st)) return p.evaluate(st[0], st[1]);
  }
  return model.support(d);
}

}  // namespace unidist::nurbs
