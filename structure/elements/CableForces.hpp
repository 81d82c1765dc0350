#pragma once
// CableForces: tension-only two-node cables. Engineering strain ε = (L − L0)/L0, tension T = EA max(0, ε)
// (a cable buckles at once under compression), optional Rayleigh β and linear bulk viscosity on ε̇.
// Stable step: L0/c with c = sqrt(E/ρ) (the axial stiffness EA/L0 does not soften when the cable stretches).
// Evaluation: batches of lanes::kWidth cables in vector lanes (CableBatch.hpp) on structure-of-arrays data
// laid out at construction (the two end nodes' offsets in separate arrays, the viscous coefficient per
// cable), the per-cable loop for each block's remainder and as the reference. Threads evaluate it in
// contiguous cable ranges (whole batches; effects/ThreadedForces.hpp) when it has kMinParallelItems cables
// or more; fewer run whole on the first thread. Mass scaling must precede
// construction (wave speeds are cached).

#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/elements/ElementKind.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

/// Rayleigh β and bulk viscosity b1 on the strain rate (ρ, c the element's own after mass scaling).
using CableViscosity = ElementDamping;

/// Which loop evaluates the cables: batches of lanes::kWidth in vector lanes (CableBatch.hpp, the default)
/// or one cable at a time (the reference the batched kernel is tested and benchmarked against).
enum class CableKernel { Batched, PerElement };

/// What the batched kernel reads besides the model's arrays, laid out once at construction.
struct CableLanes {
  /// The two end nodes of every cable as offsets into the node arrays (3 × node index): conn split in two.
  std::vector<int> first, second;
  /// Viscous coefficient (β + b1 L0/c) EA of every cable [N s]: T += coefficient · ε̇ (empty without damping).
  std::vector<double> viscous;
};

class CableForces final : public Effect {
 public:
  CableForces(const Cables& cables, CableViscosity viscosity, CableKernel kernel = CableKernel::Batched);
  std::string name() const override { return "cable"; }
  void addForces(ForceContext& ctx) const override;
  /// The cables, 2 nodes each, in batches of the kernel's width; scattered (a small set, e.g. lines from a
  /// canopy to a confluence point, spans the node numbering: it runs whole rather than through the
  /// threads' seam buffers).
  Connectivity connectivity() const override;
  void addRange(ForceContext& ctx, int begin, int end) const override;
  /// Elastic tension [N] of every cable at configuration x.
  void evaluate(const double* x, std::vector<double>& tension) const;

 private:
  const Cables& el_;
  CableViscosity visc_;
  CableKernel kernel_;
  CableLanes lanes_;
  double minDt_ = 0;  ///< the cable step depends only on reference data: computed once
};

/// Elastic tension [N] of every cable at configuration x.
void cableTensions(const Cables& cables, const double* x, std::vector<double>& tension);

}  // namespace fsi::structure
