// The median of repeated timings, as the benchmarks report them (0 for none).
#pragma once

#include <algorithm>
#include <vector>

namespace fcc::cli {

inline double median(std::vector<double> values) {
  std::sort(values.begin(), values.end());
  const std::size_t n = values.size();
  return n == 0 ? 0.0 : n % 2 ? values[n / 2] : 0.5 * (values[n / 2 - 1] + values[n / 2]);
}

}  // namespace fcc::cli
