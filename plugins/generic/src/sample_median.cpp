#include "ftsense/generic/sample_median.hpp"

#include <algorithm>
#include <cstddef>

namespace ftsense::generic {

double sample_median(std::vector<double> values) {
  const auto middle = values.begin() + static_cast<std::ptrdiff_t>(values.size() / 2);
  std::nth_element(values.begin(), middle, values.end());
  double median = *middle;
  if (values.size() % 2 == 0) median = 0.5 * (median + *std::max_element(values.begin(), middle));
  return median;
}

}  // namespace ftsense::generic
