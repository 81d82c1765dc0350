#pragma once
// GapGradient: the gap correction of the L2 projection (ProjectionOptions::gapCorrection): per source
// triangle, the weights of the fitted gradient of a field over its neighbourhood (coupling/mapping/
// L2Projection).

#include <Eigen/Core>
#include <array>
#include <cmath>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/interface/SurfaceSearch.hpp"

namespace fsi::coupling {

// First-order transport of the source field across the gap between the two discrete surfaces. Where they
// do not coincide (a curved surface meshed twice: each mesh's chords lie inside the surface by up to
// h²/8R), a target quadrature point x and its closest source point P(x) are a gap d = x − P(x) apart, and a
// field varying along the normal differs there by d·∇f: the source value at P(x) is the wrong value for x.
// For a field linear in x, y, z the L2 projection then maps even the coordinates with an O(h²) error (so a
// rigid rotation is distorted and Hᵀ does not conserve the moment), and a coarse target is biased by its
// own chord gap h_t²/8R, ~(h_t/h_s)² times the error of nearest-point interpolation from a finer source.
// The fix evaluates f(P(x)) + d·∇f instead, with ∇f the gradient of the least-squares fit
// a + b·(y − c) of the source values over the nodes of the faces around the source triangle's nodes:
// ∇f = Σ_j g_j f_j with Σ_j g_j = 0 (constants, so row sums and the total force are unchanged) and
// Σ_j g_j x_jᵀ = I (exact for linear fields). The surface's own curvature is what makes the normal
// derivative observable; on a flat neighbourhood it is not, and only the tangential part is used (the gap
// of two coinciding flat surfaces is zero anyway).
class GapGradient {
 public:
  struct Entry {
    int node;
    std::array<double, 3> g;
  };

  GapGradient(const InterfaceMesh& mesh, const FanTriangulation& fan, double minRadius);

  // Builds the stencils of the triangles flagged in `used`, in triangle order.
  void build(const std::vector<unsigned char>& used) {
    for (int t = 0; t < fan_.numTriangles(); ++t) {
      start_[std::size_t(t)] = int(entries_.size());
      if (used[std::size_t(t)]) buildOne(t);
    }
    start_.back() = int(entries_.size());
  }
  const Entry* begin(int t) const { return entries_.data() + start_[std::size_t(t)]; }
  const Entry* end(int t) const { return entries_.data() + start_[std::size_t(t) + 1]; }
  long entries() const { return long(entries_.size()); }
  long flatTriangles = 0;

 private:
  void buildOne(int t);

  // Bounds on a patch: the stencils are stored for every source triangle hit (32 bytes per patch node), so a
  // target many times coarser than the source must not make them grow as the ratio squared; beyond these
  // the fit is noisier (Hᵀ less smooth), never inexact.
  static constexpr int kMaxRings = 16;
  static constexpr std::size_t kMaxPatch = 256;

  const InterfaceMesh& mesh_;
  const FanTriangulation& fan_;
  double minRadius_;
  std::vector<int> start_, mark_, nodeFaceStart_, nodeFaces_, patch_;
  std::vector<Eigen::Vector3d> faceNormal_;
  std::vector<Entry> entries_;
};

/// A gap d = x − P(x) at round-off of the source's mean edge `sourceEdge`: coinciding surfaces, where a gap
/// correction would only add entries of round-off size to C.
inline bool negligibleGap(const std::array<double, 3>& d, double sourceEdge) {
  return std::abs(d[0]) + std::abs(d[1]) + std::abs(d[2]) <= 1e-12 * sourceEdge;
}

}  // namespace fsi::coupling
