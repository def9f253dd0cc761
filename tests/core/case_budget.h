// Shared by the randomized core tests: case counts scaled for debug builds, constants, short number text.
#pragma once

#include <algorithm>
#include <cstdio>
#include <limits>
#include <string>

namespace unidist::testing {

constexpr double kInf = std::numeric_limits<double>::infinity();
constexpr double kPi = 3.14159265358979323846;

// Random-case counts are divided by kReduce in debug builds (unoptimised Eigen is ~50x slower), never to none.
#ifdef NDEBUG
constexpr int kReduce = 1;
#else
constexpr int kReduce = 10;
#endif
inline int cases(int n) { return std::max(n / kReduce, 2); }

inline std::string sci(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

}  // namespace unidist::testing
