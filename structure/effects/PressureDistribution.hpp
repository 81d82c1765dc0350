#pragma once
// PressureDistribution: a follower pressure whose value differs from triangle to triangle — an external
// pressure field from a pressure-coefficient table, a panel code or another flow solver, applied one-way.
// Each triangle holds its own p_e (given once, on the reference geometry) scaled by f(t); like
// FollowerPressure every node of the triangle receives p_e(t) A n / 3 on the CURRENT area and normal.
//
// chordwisePressure() builds the values from a Cp(x/c) table: p = q·Cp at the triangle's reference centroid,
// x/c measured along a chord axis from the leading edge.

#include <array>
#include <string>
#include <utility>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/effects/TimeFunction.hpp"

namespace fsi::structure {

// Follower by default (as FollowerPressure); dead() makes a load fixed in space.
class PressureDistribution final : public Effect {
 public:
  /// triangleConn: model node indices, 3 per triangle; values: one pressure per triangle [Pa] (positive
  /// along the triangle's normal).
  PressureDistribution(std::string label, std::vector<int> triangleConn, std::vector<double> values,
                       TimeFunction f);
  /// The same as a DEAD load: the forces of the pressure on the reference area and normal (reference
  /// coordinates X, 3 per node), fixed in direction and size while the structure moves. A load whose
  /// direction is fixed in space is what makes a line-anchored canopy under a prescribed pressure field
  /// statically well posed: a follower field turns with the canopy, so its moment about the anchor never
  /// vanishes by rotating.
  static PressureDistribution dead(std::string label, std::vector<int> triangleConn,
                                   std::vector<double> values, TimeFunction f, const std::vector<double>& X);
  bool follower() const { return dead_.empty(); }
  std::string name() const override { return "pressure_distribution:" + label_; }
  void addForces(ForceContext& ctx) const override { addRange(ctx, 0, int(sixth_.size())); }
  /// The triangles, 3 nodes each.
  Connectivity connectivity() const override { return {int(sixth_.size()), 3, conn_.data()}; }
  void addRange(ForceContext& ctx, int begin, int end) const override;

 private:
  std::string label_;
  std::vector<int> conn_;
  std::vector<double> sixth_;  ///< p_e / 6 (p A n / 3 = p (d21 × d31) / 6)
  std::vector<double> dead_;   ///< dead load: the force on each node of each triangle, 3 per triangle
  TimeFunction fn_;
};

/// Piecewise-linear table Cp(x/c), abscissae strictly increasing in [0, 1]; constant beyond its ends.
struct CpTable {
  std::vector<double> xc, cp;
  double at(double x) const;
};

/// Pressure q·Cp(x/c) of each triangle (3 node indices per triangle into `X`, reference coordinates, 3 per
/// node) at its centroid, x/c = ((centroid − leadingEdge)·axis) / chord.
std::vector<double> chordwisePressure(const std::vector<double>& X, const std::vector<int>& triangleConn,
                                      const CpTable& table, double dynamicPressure,
                                      std::array<double, 3> leadingEdge, std::array<double, 3> axis,
                                      double chord);

}  // namespace fsi::structure
