#include "core/extremes_harness.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <ctime>
#include <exception>
#include <iterator>
#include <map>
#include <mutex>
#include <thread>
#include <utility>

namespace extremes {

/// Budgets are for an optimised build; a sanitizer build (UNIDIST_SANITIZE, tests/CMakeLists.txt) runs queries
/// several times slower, so its budgets and hang limit are scaled by this.
#ifdef UNIDIST_SANITIZER_SLOWDOWN
constexpr double kSanitizerSlowdown = UNIDIST_SANITIZER_SLOWDOWN;
#else
constexpr double kSanitizerSlowdown = 1;
#endif

namespace {

constexpr double kEps = std::numeric_limits<double>::epsilon();

double worldDiagonal(const unidist::Model& m, const Pose& X) {
  const unidist::Aabb box = m.localBounds();
  return box.bounded() ? box.transformed(X).diagonal() : 0.0;
}

/// Magnitude of the coordinates a case involves: what rounding is relative to.
double coordinateScale(const Case& c) {
  return c.XA.translation().norm() + c.XB.translation().norm() + worldDiagonal(*c.a, c.XA) + worldDiagonal(*c.b, c.XB);
}

double sizeOf(const Case& c) {
  const double d = std::max(worldDiagonal(*c.a, c.XA), worldDiagonal(*c.b, c.XB));
  return d > 0 ? d : 1.0;
}

/// Rounding of the coordinates: the library's own floor for "tolerance 0" (64 ulps of the coordinate scale).
double roundingOf(const Case& c) { return 64 * kEps * coordinateScale(c); }

/// A NURBS point query resolves distances to 1e-13 of the model's size (core/src/nurbs/nurbs_model.cpp,
/// kRelativeTolerance), and the generic searches take point queries as exact: their proved bounds can be off by
/// that much (measured: 1.4e-13 on touching NURBS solids). Known, stated in docs/extremes.md; not tolerance-sized.
double pointQueryResolution(const Case& c) {
  double r = 0;
  if (c.a->type() == unidist::ModelType::Nurbs) r += 1e-13 * worldDiagonal(*c.a, c.XA);
  if (c.b->type() == unidist::ModelType::Nurbs) r += 1e-13 * worldDiagonal(*c.b, c.XB);
  return r;
}

/// Worst cases per table cell (family pair x kind of extreme), relative to the models' size.
struct Cell {
  int cases = 0, bounded = 0;
  double allowance = 0, worstError = 0;
};

/// The column of docs/extremes.md a case belongs to: every scale in one, every gap in another.
std::string columnOf(const std::string& extreme) {
  if (extreme.rfind("scale", 0) == 0) return "scales";
  if (extreme.rfind("gap", 0) == 0) return "gaps";
  return extreme;
}

std::mutex tableMutex;
std::map<std::pair<std::string, std::string>, Cell>& table() {
  static std::map<std::pair<std::string, std::string>, Cell> t;
  return t;
}

void record(const Case& c, const unidist::DistanceResult& r) {
  const double size = sizeOf(c);
  std::lock_guard<std::mutex> lock(tableMutex);
  Cell& cell = table()[{c.family, columnOf(c.extreme)}];
  ++cell.cases;
  cell.allowance = std::max(cell.allowance, allowanceOf(c) / size);
  if (r.status == unidist::Status::Certified) {
    const double err = std::max({c.truth.lo - r.distance, r.distance - c.truth.hi, 0.0});
    cell.worstError = std::max(cell.worstError, err / size);
  } else {
    ++cell.bounded;
  }
}

/// Prints the table of docs/extremes.md (markdown) at the end of the run when UNIDIST_EXTREMES_TABLE is set: per
/// cell the worst error of a certified answer / the largest allowance, both relative to the models' size, and
/// how many answers were only bounded (their bounds are checked all the same).
class TablePrinter : public ::testing::Environment {
 public:
  void TearDown() override {
    if (!std::getenv("UNIDIST_EXTREMES_TABLE")) return;
    const char* rows[] = {"prim-prim", "prim-mesh", "prim-cloud", "prim-nurbs", "mesh-mesh",
                          "mesh-cloud", "mesh-nurbs", "cloud-cloud", "cloud-nurbs", "nurbs-nurbs"};
    const char* columns[] = {"scales", "offset 1e6", "gaps", "touching", "near-parallel",
                             "deep", "containment", "degenerate", "tangent"};
    std::lock_guard<std::mutex> lock(tableMutex);
    std::printf("| family |");
    for (const char* col : columns) std::printf(" %s |", col);
    std::printf("\n| --- |");
    for (std::size_t k = 0; k < std::size(columns); ++k) std::printf(" --- |");
    std::printf("\n");
    for (const char* row : rows) {
      std::printf("| %s |", row);
      for (const char* col : columns) {
        const auto it = table().find({row, col});
        if (it == table().end()) {
          std::printf(" — |");
          continue;
        }
        const Cell& cell = it->second;
        std::printf(" %.1e / %.0e", cell.worstError, cell.allowance);
        if (cell.bounded) std::printf(" (%d/%d b)", cell.bounded, cell.cases);
        std::printf(" |");
      }
      std::printf("\n");
    }
  }
};

[[maybe_unused]] const auto* const kTablePrinter = ::testing::AddGlobalTestEnvironment(new TablePrinter);

/// CPU time of the calling thread: the budget holds on a machine shared with other work, where wall time does not.
double threadCpuSeconds() {
  timespec t{};
  clock_gettime(CLOCK_THREAD_CPUTIME_ID, &t);
  return static_cast<double>(t.tv_sec) + 1e-9 * static_cast<double>(t.tv_nsec);
}

/// The query on its own thread, so a hang is reported (and ends this test process) instead of stalling the suite.
struct Run {
  std::mutex m;
  std::condition_variable cv;
  bool done = false;
  unidist::DistanceResult result;
  std::exception_ptr error;
  double seconds = 0;  // CPU time of the query
};

std::shared_ptr<Run> launch(const Case& c) {
  auto run = std::make_shared<Run>();
  std::thread([run, a = c.a, b = c.b, XA = c.XA, XB = c.XB, options = c.options] {
    const double start = threadCpuSeconds();
    unidist::DistanceResult r;
    std::exception_ptr error;
    try {
      r = unidist::distance(*a, XA, *b, XB, options);
    } catch (...) {
      error = std::current_exception();
    }
    const double seconds = threadCpuSeconds() - start;
    std::lock_guard<std::mutex> lock(run->m);
    run->result = r;
    run->error = error;
    run->seconds = seconds;
    run->done = true;
    run->cv.notify_all();
  }).detach();
  return run;
}

bool finite(const Vec& v) { return v.allFinite(); }

}  // namespace

double allowanceOf(const Case& c) {
  const double tolerance = c.options.tolerance < 0 ? unidist::defaultTolerance(*c.a, c.XA, *c.b, c.XB) : c.options.tolerance;
  return std::max(tolerance, roundingOf(c)) + roundingOf(c);
}

unidist::DistanceResult runCase(const Case& c) {
  SCOPED_TRACE(c.family + " | " + c.extreme + " | " + c.what);
  const std::shared_ptr<Run> run = launch(c);
  {
    // A hang is a hard failure: wait well past the budget, then end this test process with a message.
    const double hardLimit = std::max(20.0, 4 * c.budgetSeconds) * kSanitizerSlowdown;
    std::unique_lock<std::mutex> lock(run->m);
    if (!run->cv.wait_for(lock, std::chrono::duration<double>(hardLimit), [&] { return run->done; })) {
      std::fprintf(stderr, "HANG: %s | %s | %s: no answer after %.0f s\n", c.family.c_str(), c.extreme.c_str(),
                   c.what.c_str(), hardLimit);
      std::fflush(stdout);
      std::fflush(stderr);
      std::_Exit(3);
    }
  }
  if (run->error) {
    try {
      std::rethrow_exception(run->error);
    } catch (const std::exception& e) {
      ADD_FAILURE() << "query threw: " << e.what();
    }
    return {};
  }
  const unidist::DistanceResult& r = run->result;
  const double allowance = allowanceOf(c), boundSlack = roundingOf(c) + pointQueryResolution(c);
  const ::testing::Message context = ::testing::Message()
                                     << "truth [" << c.truth.lo << ", " << c.truth.hi << "], distance " << r.distance
                                     << ", bounds [" << r.lowerBound << ", " << r.upperBound << "], status "
                                     << unidist::toString(r.status) << ", method " << r.method << ", allowance "
                                     << allowance << ", " << run->seconds << " s CPU";
  EXPECT_TRUE(std::isfinite(r.distance) && finite(r.pointA) && finite(r.pointB) && finite(r.normal)) << context;
  EXPECT_FALSE(std::isnan(r.lowerBound) || std::isnan(r.upperBound)) << context;
  EXPECT_NEAR(r.normal.norm(), 1.0, 1e-9) << context;
  EXPECT_LE(r.lowerBound, c.truth.hi + boundSlack) << context;
  EXPECT_GE(r.upperBound, c.truth.lo - boundSlack) << context;
  EXPECT_LE(r.lowerBound, r.distance + boundSlack) << context;
  EXPECT_GE(r.upperBound, r.distance - boundSlack) << context;
  EXPECT_LE((r.pointB - r.pointA - r.distance * r.normal).norm(), allowance) << context;
  if (r.status == unidist::Status::Certified) {
    EXPECT_GE(r.distance, c.truth.lo - allowance) << context;
    EXPECT_LE(r.distance, c.truth.hi + allowance) << context;
  }
  EXPECT_LE(run->seconds, c.budgetSeconds * kSanitizerSlowdown) << context;
  if (std::getenv("UNIDIST_EXTREMES_VERBOSE")) {
    std::printf("CASE %s | %s | %s | d %.17g truth %.17g err %.2e %s %.4f s %s\n", c.family.c_str(), c.extreme.c_str(),
                c.what.c_str(), r.distance, c.truth.lo, std::max({c.truth.lo - r.distance, r.distance - c.truth.hi, 0.0}),
                unidist::toString(r.status), run->seconds, r.method);
  }
  record(c, r);
  return r;
}

}  // namespace extremes
