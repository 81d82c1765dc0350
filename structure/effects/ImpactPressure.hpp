#pragma once
// ImpactPressure: the semi-empirical pressure on parachute cloth in a relative wind, for structure-only runs
// (inflation, descent) without a flow solver: largest where the cloth faces the wind, falling with its
// inclination, and reduced by the air the cloth lets through.
//
//   impermeable cloth   Δp₀ = C_p,max · ½ ρ |w|² · cⁿ,   c = max(0, n̂·ŵ)
//     (the modified-Newtonian impact law: n = 2, C_p,max the stagnation value, 1 for incompressible flow;
//      w the relative wind, air velocity minus cloth velocity; n̂ the cloth's normal; cloth seen edge-on
//      or from behind carries nothing)
//   porous cloth        the through-flow u takes the pressure the cloth sees down to Δp = Δp₀ (1 − (u/V_n)²),
//                       V_n = c|w| the wind's normal part (the flow that passes is not stopped), and the
//                       cloth passes what its law allows at that drop: Δp = a μ u + b ρ u²
//                       (Darcy–Forchheimer, docs/ROUND_CANOPY.md "Porous fabric"). Both hold at
//                         (b ρ + Δp₀/V_n²) u² + a μ u − Δp₀ = 0,
//                       the positive root; u = V_n for a = b = 0 (no load), u → 0 for a tight cloth (Δp →
//                       Δp₀).
//
// The reduction is this project's model, stated in docs/ROUND_CANOPY.md with its assumptions; the impact law
// is the classical one. The pure functions, and the effect that applies them per triangle
// (ImpactPressureLoad).

#include <array>
#include <string>
#include <vector>

#include "structure/effects/AerodynamicDrag.hpp"
#include "structure/effects/Effect.hpp"

namespace fsi::structure {

/// Darcy–Forchheimer coefficients of a cloth: Δp = a μ u + b ρ u² (u the through-flow).
struct ClothPermeability {
  double a = 0;               ///< viscous (Darcy) coefficient [1/m]; 0 with b = 0: impermeable
  double b = 0;               ///< inertial (Forchheimer) coefficient [-]
  double viscosity = 1.8e-5;  ///< μ of the air [Pa s]
  bool porous() const { return a > 0 || b > 0; }
};

struct ImpactLoad {
  double pressure = 0;     ///< Δp on the cloth, along its normal [Pa]
  double throughFlow = 0;  ///< u through the cloth [m/s] (0 for impermeable cloth)
};

/// The pressure drop and through-flow of porous cloth whose impermeable pressure would be dp0 [Pa] in a
/// wind of normal part vn [m/s] (dp0 >= 0, vn >= 0). Impermeable cloth (cloth.porous() false): {dp0, 0}.
ImpactLoad porousReduction(double dp0, double vn, double density, const ClothPermeability& cloth);

/// The load on cloth with unit normal `normal` in the relative wind `wind` [m/s].
ImpactLoad impactPressure(const std::array<double, 3>& normal, const std::array<double, 3>& wind,
                          double density, double cpMax, double exponent, const ClothPermeability& cloth);

/// The impact pressure on triangles in a uniform wind U·f(t) (AirStream), relative to each triangle's
/// velocity (the mean of its nodes'): a follower load, p·A·n/3 to each node on the CURRENT area and normal, p
/// from impactPressure() at the triangle's normal. Scaled by the load factor (incremental loading).
class ImpactPressureLoad final : public Effect {
 public:
  /// triangleConn: model node indices, 3 per triangle.
  ImpactPressureLoad(std::string label, std::vector<int> triangleConn, AirStream air, double cpMax,
                     double exponent, ClothPermeability cloth);
  std::string name() const override { return "impact_pressure:" + label_; }
  void addForces(ForceContext& ctx) const override { addRange(ctx, 0, int(conn_.size() / 3)); }
  Connectivity connectivity() const override;
  void addRange(ForceContext& ctx, int begin, int end) const override;

 private:
  std::string label_;
  std::vector<int> conn_;
  AirStream air_;
  double cpMax_, exponent_;
  ClothPermeability cloth_;
};

}  // namespace fsi::structure
