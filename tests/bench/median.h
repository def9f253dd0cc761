// The statistics every benchmark quotes: the median (upper median for an even count; 0 for no samples) and
// quantiles.
#pragma once

#include <algorithm>
#include <limits>
#include <vector>

inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}

/// The q-quantile (0 <= q <= 1; 1 is the maximum) by rank; NaN for no samples (printed "nan", never a fake 0).
inline double quantile(std::vector<double> v, double q) {
  if (v.empty()) return std::numeric_limits<double>::quiet_NaN();
  std::sort(v.begin(), v.end());
  return v[std::min(v.size() - 1, static_cast<std::size_t>(q * static_cast<double>(v.size())))];
}
