#include "structure/effects/ImpactPressure.hpp"

#include <cmath>

namespace fsi::structure {

ImpactLoad porousReduction(double dp0, double vn, double density, const ClothPermeability& cloth) {
  if (!cloth.porous() || !(dp0 > 0) || !(vn > 0)) return {dp0 > 0 ? dp0 : 0.0, 0.0};
  // (b ρ + Δp₀/V_n²) u² + a μ u − Δp₀ = 0: positive root, written to avoid cancellation when a μ dominates.
  const double qa = cloth.b * density + dp0 / (vn * vn), qb = cloth.a * cloth.viscosity;
  const double u = 2.0 * dp0 / (qb + std::sqrt(qb * qb + 4.0 * qa * dp0));
  const double ratio = u / vn;
  return {dp0 * (1.0 - ratio * ratio), u};
}

ImpactLoad impactPressure(const std::array<double, 3>& normal, const std::array<double, 3>& wind,
                          double density, double cpMax, double exponent, const ClothPermeability& cloth) {
  const double w2 = wind[0] * wind[0] + wind[1] * wind[1] + wind[2] * wind[2];
  if (!(w2 > 0)) return {};
  const double w = std::sqrt(w2);
  const double c = (normal[0] * wind[0] + normal[1] * wind[1] + normal[2] * wind[2]) / w;
  if (!(c > 0)) return {};
  const double dp0 = cpMax * 0.5 * density * w2 * std::pow(c, exponent);
  return porousReduction(dp0, c * w, density, cloth);
}

}  // namespace fsi::structure
