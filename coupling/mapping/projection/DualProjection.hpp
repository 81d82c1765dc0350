#pragma once
// DualProjection: H = D⁻¹ C_ψ with dual (biorthogonal) test functions. On face f, ψ_a = Σ_b A_f,ab N_b with
// A_f = D_f M_f⁻¹ (M_f the face's mass matrix, D_f its row sums), so that ∫_f ψ_a N_b = δ_ab ∫_f N_a: the
// projection's mass matrix is exactly diagonal, H is as sparse as C, and every field of the target space is
// still reproduced (Σ_a ψ_a = 1 and ∫ψ_a = ∫N_a on every face) — for large meshes
// (ProjectionOptions::mass = Dual, and Auto above kAutoConsistentMaxNodes; coupling/mapping/L2Projection).

#include <memory>

#include "coupling/mapping/projection/ProjectionVariant.hpp"

namespace fsi::coupling {

class DualProjection final : public ProjectionVariant {
 public:
  DualProjection(const ProjectionSetup& setup, ProjectionReport& report);
  MassMatrix mass() const override { return MassMatrix::Dual; }
  void apply(const double* us, double* ut, int components) const override {
    applyDiagonal(us, ut, components);
  }
  void applyTranspose(const double* ft, double* fs, int components) const override {
    applyTransposeDiagonal(ft, fs, components);
  }
  SparseRows matrix(double /*dropTolerance*/) const override { return diagonalMatrix(); }
};

/// The target quadrature of a dual projection must record every fan triangle's own points (perTriangle).
std::unique_ptr<ProjectionVariant> makeDualProjection(const ProjectionSetup& setup, ProjectionReport& report);

}  // namespace fsi::coupling
