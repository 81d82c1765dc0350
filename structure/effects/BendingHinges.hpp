#pragma once
// BendingHinges: the fabric bending's evaluation (FabricBending) on batches of lanes::kWidth hinges and
// triangles, from constants in structure-of-arrays form laid out once at construction.
//
// The energy Σ_T ½ D A_T tr(S_T²), S_T = B_T Δθ, is a quadratic form in the hinge angles: E = ½ Δθᵀ K Δθ
// with K = Σ_T (signed B_T)ᵀ W_T (signed B_T), W_T = D A_T diag(1, 2, 1). A hinge's row of K has at most five
// entries (itself and the other two edges of each of its two triangles), so each hinge's moment M_h = ∂E/∂θ_h
// is a five-term sum over the angles of the first pass, and its share of the energy ½ Δθ_h M_h (the whole by
// Euler's theorem for a quadratic form). The forces M_h ∂θ_h/∂x: the angle's gradient (hingeAngle) is, on
// each of the hinge's two triangles, that triangle's normal n times |e|/|n|² at its opposite vertex and
// times (o − b)·e/(|e| |n|²), −(o − a)·e/(|e| |n|²) at the edge's ends a, b (e = b − a). So each triangle
// gathers the moments of its (up to three) hinges and adds one multiple of its own normal to each of its
// three vertices. Three passes:
//   angles   (hinges) every hinge's Δθ and 1/|e| into the working memory, and the largest stable-step
//            bound ω² ≤ max_i k_h |g_i| Σ_j |g_j| / m_i of each batch (g = ∂θ/∂x);
//   moments  (hinges) M_h (times 1/|e|) from its row of K; the batch's energy;
//   forces   (triangles, each with the lowest of its hinges, so that a range of hinges writes only to its
//            own nodes) its normal, the three multiples, scatter-added to its three nodes.
// The same arithmetic as the per-triangle formulation (FabricBending::energy, curvature) up to round-off:
// tests/unit/test_fabric_bending.cpp checks the forces against the energy's finite differences and plate
// theory, test_threads.cpp the threaded ranges against the serial evaluation.

#include <cstddef>
#include <vector>

#include "structure/effects/Effect.hpp"

namespace fsi::structure {

struct BendingHinges {
  static constexpr int kNeighbours = 4;  ///< entries of a hinge's row of K besides its own
  int count = 0;                         ///< hinges
  int padded = 0;  ///< count + 1 rounded up to whole batches (the arrays' length; lane `count` is padding)
  std::vector<int> nodes;         ///< 4 × padded: vertex k of hinge h at [k padded + h]
  std::vector<double> theta0;     ///< reference angle
  std::vector<double> stiffness;  ///< k_h = Σ over its triangles of D A_T Σ_r W_r B_r,e²: step bound
  std::vector<double> selfCoef;   ///< K_hh
  std::vector<double> coef;       ///< kNeighbours × padded: K_hj of the neighbours (0 where none)
  std::vector<int> neighbour;     ///< kNeighbours × padded: j (h itself where none)

  /// The triangles with at least one hinge, in the order of the lowest of their hinges.
  int triangles = 0;
  int triPadded = 0;          ///< the arrays' length: triangles plus a batch of padding
  std::vector<int> triNodes;  ///< 3 × triPadded: vertex k of triangle t at [k triPadded + t]
  /// 3 × triPadded: the hinge h of edge k (vertices k, k + 1) where its angle's gradient on this side is
  /// along the triangle's normal (v1 − v0) × (v2 − v0), ~h where against it; `count` (a padded lane: no
  /// moment) where the edge has no hinge.
  std::vector<int> triHinge;
  std::vector<int> batchFirstTriangle;  ///< padded / width + 1: the first triangle of each hinge batch

  /// Doubles of working memory an evaluation needs (Δθ, the scaled moments, a bound and an energy per batch).
  std::size_t scratch() const;
};

/// The angles pass of hinges [begin, end) at coordinates x (begin a multiple of the lane width; the lanes of
/// the last batch past `count` are written too): Δθ, 1/|e| and the batches' step bounds (mass may be null:
/// none) into the working memory.
void bendingAngles(const BendingHinges& h, const double* mass, const double* x, double* scratch, int begin,
                   int end);
/// The moments pass of hinges [begin, end) (after the angles of every hinge), with the batches' energies.
void bendingMoments(const BendingHinges& h, double* scratch, bool wantEnergy, int begin, int end);
/// The forces of the triangles of hinges [begin, end) into ctx.fint (only those hinges' nodes), their stable
/// step and, with ctx.wantEnergy, their energy (after the moments of every hinge).
void bendingForces(const BendingHinges& h, const double* scratch, ForceContext& ctx, int begin, int end);

}  // namespace fsi::structure
