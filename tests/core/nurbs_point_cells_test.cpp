// The NURBS point query's convexity proof (point_convexity.h) and query cells (point_cells.h): every bound
// checked against dense sampling of the exact surface, every cell answer against the full search.
#include "core/nurbs_fixtures.h"
#include "core/nurbs_oracle.h"
#include "nurbs/objectives.h"
#include "nurbs/patch_search.h"
#include "nurbs/point_cells.h"
#include "nurbs/point_convexity.h"
#include "unidist/nurbs.h"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>

#include <functional>
#include <random>
#include <thread>

namespace {

using Vec = Eigen::Vector3d;
using namespace unidist::nurbs;

// Signed distances to the exact torus (core radius R, tube a) and sphere (radius R), both about the origin.
double torusDistance(const Vec& q, double R, double a) { return std::hypot(std::hypot(q.x(), q.y()) - R, q.z()) - a; }
double sphereDistance(const Vec& q, double R) { return q.norm() - R; }

struct Case {
  const char* name;
  unidist::NurbsSurface surface;
  bool solid;
  Vec extent;  // queries uniform in [−extent, extent]
  std::function<double(const Vec&)> truth;  // the distance in closed form; empty: the grid + Newton oracle
};

std::vector<Case> cases(double scale = 1) {
  return {{"torus", nurbs_fixtures::torusSurface(1, 0.25, scale), true, scale * Vec(1.6, 1.6, 0.6),
           [scale](const Vec& q) { return std::abs(torusDistance(q, scale, 0.25 * scale)); }},
          {"sphere", nurbs_fixtures::sphereSurface(scale), true, scale * Vec(2, 2, 2),
           [scale](const Vec& q) { return std::abs(sphereDistance(q, scale)); }},
          {"wavy", nurbs_fixtures::wavySurface(), false, Vec(1.6, 1.6, 0.64), nullptr}};
}

std::vector<Vec> randomPoints(const Vec& extent, int count, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> U(-1, 1);
  std::vector<Vec> out;
  for (int k = 0; k < count; ++k) out.push_back(extent.cwiseProduct(Vec(U(rng), U(rng), U(rng))));
  return out;
}

// The nodes down to `depth` of every patch.
std::vector<const PatchNode*> nodesTo(const PatchForest& forest, int depth) {
  std::vector<const PatchNode*> out, stack;
  std::vector<std::unique_ptr<PatchNode>> arena;
  for (const auto& r : forest.roots) stack.push_back(r.get());
  while (!stack.empty()) {
    const PatchNode* n = stack.back();
    stack.pop_back();
    out.push_back(n);
    if (n->depth < depth)
      for (const PatchNode* c : forest.children(*n, arena)) stack.push_back(c);
  }
  return out;
}

// The Hessian of ½|S − q|² in the node's own parameters at (u, v) ∈ [0,1]².
double sampledLeastEigenvalue(const PatchNode& n, const Vec& q, double u, double v) {
  const unidist::SurfaceDerivatives d = n.net.derivatives(u, v);
  const Vec r = d.point - q;
  Eigen::Matrix2d H;
  H << d.du.dot(d.du) + r.dot(d.duu), d.du.dot(d.dv) + r.dot(d.duv), d.du.dot(d.dv) + r.dot(d.duv),
      d.dv.dot(d.dv) + r.dot(d.dvv);
  return Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d>(H).eigenvalues()[0];
}

TEST(NurbsPointConvexity, LeastCurvatureIsBelowTheSampledHessianEverywhere) {
  for (const Case& c : cases()) {
    const unidist::NurbsModel model({c.surface}, c.solid);
    const std::vector<Vec> queries = randomPoints(c.extent, 40, 3);
    int proved = 0;
    for (const PatchNode* n : nodesTo(model.forest(), 3)) {
      const CurvatureForm& form = curvatureForm(*n, model.forest());
      for (const Vec& q : queries) {
        const double reach = 0.05;
        const double mu = leastCurvature(form, q, reach);
        if (!(mu > 0)) continue;
        ++proved;
        // At q and at points within reach of it, on a grid over the node.
        for (const Vec& x : {q, Vec(q + Vec(reach, 0, 0)), Vec(q - Vec(0, 0.7 * reach, 0.7 * reach))})
          for (int i = 0; i <= 6; ++i)
            for (int j = 0; j <= 6; ++j)
              ASSERT_GE(sampledLeastEigenvalue(*n, x, i / 6.0, j / 6.0), mu * (1 - 1e-9))
                  << c.name << " node depth " << n->depth << " patch " << n->patch;
      }
    }
    EXPECT_GT(proved, 100) << c.name;  // the test proves something
  }
}

TEST(NurbsPointConvexity, BasinBoundIsBelowEveryPointOfTheNode) {
  for (const Case& c : cases()) {
    const unidist::NurbsModel model({c.surface}, c.solid);
    const double size = model.localBounds().diagonal();
    int proved = 0, tight = 0;
    for (const Vec& q : randomPoints(c.extent, 60, 5)) {
      const PointObjective f(q, size);
      for (const PatchNode* n : nodesTo(model.forest(), 2)) {
        const double mu = f.curvature(*n, model.forest());
        if (!(mu > 0)) continue;
        const unidist::RationalBezierPatch& patch = model.patches()[static_cast<std::size_t>(n->patch)];
        // From the node's middle (not a minimum: the bound must hold all the same) and from a run's end.
        const PatchHit middle = pointAt(patch, n->patch, f, 0.5 * (n->s0 + n->s1), 0.5 * (n->t0 + n->t1));
        const PatchHit run = polish(patch, n->patch, f, n->s0, n->t1, ParamBox{n->s0, n->s1, n->t0, n->t1});
        double least = std::numeric_limits<double>::infinity();
        for (int i = 0; i <= 24; ++i)
          for (int j = 0; j <= 24; ++j)
            least = std::min(least, (n->net.evaluate(i / 24.0, j / 24.0) - q).norm());
        for (const PatchHit& h : {middle, run}) EXPECT_LE(f.basinBound(*n, h, mu), least + 1e-15) << c.name;
        // A run's end is the node's least value: its bound is within the tolerance of it, unless the run
        // stopped short of the rounding limit where the curvature is weak (then the search goes on).
        tight += f.basinBound(*n, run, mu) >= run.value - 1e-13 * size;
        EXPECT_LE(run.value, least + 1e-12) << c.name;
        ++proved;
      }
    }
    EXPECT_GT(proved, 50) << c.name;
    EXPECT_GE(tight, 0.95 * proved) << c.name;
  }
}

// Where a Newton run ends on a patch edge the node touches, the edge bound holds below every point of the node
// (its least distance is on that edge), and from the run's end it is nearly the end's value.
TEST(NurbsPointConvexity, EdgeBoundIsBelowEveryPointOfTheNode) {
  for (const Case& c : cases()) {
    const unidist::NurbsModel model({c.surface}, c.solid);
    const double size = model.localBounds().diagonal();
    int proved = 0, tight = 0, asked = 0;
    for (const Vec& q : randomPoints(c.extent, 60, 9)) {
      const PointObjective f(q, size);
      for (const PatchNode* n : nodesTo(model.forest(), 3)) {
        if (n->s0 > 0 && n->s1 < 1 && n->t0 > 0 && n->t1 < 1) continue;
        const unidist::RationalBezierPatch& patch = model.patches()[static_cast<std::size_t>(n->patch)];
        const PatchHit run = polish(patch, n->patch, f, 0.5 * (n->s0 + n->s1), 0.5 * (n->t0 + n->t1),
                                    ParamBox{n->s0, n->s1, n->t0, n->t1});
        if (!(run.s == 0 || run.s == 1 || run.t == 0 || run.t == 1)) continue;
        ++asked;
        const double bound = f.edgeBound(*n, model.forest(), run);
        if (!(bound > -std::numeric_limits<double>::infinity())) continue;
        double least = std::numeric_limits<double>::infinity();
        for (int i = 0; i <= 24; ++i)
          for (int j = 0; j <= 24; ++j)
            least = std::min(least, (n->net.evaluate(i / 24.0, j / 24.0) - q).norm());
        ASSERT_LE(bound, least + 1e-15) << c.name << " q " << q.transpose() << " depth " << n->depth;
        // A corner h is proved outright; along an edge the run converged, so the bound is at its value.
        tight += bound >= run.value - 1e-12 * size;
        ++proved;
      }
    }
    EXPECT_GT(proved, 0.2 * asked) << c.name << " of " << asked;  // the proof is not vacuous
    EXPECT_GE(tight, 0.95 * proved) << c.name;
  }
}

// The search closes the leaf its Newton run ends in on a proof, not the one-minimum premise: the convexity proof,
// or the edge bound where the end is on the patch boundary (most of the wavy patch's points), or else it splits the
// leaf. Next to a pole (the sphere's), where the parametrisation degenerates, the strips along it (patch_tree.h)
// are split on instead.
TEST(NurbsPointConvexity, SearchRarelyRestsOnThePremise) {
  // Per 1,000 queries: torus (0 measured), sphere (0; 58 before the strips, nearly all next to its poles), wavy
  // (1). Before the edge bound and the splitting, 2,000 queries left 1, 72 and 1,270.
  const int allowed[] = {2, 5, 5};
  int k = 0;
  for (const Case& c : cases()) {
    const unidist::NurbsModel model({c.surface}, c.solid);
    const nurbs_fixtures::GridOracle oracle(c.surface);
    const double size = model.localBounds().diagonal();
    int premised = 0, proved = 0, index = 0;
    for (const Vec& q : randomPoints(c.extent, 1000, 17)) {
      const SearchResult r = minimise(model.forest(), model.patches(), PointObjective(q, size), 1e-13 * size, 0);
      premised += r.premised;
      proved += r.convex;
      if (index++ % 20 == 0) {
        ASSERT_NEAR(r.best.value, c.truth ? c.truth(q) : oracle.distance(q), 1e-9 * size) << c.name;
      }
    }
    EXPECT_LE(premised, allowed[k++]) << c.name;
    EXPECT_GE(proved, 900) << c.name;
  }
}

// The search's lower bound is proved also where a piece is closed without a proof that a run found its minimum
// (next to a sphere's poles): it stays below the truth, and elsewhere within the tolerance of the answer.
TEST(NurbsPointConvexity, LowerBoundHoldsNextToPoles) {
  const unidist::NurbsModel model({nurbs_fixtures::sphereSurface()}, true);
  const double size = model.localBounds().diagonal(), tolerance = 1e-10 * size;
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> U(-1, 1);
  int wide = 0;
  for (int k = 0; k < 800; ++k) {
    const double spread = std::pow(10.0, -7 + 7 * (k % 8) / 7.0);
    const Vec q(spread * U(rng), spread * U(rng), (k % 2 ? 1 : -1) * (1 + spread * U(rng)));
    const SearchResult r = minimise(model.forest(), model.patches(), PointObjective(q, size), tolerance, 0);
    const double truth = std::abs(sphereDistance(q, 1));
    // The truth lies in [lowerBound, value]: the value is a realised distance, the bound is proved. Where the
    // run next to the pole stopped short (a miss of up to a few tolerances: 1.7e-9 for 7.9e-10), the bound
    // says so.
    ASSERT_GE(r.best.value, truth - 1e-15) << q.transpose();
    ASSERT_LE(r.lowerBound, truth + 1e-15) << q.transpose();
    wide += r.lowerBound < r.best.value - tolerance;
  }
  EXPECT_GT(wide, 0);  // the premise was needed there: the bound says so
  const unidist::NurbsModel torus({nurbs_fixtures::torusSurface()}, true);
  for (const Vec& q : randomPoints(Vec(1.6, 1.6, 0.6), 1000, 29)) {
    const SearchResult r = minimise(torus.forest(), torus.patches(), PointObjective(q, size), tolerance, 0);
    ASSERT_GE(r.lowerBound, r.best.value - tolerance) << q.transpose();
  }
}

// Cells answer most repeated queries, each as the full search does and as the truth has it (closed forms;
// the grid + Newton oracle on every tenth point of the wavy patch, whose oracle is slow).
void expectCellsMatchSearch(const Case& c, double tolerance) {
  const unidist::NurbsModel model({c.surface}, c.solid);
  const nurbs_fixtures::GridOracle oracle(c.surface);
  const double size = model.localBounds().diagonal();
  const Vec margin = Vec::Constant(0.5 * size);
  const PointCells cells(model.localBounds().min - margin, model.localBounds().max + margin, size / 32);
  const std::vector<Vec> queries = randomPoints(c.extent, 3000, 7);
  int answered = 0;
  constexpr int kPasses = 2;  // a cell is built by its first query
  for (int pass = 0; pass < kPasses; ++pass)
    for (std::size_t k = 0; k < queries.size(); ++k) {
      const Vec& q = queries[k];
      SearchResult r;
      if (!cells.closest(model.forest(), model.patches(), q, size, tolerance, r)) continue;
      answered += pass == kPasses - 1;
      if (c.truth) {
        ASSERT_NEAR(r.best.value, c.truth(q), 1e-10 * size) << c.name << " q " << q.transpose();
      } else if (pass == 0 && k % 10 == 0) {
        ASSERT_NEAR(r.best.value, oracle.distance(q), 1e-9 * size) << c.name << " q " << q.transpose();
      }
      const SearchResult full = minimise(model.forest(), model.patches(), PointObjective(q, size), tolerance, 0);
      ASSERT_NEAR(r.best.value, full.best.value, 2 * tolerance) << c.name << " q " << q.transpose();
      ASSERT_LE(r.lowerBound, full.best.value + tolerance) << c.name;
      ASSERT_GE(r.lowerBound, r.best.value - tolerance) << c.name;
      ASSERT_NEAR((r.best.point - q).norm(), r.best.value, 1e-12 * size);
    }
  // Cells near a centre of curvature (the torus's core circle, the sphere's centre) or with too many pieces
  // are left to the search: most are settled.
  std::printf("%s: cells answered %d of %zu\n", c.name, answered, queries.size());
  EXPECT_GT(answered, c.solid ? 1500 : 1000) << c.name;
  EXPECT_GT(cells.bytes(), 0u);
}

TEST(NurbsPointCells, AnswersAsTheFullSearch) {
  for (const Case& c : cases()) expectCellsMatchSearch(c, 1e-13 * 3.6);
}

TEST(NurbsPointCells, AnswersAtTinyAndHugeScales) {
  for (double scale : {1e-4, 1e4})
    for (const Case& c : cases(scale)) {
      if (std::string(c.name) == "wavy") continue;  // its fixture has no scale
      expectCellsMatchSearch(c, 1e-13 * 3.6 * scale);
    }
}

TEST(NurbsPointCells, ModelQueriesAgreeAcrossThreadsAndPasses) {
  unidist::NurbsModel model({nurbs_fixtures::torusSurface()}, true);
  model.preparePointQueries();
  const std::vector<Vec> queries = randomPoints(Vec(1.6, 1.6, 0.6), 4000, 9);
  std::vector<double> truth;
  for (const Vec& q : queries) truth.push_back(torusDistance(q, 1, 0.25));
  // Four threads build and use the same cells at once, three passes each.
  std::vector<int> wrong(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([&, t] {
      for (int pass = 0; pass < 3; ++pass)
        for (std::size_t k = static_cast<std::size_t>(t); k < queries.size(); k += 2) {
          const unidist::SurfacePoint p = model.closestPoint(queries[k]);
          wrong[static_cast<std::size_t>(t)] += std::abs(p.signedDistance - truth[k]) > 1e-12 || p.error > 1e-12;
        }
    });
  for (std::thread& t : threads) t.join();
  for (int w : wrong) EXPECT_EQ(w, 0);
  bool reported = false;
  for (const unidist::StructureReport& s : model.structures())
    if (s.name == "point-cells") reported = s.built && s.bytes > 0;
  EXPECT_TRUE(reported);
}

// A cell is made by the first query in it, from its centre alone: an answer never depends on the queries
// before it (the pair routines compare answers bit for bit across argument orders).
TEST(NurbsPointCells, AnswersDependOnTheQueryOnly) {
  const std::vector<Vec> queries = randomPoints(Vec(1.6, 1.6, 0.6), 1500, 13);
  unidist::NurbsModel fresh({nurbs_fixtures::torusSurface()}, true), used({nurbs_fixtures::torusSurface()}, true);
  const unidist::NurbsModel plain({nurbs_fixtures::torusSurface()}, true);
  fresh.preparePointQueries();
  used.preparePointQueries();
  for (const Vec& q : randomPoints(Vec(1.6, 1.6, 0.6), 3000, 14)) (void)used.closestPoint(q);
  for (auto it = queries.rbegin(); it != queries.rend(); ++it) (void)used.closestPoint(*it);
  for (const Vec& q : queries) {
    const unidist::SurfacePoint a = fresh.closestPoint(q), b = used.closestPoint(q);
    ASSERT_EQ(a.signedDistance, b.signedDistance);
    ASSERT_EQ(a.point, b.point);
    ASSERT_EQ(a.normal, b.normal);
    ASSERT_EQ(a.error, b.error);
    // Unprepared, the search answers the same distance to the tolerance.
    ASSERT_NEAR(plain.closestPoint(q).signedDistance, a.signedDistance, 1e-12);
  }
}

TEST(NurbsPointCells, QueriesOutsideTheGridTakeTheSearch) {
  const unidist::NurbsModel model({nurbs_fixtures::sphereSurface()}, true);
  const double size = model.localBounds().diagonal();
  const PointCells cells(Vec::Constant(-1), Vec::Constant(1), 0.1);
  SearchResult r;
  for (const Vec& q : {Vec(5, 0, 0), Vec(-1.5, 0, 0), Vec(0, 0, 1.01)})
    EXPECT_FALSE(cells.closest(model.forest(), model.patches(), q, size, 1e-12, r));
  // Far outside: the model's own query is exact all the same.
  unidist::NurbsModel prepared({nurbs_fixtures::sphereSurface()}, true);
  prepared.preparePointQueries();
  EXPECT_NEAR(prepared.closestPoint(Vec(50, 0, 0)).signedDistance, 49, 1e-12);
}

}  // namespace
