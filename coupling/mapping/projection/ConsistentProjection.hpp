#pragma once
// ConsistentProjection: H = M_t⁻¹ C with the nodal test functions, the exact L2 projection (reproduces
// linear fields). H is dense, so it is never formed: apply = sparse C, then the LDLᵀ factors of M_t (AMD
// ordering; fill grows ~N log N), solved by hand for 1 or 3 components per pass over L
// (ProjectionOptions::mass = Consistent; coupling/mapping/L2Projection).

#include <memory>
#include <vector>

#include "coupling/mapping/projection/ProjectionVariant.hpp"

namespace fsi::coupling {

class ConsistentProjection final : public ProjectionVariant {
 public:
  /// Assembles and factors M_t; throws fsi::InputError when it is not positive definite.
  ConsistentProjection(const ProjectionSetup& setup, ProjectionReport& report);
  MassMatrix mass() const override { return MassMatrix::Consistent; }
  void apply(const double* us, double* ut, int components) const override;
  void applyTranspose(const double* ft, double* fs, int components) const override;
  /// Column j of H = M⁻¹ (column j of C), entries below dropTolerance × the row's largest dropped.
  SparseRows matrix(double dropTolerance) const override;

 private:
  void factor(const InterfaceMesh& target);
  template <int K>
  void solveInPlace(double* z) const;  // z ← (L D Lᵀ)⁻¹ z in the permuted ordering
  template <int K>
  void applyK(const double* us, double* ut) const;
  template <int K>
  void applyTransposeK(const double* ft, double* fs) const;

  // P M_t Pᵀ = L D Lᵀ, target row i sits at perm_[i] of the permuted ordering. L is kept in compressed
  // columns (unit diagonal not stored) for hand-written solves that handle 3 components per pass over L.
  std::vector<int> perm_, lp_, li_;
  std::vector<double> lx_, dinv_;
  mutable std::vector<double> scratch_;
};

std::unique_ptr<ProjectionVariant> makeConsistentProjection(const ProjectionSetup& setup,
                                                            ProjectionReport& report);

}  // namespace fsi::coupling
