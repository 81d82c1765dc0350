#pragma once
// LumpedProjection: H = diag(M_t 1)⁻¹ C with the nodal test functions: sparse, rows sum to 1; linear fields
// are reproduced only on symmetric meshes (ProjectionOptions::mass = Lumped; coupling/mapping/L2Projection).

#include <memory>

#include "coupling/mapping/projection/ProjectionVariant.hpp"

namespace fsi::coupling {

class LumpedProjection final : public ProjectionVariant {
 public:
  LumpedProjection(const ProjectionSetup& setup, ProjectionReport& report);
  MassMatrix mass() const override { return MassMatrix::Lumped; }
  void apply(const double* us, double* ut, int components) const override {
    applyDiagonal(us, ut, components);
  }
  void applyTranspose(const double* ft, double* fs, int components) const override {
    applyTransposeDiagonal(ft, fs, components);
  }
  SparseRows matrix(double /*dropTolerance*/) const override { return diagonalMatrix(); }
};

std::unique_ptr<ProjectionVariant> makeLumpedProjection(const ProjectionSetup& setup,
                                                        ProjectionReport& report);

}  // namespace fsi::coupling
