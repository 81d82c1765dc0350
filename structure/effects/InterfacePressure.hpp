#pragma once
// InterfacePressure: the flow's load on a set of triangles, as the coupling delivers it at the interface
// nodes. A PRESSURE field (one value per node) is applied as a follower load: for a triangle with linear p,
// node a receives ∫ N_a p n dA = (A n / 12)(2 p_a + p_b + p_c) on the CURRENT area and normal. NODAL FORCES
// (3 per interface node, the conservative transfer Hᵀ f of the fluid's face forces) are added as given:
// computed by the fluid on its deformed mesh, they need no follower update, and their sum is the fluid's
// interface force to round-off (the Kalro–Tezduyar conservation check).
//
// The effect owns no load. It reads an InterfaceLoad that its owner (coupling/StructureParticipant) writes
// before every structural step: the kind of the values is stated there, never guessed from their number,
// and the integrator's `const Effect*` really is a read-only view. How the load varies inside a coupling
// window (LoadInterpolation) is the coupling library's business (coupling/scheme/TimeInterpolation); the
// enum lives here only because the scene, which the coupling builds on, reads `load_in_window`.

#include <string>
#include <vector>

#include "structure/effects/Effect.hpp"

namespace fsi::structure {

/// How the flow's load varies inside a coupling window [t, t + Δt] known at its two ends
/// (`coupling: {load_in_window: mean | end | linear}`; coupling/scheme/TimeInterpolation.hpp explains each).
enum class LoadInterpolation { ConstantMean, ConstantEnd, Linear };

/// What the values of an InterfaceLoad are.
enum class InterfaceLoadKind {
  Pressure,    ///< one value per interface node [Pa]
  NodalForces  ///< three values per interface node, xyz [N]
};
const char* toString(InterfaceLoadKind kind);

/// The interface load in force now: written by its owner, read by InterfacePressure.
struct InterfaceLoad {
  InterfaceLoadKind kind = InterfaceLoadKind::Pressure;
  std::vector<double> values;  ///< in the order of the interface nodes
};

/// Values an InterfaceLoad of `kind` needs on an interface of `nodes` nodes.
inline std::size_t valuesPerInterface(InterfaceLoadKind kind, std::size_t nodes) {
  return kind == InterfaceLoadKind::Pressure ? nodes : 3 * nodes;
}

class InterfacePressure final : public Effect {
 public:
  /// triangleConn: model node indices, 3 per triangle; nodes: the model nodes of the interface (their order
  /// is the order of the load's values); load: read at every force evaluation, must outlive the effect.
  InterfacePressure(std::vector<int> triangleConn, std::vector<int> nodes, const InterfaceLoad& load);
  std::string name() const override { return "interface_pressure"; }
  void addForces(ForceContext& ctx) const override { addForces(ctx, load_); }
  /// The forces of any load on this interface (e.g. to sum a load that is not the current one).
  void addForces(ForceContext& ctx, const InterfaceLoad& load) const { addRange(ctx, load, 0, triangles()); }
  /// The triangles. Nodal forces are a cheap pass over the interface nodes, cut in proportion: triangles
  /// [b, e) of T add the interface nodes [n b / T, n e / T) (nodeSlice), so the ranges of one evaluation add
  /// each node once, and each triangle's nodes are its 3 and its slice's.
  Connectivity connectivity() const override;
  void addRange(ForceContext& ctx, int begin, int end) const override { addRange(ctx, load_, begin, end); }
  const std::vector<int>& nodes() const { return nodes_; }

 private:
  int triangles() const { return int(conn_.size() / 3); }
  void addRange(ForceContext& ctx, const InterfaceLoad& load, int begin, int end) const;
  std::vector<int> conn_;   ///< triangles as local interface node indices
  std::vector<int> nodes_;  ///< interface node -> model node
  /// The model nodes each triangle writes to (connectivity): triangle e's are itemNodes_[itemOffsets_[e],
  /// itemOffsets_[e + 1]).
  std::vector<int> itemNodes_, itemOffsets_;
  const InterfaceLoad& load_;
};

}  // namespace fsi::structure
