#pragma once
// Summary statistics of the benchmark reports (NaN for an empty list).

#include <algorithm>
#include <cmath>
#include <numeric>
#include <vector>

namespace ccbuild::bench {

inline double mean(const std::vector<double>& v) {
  return v.empty() ? NAN : std::accumulate(v.begin(), v.end(), 0.0) / v.size();
}
inline double max_of(const std::vector<double>& v) {
  return v.empty() ? NAN : *std::max_element(v.begin(), v.end());
}
inline double min_of(const std::vector<double>& v) {
  return v.empty() ? NAN : *std::min_element(v.begin(), v.end());
}
/// The middle value (the upper one of the two middle values for an even count).
inline double median(std::vector<double> v) {
  if (v.empty()) return NAN;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace ccbuild::bench
