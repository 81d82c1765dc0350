#pragma once
// SurfaceSmoothing: a field on an interface mesh's points smoothed over a length ℓ, as one implicit step of
// the heat equation on the surface: (M + ℓ² K) u = M d, i.e. S = (M + ℓ² K)⁻¹ M.
//
//   K  the surface Laplacian as a weighted graph Laplacian of the mesh's edges, w_e = Σ_faces 2 A_f /
//      (n_f |e|²) (the faces on the edge, n_f their vertex counts): the 5-point Laplacian on a square grid
//      and the cotangent weights on equilateral triangles, non-negative on any mesh (so S averages, never
//      overshoots);
//   M  the lumped area of each point, Σ_faces A_f / n_f.
// A Fourier mode of wavenumber k is damped by 1 / (1 + (kℓ)²): with ℓ = 1 cm a canopy cell's ballooning
// (wavelength 37 cm) keeps 97 % of its amplitude, a crumple 3 cm long keeps a fifth.
// S keeps constants exactly (K1 = 0), so a translation moves the surface unchanged. Its transpose
// Sᵀ = M (M + ℓ² K)⁻¹ carries nodal forces the other way: Sᵀ keeps their sum exactly and the pair is
// work-consistent, f·(S d) = (Sᵀ f)·d, so a transfer composed with it (H' = S H, loads Hᵀ Sᵀ) stays
// conservative.
// Why: a membrane crumples where it is compressed (a ram-air canopy's scalloped trailing edge) at the scale
// of its elements, and a fluid mesh moved onto those creases folds its cells; the flow should see the
// crumpled region's mean surface (docs/RAMAIR.md, docs/COUPLING.md).

#include <Eigen/SparseCholesky>
#include <Eigen/SparseCore>

#include "coupling/interface/InterfaceMesh.hpp"

namespace fsi::coupling {

class SurfaceSmoothing {
 public:
  /// length ℓ > 0 [m]; throws std::invalid_argument for a non-positive length or a mesh with a face of zero
  /// area or no faces.
  SurfaceSmoothing(const InterfaceMesh& mesh, double length);
  /// out = S in, `components` interleaved values per point (in and out may be the same array).
  void apply(const double* in, double* out, int components) const;
  /// out = Sᵀ in (nodal forces), the same layout.
  void applyTranspose(const double* in, double* out, int components) const;
  double length() const { return length_; }
  int points() const { return int(area_.size()); }

 private:
  double length_;
  Eigen::VectorXd area_;  ///< M
  Eigen::SimplicialLDLT<Eigen::SparseMatrix<double>> solver_;
  mutable Eigen::VectorXd rhs_, sol_;
};

}  // namespace fsi::coupling
