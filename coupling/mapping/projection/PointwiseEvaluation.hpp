#pragma once
// PointwiseEvaluation: the consistent transfer by evaluation at the target nodes. Each target node takes the
// source field at its closest point on the source surface (the fan triangle and barycentric point of
// SurfaceSearch, the fan's centre value split over its face), i.e. nearest-projection interpolation: E is
// sparse (at most 3 source nodes per row for triangles), reproduces constants and — on coinciding surfaces —
// linear fields, and is second order (the error at a node is the source's own interpolation error plus the
// gap between the two surfaces times the field's normal derivative). L2Projection uses it for u_t = E u_s
// when ProjectionOptions::evaluation is Pointwise; the conservative transfer stays Hᵀ of the L2 projection
// (smooth, exact totals). docs/PROJECTION.md, "Consistent direction: pointwise or L2".

#include <vector>

#include "coupling/interface/SurfaceSearch.hpp"
#include "coupling/mapping/L2Projection.hpp"

namespace fsi::coupling {

class PointwiseEvaluation {
 public:
  using SparseRows = L2Projection::SparseRows;
  /// E from the source surface of `search` to the nodes of `target`. Nodes farther than the search's
  /// tolerance get an empty row (value 0) and nodeMapped() 0.
  PointwiseEvaluation(const SurfaceSearch& search, const InterfaceMesh& target);

  /// u_t = E u_s, 1 or 3 components (xyz-interleaved); no allocation.
  void apply(const double* us, double* ut, int components) const;
  const SparseRows& matrix() const { return e_; }
  const std::vector<unsigned char>& nodeMapped() const { return nodeMapped_; }
  int unmappedNodes() const { return unmapped_; }
  double maxGap() const { return maxGap_; }  ///< largest distance of a mapped node to the source surface

 private:
  SparseRows e_;
  std::vector<unsigned char> nodeMapped_;
  int unmapped_ = 0;
  double maxGap_ = 0.0;
};

}  // namespace fsi::coupling
