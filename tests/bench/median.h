// The statistic every benchmark quotes: the median (upper median for an even count; 0 for no samples).
#pragma once

#include <algorithm>
#include <vector>

inline double median(std::vector<double> v) {
  if (v.empty()) return 0;
  const auto mid = v.begin() + static_cast<std::ptrdiff_t>(v.size() / 2);
  std::nth_element(v.begin(), mid, v.end());
  return *mid;
}
