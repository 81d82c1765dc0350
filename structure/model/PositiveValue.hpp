#pragma once
// The one rule for a physical quantity that must be > 0 (a length, a thickness, a density, a modulus, a
// tolerance, a time), shared by the scene reader and the generators.

#include <limits>

namespace fsi::structure {

/// Finite and at least the smallest normal double, 2.2e-308. A subnormal value such as 1e-320 is refused:
/// masses, stiffnesses and steps made from it underflow to 0, or their reciprocals overflow to inf.
inline bool isPositiveNormal(double v) {
  return v >= std::numeric_limits<double>::min() && v <= std::numeric_limits<double>::max();
}

/// How messages state that rule.
inline constexpr const char* kPositiveRule =
    "must be > 0 and at least 2.2e-308 (a smaller, subnormal value underflows)";

}  // namespace fsi::structure
