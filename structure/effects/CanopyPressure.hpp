#pragma once
// CanopyPressure: the semi-empirical load on a round canopy in a relative wind, for structure-only inflation
// and descent runs without a flow solver (docs/ROUND_CANOPY.md, "Inflation"). Two parts, on every triangle
// along its outward normal n̂ (out of the canopy):
//
//   inside   one pressure p_in for the whole canopy: the air that enters the mouth. Quasi-steady Bernoulli
//            from the free stream to the mouth and continuity of the air inside,
//              p_in = ½ ρ (W² − u_m |u_m|),    u_m = (V̇ + Q_out(p_in)) / A_m,
//            W the canopy's speed relative to the air (the wind minus the mean velocity of its nodes), A_m
//            the mouth's area seen along the wind, V̇ the rate of the canopy's volume (Σ (v̄ − V)·n̂ A over the
//            triangles, relative to the canopy's mean velocity V), Q_out the air that leaves through porous
//            cloth (A_cloth · u(p_in), u the cloth's Darcy–Forchheimer through-flow) and the vent
//            (C_v A_vent √(2 p_in / ρ)). A canopy at rest holding all its air has p_in = ½ ρ W², the
//            stagnation pressure; a canopy growing faster than air can enter its mouth draws p_in down,
//            which is what makes the filling take time (the classical filling distance). p_in is bounded
//            below by −k ½ ρ W² (k: suction_limit).
//   outside  the modified-Newtonian impact law on the outer face wherever the local relative wind w (wind
//            minus the triangle's velocity) meets it (n̂·ŵ < 0): C_p,max ½ ρ |w|² |n̂·ŵ|ⁿ pressing in, less
//            what porous cloth lets through (ImpactPressure's porousReduction); on the leeward outer face a
//            uniform wake suction C_wake ½ ρ W² pulling out.
//
// Assumed: the air inside is one uniform pressure (no inflation front travelling up the canopy), the flow is
// quasi-steady (the air moved with the cloth only as the scene's optional apparent mass), the mouth is the
// skirt polygon projected normal to the wind. The pure functions and the effect (one pass: the inside
// pressure is a sum over the whole canopy).

#include <array>
#include <string>
#include <vector>

#include "structure/effects/AerodynamicDrag.hpp"
#include "structure/effects/Effect.hpp"
#include "structure/effects/ImpactPressure.hpp"

namespace fsi::structure {

struct CanopyPressureParams {
  double cpMax = 1.0;          ///< C_p,max of the impact law on the outside
  double exponent = 2.0;       ///< n of cosⁿ
  double wakeCp = 0.0;         ///< C_wake: suction on the leeward outer face, in ½ ρ W²
  double ventDischarge = 0.6;  ///< C_v of the vent (orifice discharge coefficient)
  double suctionLimit = 1.0;   ///< k: p_in ≥ −k ½ ρ W²
  ClothPermeability cloth;
};

/// The through-flow u ≥ 0 of cloth at a pressure drop dp: a μ u + b ρ u² = max(dp, 0) (0 for impermeable
/// cloth).
double clothThroughFlow(double dp, double density, const ClothPermeability& cloth);

/// What the inside of a canopy sees at one instant.
struct CanopyState {
  double speed = 0;       ///< W: the canopy's speed relative to the air [m/s]
  double mouthArea = 0;   ///< A_m [m²]
  double volumeRate = 0;  ///< V̇ [m³/s]
  double clothArea = 0;   ///< A_cloth [m²]
  double ventArea = 0;    ///< A_vent [m²]
};

/// p_in solving p = ½ ρ (W² − u_m|u_m|), u_m = (V̇ + Q_out(p)) / A_m (monotone in p: bisection to round-off),
/// bounded below by −k ½ ρ W². 0 with W = 0; −k ½ ρ W² with A_m = 0 and air leaving or the canopy growing.
double insidePressure(const CanopyState& s, double density, const CanopyPressureParams& prm);

/// The area of the polygon through `points` (x y z interleaved) projected on the plane normal to the unit
/// vector `axis`, the points taken in the order of their azimuth about their centroid (a star-shaped
/// mouth or vent).
double projectedRingArea(const std::vector<double>& points, const std::array<double, 3>& axis);

/// The canopy pressure on `triangleConn` (model nodes, 3 per triangle) in the wind U f(t): the mouth the
/// nodes `mouth` (the skirt), the vent the nodes `vent` (none: empty). A follower load on the current area
/// and normal; scaled by the load factor.
class CanopyPressureLoad final : public Effect {
 public:
  CanopyPressureLoad(std::string label, std::vector<int> triangleConn, std::vector<int> mouth,
                     std::vector<int> vent, AirStream air, CanopyPressureParams params);
  std::string name() const override { return "canopy_pressure:" + label_; }
  void addForces(ForceContext& ctx) const override;
  /// The canopy's state at positions x and velocities v (null: at rest) at time t.
  CanopyState state(const double* x, const double* v, double time) const;

 private:
  std::string label_;
  std::vector<int> conn_, mouth_, vent_, canopyNodes_;
  AirStream air_;
  CanopyPressureParams prm_;
};

}  // namespace fsi::structure
