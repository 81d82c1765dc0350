#pragma once
// ProjectionVariant: one variant of the L2 projection (ProjectionOptions::mass), one class per file like
// the coupling accelerations: ConsistentProjection (H = M_t⁻¹ C, solves with the LDLᵀ factors of M_t),
// LumpedProjection (H = diag(M_t 1)⁻¹ C), DualProjection (dual test functions: H = D⁻¹ C_ψ). Each assembles
// its rows from the shared set-up (ProjectionRows.hpp) and applies its uncorrected H and Hᵀ; L2Projection
// owns the set-up, picks the variant from the registry (ProjectionRegistry) and adds the defect correction.

#include <Eigen/Core>
#include <vector>

#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/projection/ProjectionRows.hpp"

namespace fsi::coupling {

class ProjectionVariant {
 public:
  using SparseRows = L2Projection::SparseRows;
  virtual ~ProjectionVariant() = default;

  virtual MassMatrix mass() const = 0;
  /// u_t = H u_s and f_s = Hᵀ f_t (uncorrected) for 1 or 3 components, xyz-interleaved; no allocation.
  virtual void apply(const double* us, double* ut, int components) const = 0;
  virtual void applyTranspose(const double* ft, double* fs, int components) const = 0;
  /// H as a sparse matrix (entries below dropTolerance × the row's largest dropped).
  virtual SparseRows matrix(double dropTolerance) const = 0;

  const ProjectionRows& rows() const { return rows_; }

 protected:
  explicit ProjectionVariant(ProjectionRows rows);
  /// H = diag⁻¹ C and its transpose, diag the row sums (lumped: ∫ N_i; dual: D): the lumped and dual apply.
  void applyDiagonal(const double* us, double* ut, int components) const;
  void applyTransposeDiagonal(const double* ft, double* fs, int components) const;
  SparseRows diagonalMatrix() const;

  ProjectionRows rows_;
  Eigen::VectorXd lumpedInv_;  ///< 1 / row sums (0 for a row without support)
  int ns_ = 0, nt_ = 0;

 private:
  template <int K>
  void applyDiagonalK(const double* us, double* ut) const;
  template <int K>
  void applyTransposeDiagonalK(const double* ft, double* fs) const;
};

}  // namespace fsi::coupling
