// One CSV row of the tolerance dial (docs/results/dial.csv) and how it is summarised from per-case samples:
// times are per-case medians of repeated calls; errors and bound widths are divided by the case's model size,
// so tolerance, error and width share one dimensionless axis. Benchmark-only.
#pragma once

#include "bench/median.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <string>
#include <vector>

namespace dial {

using Clock = std::chrono::steady_clock;

/// One answer of one method on one case at one setting of its dial.
struct Sample {
  double micros = 0;
  double error = 0;                                          // |answer − truth| / size
  double width = std::numeric_limits<double>::quiet_NaN();   // (upper − lower) / size; NaN: no bounds reported
  bool certified = false;
};

using ::quantile;

/// With DIAL_VERBOSE=1 in the environment every answer is also printed on stderr.
inline void traceAnswer(const std::string& family, const std::string& method, const std::string& what, double setting,
                        double value, double truth, double micros) {
  static const bool verbose = std::getenv("DIAL_VERBOSE") && std::string(std::getenv("DIAL_VERBOSE")) == "1";
  if (verbose)
    std::fprintf(stderr, "  %s | %s | %s | %.0e | value %.15g truth %.15g | %.4g us\n", family.c_str(), method.c_str(),
                 what.c_str(), setting, value, truth, micros);
}

/// Prints the header once, then one row per (family, method, tolerance).
inline void printHeader() {
  std::printf("family,method,tolerance,median_us,p90_us,max_err,median_err,median_bound_width,certified_share\n");
}

inline void printRow(const std::string& family, const std::string& method, double tolerance,
                     const std::vector<Sample>& samples, bool reportsBounds) {
  std::vector<double> t, e, w;
  int certified = 0;
  for (const Sample& s : samples) {
    t.push_back(s.micros);
    e.push_back(s.error);
    if (!std::isnan(s.width)) w.push_back(s.width);
    certified += s.certified;
  }
  const double share = static_cast<double>(certified) / static_cast<double>(std::max<std::size_t>(1, samples.size()));
  std::printf("%s,%s,%.0e,%.4g,%.4g,%.3g,%.3g,%.3g,", family.c_str(), method.c_str(), tolerance, quantile(t, 0.5),
              quantile(t, 0.9), quantile(e, 1.0), quantile(e, 0.5), reportsBounds ? quantile(w, 0.5) : std::nan(""));
  if (reportsBounds) {
    std::printf("%.3g\n", share);
  } else {
    std::printf("nan\n");
  }
  std::fflush(stdout);
}

/// Median wall time (µs) of a call, every call timed (the caller warms lazy hierarchies first); `last` receives
/// the first call's result. Repeated until about `budgetMicros` are spent, 1 to maxReps calls.
template <class F, class R>
double medianMicros(F&& call, R& last, double budgetMicros = 20000, int maxReps = 15) {
  std::vector<double> times;
  double spent = 0;
  while (times.empty() || (spent < budgetMicros && static_cast<int>(times.size()) < maxReps)) {
    const auto t1 = Clock::now();
    if (times.empty()) {
      last = call();
    } else {
      (void)call();
    }
    times.push_back(std::chrono::duration<double, std::micro>(Clock::now() - t1).count());
    spent += times.back();
  }
  return quantile(times, 0.5);
}

/// Requested tolerances, relative to model size: 1e-1 … 1e-12.
inline std::vector<double> decades() {
  std::vector<double> out;
  for (int k = 1; k <= 12; ++k) out.push_back(std::pow(10.0, -k));
  return out;
}

}  // namespace dial
