#pragma once
// MomentConservation: nodal loads on an interface corrected to carry a given moment, their sum unchanged.
//
// Why: the conservative transfer F_s = Hᵀ F_f keeps the total force exactly, but the moment only as far as
// H reproduces positions (H x_s = x_f). Between a structure's coarse facets and a finer curved fluid skin it
// does not (the gap between the surfaces, docs/PROJECTION.md), so the structure feels a moment the flow did
// not exert: on the anchored ram-air wing 1e-3 to 5e-3 of the aerodynamic moment, which shifts its trim
// (docs/RAMAIR.md). Static equivalence needs both the force and the moment.
//
// The correction is the smallest traction in the L2 norm on the interface with zero resultant and the
// missing moment ΔM = M_target − Σ x_i × F_i: t(x) = a × (x − c), c the area centroid. As nodal forces
//   δ_i = w_i a × r_i,  r_i = x_i − c,  w_i the lumped area,
// so Σ δ_i = a × Σ w_i r_i = 0 and Σ x_i × δ_i = Σ r_i × δ_i = J a with J = Σ w_i (|r_i|² I − r_i r_iᵀ)
// (the surface's second moment of area, polar form): a = J⁻¹ ΔM.
//
// Work: δ does no work on a rigid translation and exactly the missing θ·ΔM on a rigid rotation θ, so the
// transfer conserves the work of rigid motions, which H alone does not (its H x_s ≠ x_f); on deformations δ
// does work of the size of the defect, which is what the result reports. Where the two surfaces coincide ΔM
// is round-off, and so is δ. J is singular only for points on one line (a cable interface): the moment about
// that line cannot be carried by a traction of this form and is left, reported as `remaining`.

#include <array>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"

namespace fsi::coupling {

struct MomentCorrection {
  std::array<double, 3> defect{};     ///< ΔM before the correction [N m]
  std::array<double, 3> remaining{};  ///< the part of ΔM no traction a × r carries (points on one line)
  double largestNodalForce = 0;       ///< max_i |δ_i| [N]
};

class MomentConservation {
 public:
  /// weights: one per interface point, ≥ 0 and finite, with a positive sum (std::invalid_argument otherwise).
  explicit MomentConservation(std::vector<double> weights);
  /// The weights of a surface: its points' lumped areas; a mesh without faces (cables) weighs its points
  /// equally.
  static MomentConservation onSurface(const InterfaceMesh& mesh);

  /// loads (3 per point, interleaved) += δ, so that Σ x_i × loads_i = targetMoment (moments about the
  /// origin, x the points' current positions, 3 per point).
  MomentCorrection apply(const double* x, double* loads, const std::array<double, 3>& targetMoment) const;

  int points() const { return int(weights_.size()); }

 private:
  std::vector<double> weights_;
};

}  // namespace fsi::coupling
