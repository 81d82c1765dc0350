#pragma once
// InterfacePressure: a pressure FIELD given at the nodes of a set of triangles (what a flow solver delivers
// through the coupling), applied as a follower load: for a triangle with linear p, node a receives
// ∫ N_a p n dA = (A n / 12)(2 p_a + p_b + p_c) on the CURRENT area and normal. Within a coupling window
// [t0, t1] the field is interpolated linearly in time between the start and end values (or held at the end
// value). Default: the MEAN of the start and end values held over the window — the window's trapezoidal
// impulse, as the fluid integrates it; linear interpolation destabilises a subcycled structure under a heavy
// added mass (docs/COUPLING.md).
//
// Alternatively the flow delivers NODAL FORCES (3 per interface node, the conservative transfer Hᵀ f of the
// fluid's face forces): they are added as given, with the same window rule. Forces computed by the fluid
// on its deformed mesh at both window ends need no follower update within the window, and their sum is the
// fluid's interface force to round-off (the Kalro–Tezduyar conservation check).

#include <string>
#include <vector>

#include "structure/effects/Effect.hpp"

namespace fsi::structure {

enum class WindowLoad { Mean, End, Linear };

class InterfacePressure final : public Effect {
 public:
  /// triangleConn: model node indices, 3 per triangle; nodes: the model nodes carrying a pressure value
  /// (their order defines the order of the pressure arrays).
  InterfacePressure(std::vector<int> triangleConn, std::vector<int> nodes);
  std::string name() const override { return "interface_pressure"; }
  void addForces(ForceContext& ctx) const override;

  /// Pressure values (one per interface node) at the start and end of the window [t0, t1].
  void setWindow(double t0, double t1, const std::vector<double>& pStart, const std::vector<double>& pEnd,
                 WindowLoad rule);
  /// Nodal forces (3 per interface node, xyz) at the start and end of [t0, t1]; replaces the pressure.
  void setForceWindow(double t0, double t1, const std::vector<double>& fStart,
                      const std::vector<double>& fEnd, WindowLoad rule);
  bool carriesForces() const { return forces_; }
  const std::vector<int>& nodes() const { return nodes_; }
  /// Interface triangles as model node indices, 3 per triangle.
  std::vector<int> triangles() const {
    std::vector<int> t(conn_.size());
    for (std::size_t i = 0; i < conn_.size(); ++i) t[i] = nodes_[conn_[i]];
    return t;
  }

 private:
  double windowFraction(double time) const;
  void assign(double t0, double t1, const std::vector<double>& start, const std::vector<double>& end,
              WindowLoad rule, bool forces);

  std::vector<int> conn_;        ///< triangles as local interface node indices
  std::vector<int> nodes_;       ///< interface node -> model node
  std::vector<double> p0_, p1_;  ///< pressures (1 per node) or forces (3 per node)
  bool forces_ = false;
  double t0_ = 0, t1_ = 1;
  WindowLoad rule_ = WindowLoad::Mean;
  mutable std::vector<double> p_;  ///< pressure at the current time (scratch, sized once)
};

}  // namespace fsi::structure
