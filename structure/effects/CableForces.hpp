#pragma once
// CableForces: tension-only two-node cables. Engineering strain ε = (L − L0)/L0, tension T = EA max(0, ε)
// (a cable buckles at once under compression), optional Rayleigh β and linear bulk viscosity on ε̇.
// Stable step: L0/c with c = sqrt(E/ρ) (the axial stiffness EA/L0 does not soften when the cable stretches).

#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

struct CableViscosity {
  double beta = 0;
  double bulkB1 = 0;
  bool enabled() const { return beta > 0 || bulkB1 > 0; }
};

class CableForces final : public Effect {
 public:
  CableForces(const Cables& cables, CableViscosity viscosity);
  std::string name() const override { return "cable"; }
  void addForces(ForceContext& ctx) const override;
  /// Elastic tension [N] of every cable at configuration x.
  void evaluate(const double* x, std::vector<double>& tension) const;

 private:
  const Cables& el_;
  CableViscosity visc_;
  double minDt_ = 0;  ///< the cable step depends only on reference data: computed once
};

}  // namespace fsi::structure
