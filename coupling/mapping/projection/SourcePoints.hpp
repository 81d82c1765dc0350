#pragma once
// SourcePoints: where every target quadrature point of the L2 projection finds the source surface — the
// closest source point (triangle, barycentric point) or none within the tolerance, the gap x − P(x) for the
// gap correction, and with keepSide the side rule for bodies wetted from one side (coupling/mapping/
// L2Projection).

#include <array>
#include <vector>

#include "coupling/interface/SurfaceSearch.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/projection/Quadrature.hpp"

namespace fsi::coupling {

struct SourcePoints {
  std::vector<int> triangle;                ///< per quadrature point: its source triangle, -1 if unmapped
  std::vector<std::array<double, 3>> bary;  ///< the barycentric point on it
  std::vector<std::array<double, 3>> gap;   ///< x − P(x) (gap correction only; empty otherwise)
};

/// The closest source point of every quadrature point `qp` of the target fan `tf` (gaps kept with
/// `keepGap`; the side rule applied with `keepSide`); unmapped points, the largest gap and the side rule's
/// counts go into `report`.
SourcePoints findSourcePoints(const SurfaceSearch& search, const FanTriangulation& tf,
                              const std::vector<QuadPoint>& qp, bool keepGap, bool keepSide,
                              ProjectionReport& report);

}  // namespace fsi::coupling
