#pragma once
// BendingHinges: the fabric bending's evaluation (FabricBending) on batches of lanes::kWidth hinges, from
// per-hinge constants in structure-of-arrays form laid out once at construction.
//
// The energy Σ_T ½ D A_T tr(S_T²), S_T = B_T Δθ, is a quadratic form in the hinge angles: E = ½ Δθᵀ K Δθ
// with K = Σ_T (signed B_T)ᵀ W_T (signed B_T), W_T = D A_T diag(1, 2, 1). A hinge's row of K has at most five
// entries (itself and the other two edges of each of its two triangles), so each hinge's moment ∂E/∂θ_h is a
// five-term sum over the angles of the first pass, and its share of the energy ½ Δθ_h ∂E/∂θ_h (the whole
// by Euler's theorem for a quadratic form). Two passes:
//   angles  every hinge's Δθ into the working memory (one double per hinge): gathered nodes, two normals,
//           atan2 in lanes (lanes::atan2);
//   forces  each hinge's moment, the angle's exact gradient (recomputed from the gathered nodes: cheaper
//           than storing 12 doubles per hinge and reading them back), its forces scatter-added to its four
//           nodes lane by lane, and its stable-step bound ω² ≤ max_i k_h |g_i| Σ_j |g_j| / m_i.
// The same arithmetic as the per-triangle formulation (FabricBending::energy, curvature) up to round-off:
// tests/unit/test_fabric_bending.cpp checks the forces against the energy's finite differences and plate
// theory, test_threads.cpp the threaded ranges against the serial evaluation.

#include <vector>

#include "structure/effects/Effect.hpp"

namespace fsi::structure {

struct BendingHinges {
  static constexpr int kNeighbours = 4;  ///< entries of a hinge's row of K besides its own
  int count = 0;                         ///< hinges
  int padded = 0;                        ///< count rounded up to whole batches (the arrays' length)
  std::vector<int> nodes;                ///< 4 × padded: vertex k of hinge h at [k padded + h]
  std::vector<double> theta0;            ///< reference angle
  std::vector<double> stiffness;  ///< k_h = Σ over its triangles of D A_T Σ_r W_r B_r,e²: step bound
  std::vector<double> selfCoef;   ///< K_hh
  std::vector<double> coef;       ///< kNeighbours × padded: K_hj of the neighbours (0 where none)
  std::vector<int> neighbour;     ///< kNeighbours × padded: j (h itself where none)
};

/// Δθ of hinges [begin, end) at coordinates x into dtheta (padded doubles; begin a multiple of the lane
/// width; the lanes of the last batch past `count` are written too).
void bendingAngles(const BendingHinges& h, const double* x, double* dtheta, int begin, int end);
/// The forces of hinges [begin, end) into ctx.fint (only their own nodes), their stable step (mass may be
/// null: none) and, with ctx.wantEnergy, their energy. Every hinge's Δθ in dtheta.
void bendingForces(const BendingHinges& h, const double* mass, const double* dtheta, ForceContext& ctx,
                   int begin, int end);

}  // namespace fsi::structure
