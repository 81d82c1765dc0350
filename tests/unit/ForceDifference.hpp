#pragma once
// The measure the tests that compute the same forces two ways (batched against per-element kernels,
// threaded against serial) compare with: the largest difference over all components, relative to the
// reference's largest component.
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

namespace fsi::structure::test {

/// max_i |a_i − ref_i| / max_i |ref_i|; when the reference is all zero (e.g. every cable slack), 0 if `a` is
/// too and infinity otherwise, so a test against a tolerance fails.
inline double largestRelativeDifference(const std::vector<double>& a, const std::vector<double>& ref) {
  double diff = 0, scale = 0;
  for (std::size_t i = 0; i < ref.size(); ++i) {
    diff = std::max(diff, std::abs(a[i] - ref[i]));
    scale = std::max(scale, std::abs(ref[i]));
  }
  if (scale > 0) return diff / scale;
  return diff > 0 ? std::numeric_limits<double>::infinity() : 0.0;
}

}  // namespace fsi::structure::test
