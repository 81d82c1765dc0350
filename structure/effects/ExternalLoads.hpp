#pragma once
// External loads: follower pressure on surface regions, gravity, nodal forces.

#include <array>
#include <string>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/effects/TimeFunction.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

/// Pressure p(t) = value·f(t) along the CURRENT normal of each triangle on its CURRENT area (a follower
/// load): every node receives p A n / 3. Positive p pushes along the element normal (right-hand rule on the
/// node order), so an outward-oriented closed surface inflates under positive p.
class FollowerPressure final : public Effect {
 public:
  FollowerPressure(std::string label, std::vector<int> triangleConn, double value, TimeFunction f);
  std::string name() const override { return "pressure:" + label_; }
  void addForces(ForceContext& ctx) const override { addRange(ctx, 0, int(conn_.size() / 3)); }
  /// The triangles, 3 nodes each.
  Connectivity connectivity() const override { return {int(conn_.size() / 3), 3, conn_.data()}; }
  void addRange(ForceContext& ctx, int begin, int end) const override;
  double valueAt(double t) const { return value_ * fn_(t); }

 private:
  std::string label_;
  std::vector<int> conn_;  ///< private copy of the region's connectivity: one contiguous sweep
  double value_;
  TimeFunction fn_;
};

/// Body force m g with the PHYSICAL lumped mass (mass scaling must not change the weight).
class Gravity final : public Effect {
 public:
  Gravity(const std::vector<double>& physicalMass, std::array<double, 3> g, TimeFunction f);
  std::string name() const override { return "gravity"; }
  void addForces(ForceContext& ctx) const override { addRange(ctx, 0, int(weight_.size() / 3)); }
  /// The nodes, each writing only to itself; light (m g per node).
  Connectivity connectivity() const override;
  void addRange(ForceContext& ctx, int begin, int end) const override;

 private:
  std::vector<double> weight_;  ///< 3 per node: m g
  TimeFunction fn_;
};

/// The same force vector f(t)·F on every node of a set.
class NodalForces final : public Effect {
 public:
  NodalForces(std::string label, std::vector<int> nodes, std::array<double, 3> force, TimeFunction f);
  std::string name() const override { return "nodal_force:" + label_; }
  void addForces(ForceContext& ctx) const override;

 private:
  std::string label_;
  std::vector<int> nodes_;
  std::array<double, 3> force_;
  TimeFunction fn_;
};

}  // namespace fsi::structure
