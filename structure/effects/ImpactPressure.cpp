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

ImpactPressureLoad::ImpactPressureLoad(std::string label, std::vector<int> triangleConn, AirStream air,
                                       double cpMax, double exponent, ClothPermeability cloth)
    : label_(std::move(label)),
      conn_(std::move(triangleConn)),
      air_(std::move(air)),
      cpMax_(cpMax),
      exponent_(exponent),
      cloth_(cloth) {}

Connectivity ImpactPressureLoad::connectivity() const {
  Connectivity c;
  c.items = int(conn_.size() / 3);
  c.nodesPerItem = 3;
  c.nodes = conn_.data();
  return c;
}

void ImpactPressureLoad::addRange(ForceContext& ctx, int begin, int end) const {
  const double s = air_.function(ctx.time);
  const std::array<double, 3> U{s * air_.wind[0], s * air_.wind[1], s * air_.wind[2]};
  const double* __restrict x = ctx.x;
  const double* __restrict v = ctx.v;
  double* __restrict f = ctx.fext;
  for (int e = begin; e < end; ++e) {
    const int a = conn_[3 * e], b = conn_[3 * e + 1], c = conn_[3 * e + 2];
    double d21[3], d31[3];
    std::array<double, 3> w{};
    for (int k = 0; k < 3; ++k) {
      d21[k] = x[3 * b + k] - x[3 * a + k];
      d31[k] = x[3 * c + k] - x[3 * a + k];
      w[k] = U[k] - (v ? (v[3 * a + k] + v[3 * b + k] + v[3 * c + k]) / 3.0 : 0.0);
    }
    // d21 × d31 = 2 A n
    const double an[3] = {d21[1] * d31[2] - d21[2] * d31[1], d21[2] * d31[0] - d21[0] * d31[2],
                          d21[0] * d31[1] - d21[1] * d31[0]};
    const double twiceArea = std::sqrt(an[0] * an[0] + an[1] * an[1] + an[2] * an[2]);
    if (!(twiceArea > 0)) continue;
    const std::array<double, 3> n{an[0] / twiceArea, an[1] / twiceArea, an[2] / twiceArea};
    const double p = ctx.loadFactor * impactPressure(n, w, air_.density, cpMax_, exponent_, cloth_).pressure;
    if (p == 0.0) continue;
    const double sixth = p / 6.0;  // p A n / 3 = p (d21 × d31) / 6
    for (int k = 0; k < 3; ++k) {
      f[3 * a + k] += sixth * an[k];
      f[3 * b + k] += sixth * an[k];
      f[3 * c + k] += sixth * an[k];
    }
  }
}

}  // namespace fsi::structure
