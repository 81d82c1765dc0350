#pragma once
// FabricBending: the bending stiffness of a fabric (or any thin sheet) on a set of membrane triangles,
// rotation-free: the curvature of each triangle comes from the angles at which its neighbours meet it.
//
//   θ_e       the signed dihedral angle at each interior edge e (shared by exactly two triangles), its change
//             Δθ_e = θ_e − θ0_e from the reference shape;
//   S_T       the triangle's curvature (shape operator, symmetric 2×2 in its own plane), the one uniform
//             curvature that turns its edges by exactly those angles: S_T = B_T Δθ, with B_T (3×3) fixed at
//             the reference. B_T is exact for any uniform curvature on any triangulation: each edge's angle
//             is the jump of the piecewise-linear surface's slope across it, whose dependence on a uniform
//             curvature (the neighbour's centroid offset and both triangles' interpolation bias) is worked
//             out on the reference shape, the neighbour unfolded into the triangle's plane. A free edge says
//             the curvature across it is zero (no moment acts across a free edge);
//   E         = Σ_T ½ D A_T (κ1² + κ2²) = Σ_T ½ D A_T tr(S_T²), D the flexural rigidity [N·m] (a bending
//             Poisson ratio of 0, as woven fabrics nearly have).
// Forces are −∂E/∂x, with the dihedral angle's exact gradient (Bridson, Marino & Fedkiw 2003): they sum to
// zero and have no moment. A simpler hinge energy Σ_e ½ k_e Δθ_e² is mesh dependent (3x too stiff on a
// right-triangle grid, where only one edge in three turns under a cylindrical bend); this one converges to
// plate theory at second order (tests/unit/test_fabric_bending.cpp).
//
// Why a membrane model may need it: a membrane has no bending stiffness, so where the wrinkling law leaves a
// region stress-free in one direction, nothing keeps its mean surface smooth and the nodes can settle into
// element-scale folds. Measured on the ram-air canopy (docs/RAMAIR.md, "ramair-brake"): at the fabric's own
// rigidity it removes the folds that nothing forces, not the crumple of a trailing edge that the ballooning
// cells draw forward.
// The explicit step: each hinge bounds it by 2/ω, ω² ≤ max_i k_e |g_i| Σ_j |g_j| / m_i (Gerschgorin on the
// Gauss–Newton part k_e g gᵀ, g = ∂θ/∂x, k_e the hinge's stiffness through its triangles); for fabric it is
// orders of magnitude longer than the membrane's.

#include <array>
#include <string>
#include <vector>

#include "structure/effects/BendingHinges.hpp"
#include "structure/effects/Effect.hpp"

namespace fsi::structure {

/// The interior edges of a triangle set (3 nodes per triangle in conn) that exactly two of its triangles
/// share: 4 nodes per hinge, the two opposite vertices, then the edge's lower and higher node; and the count
/// of edges where three or more meet (seams). Used by FabricBending and the `folds` probe.
struct InteriorHinges {
  std::vector<int> nodes;
  int seams = 0;
};
InteriorHinges interiorHinges(const std::vector<int>& conn);

class FabricBending final : public Effect {
 public:
  /// conn: model node indices, 3 per triangle; X: reference coordinates (3 per node); mass: the nodes'
  /// lumped masses, read at every evaluation (for the stable step; may be null: no step bound); rigidity
  /// D [N·m].
  FabricBending(std::string label, const std::vector<int>& conn, const std::vector<double>& X,
                const std::vector<double>* mass, double rigidity);
  std::string name() const override { return "bending:" + label_; }
  void addForces(ForceContext& ctx) const override;
  /// The hinges, 4 nodes each, in batches of the lane width (BendingHinges.hpp): two first passes (every
  /// hinge's angle and step bound, then every hinge's moment from its row of the angles' stiffness:
  /// prepareRange with ctx.pass 0, 1), then the forces of the triangles whose lowest hinge is in the range,
  /// on their three nodes, all of them the range's hinges' nodes (addRange). addForces runs the three over
  /// all hinges. Working memory (ForceContext::scratch): BendingHinges::scratch() doubles.
  Connectivity connectivity() const override;
  void addRange(ForceContext& ctx, int begin, int end) const override;
  void prepareRange(const ForceContext& ctx, int begin, int end) const override;

  /// Hinges found (interior edges shared by exactly two triangles) and edges left out because three or more
  /// triangles of the set meet there (a rib's seam: the sheets are not one surface).
  int hinges() const { return int(hingeNodes_.size() / 4); }
  int seams() const { return seams_; }
  /// The bending energy at coordinates x (3 per node).
  double energy(const double* x) const;
  /// The curvature S_T (s11, s12, s22 in the triangle's reference frame) of triangle t at coordinates x.
  std::array<double, 3> curvature(int t, const double* x) const;

 private:
  struct Triangle {
    std::array<int, 3> hinge{-1, -1, -1};  ///< hinge of each edge, −1 on a free edge (or a seam)
    std::array<double, 3> sign{0, 0, 0};   ///< θ of the hinge as this triangle sees it
    std::array<double, 9> B{};             ///< S = B Δθ, row-major (s11, s12, s22) × edges
    double weight = 0;                     ///< D·A_T
  };
  /// Δθ of every hinge at x (scalar, std::atan2: the reference for energy and curvature).
  std::vector<double> hingeAngles(const double* x) const;
  double* scratchIn(double* memory) const;
  /// The per-hinge constants of the batched evaluation (from tris_).
  void layOutHinges();
  /// The triangles of the batched force pass: each with its hinges and their signs, ordered by the lowest.
  void layOutTriangles(const std::vector<int>& conn);
  std::string label_;
  std::vector<int> hingeNodes_;  ///< 4 per hinge: the two opposite vertices, then the edge's two
  std::vector<double> theta0_;
  std::vector<double> hingeStiffness_;  ///< Σ over its triangles of D·A_T·Σ_k B_k,e²: for the stable step
  std::vector<Triangle> tris_;
  BendingHinges batched_;
  const std::vector<double>* mass_ = nullptr;
  int seams_ = 0;
};

/// The signed dihedral angle of the hinge (x1, x2 opposite vertices; x3, x4 the edge) and, if g is given,
/// its gradient (12 values: ∂θ/∂x1 .. ∂θ/∂x4). θ = 0 for a flat hinge and positive when the two triangles
/// turn towards the normal n1 = (x1 − x3) × (x1 − x4) (a bowl open on that side).
double hingeAngle(const double* x1, const double* x2, const double* x3, const double* x4, double* g);

}  // namespace fsi::structure
