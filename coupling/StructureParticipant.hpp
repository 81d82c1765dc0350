#pragma once
// StructureParticipant: the structural solver as one side of a partitioned coupling. It owns a Scene (which
// declares its interface with `coupling: {interface: ...}`), advances it over a fluid step by as many stable
// explicit steps as needed (subcycling), takes the flow's pressure at the interface nodes and returns their
// displacements and velocities. Checkpoints let an implicit coupling repeat a step exactly.
//
// Call sequence per fluid step [t, t + Δt]:
//   setPressure(p(t), p(t+Δt));  advance(Δt);  interfaceDisplacement();   // (+ restoreCheckpoint() to
//   iterate)

#include <filesystem>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/scheme/Solvers.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::coupling {

class StructureParticipant final : public StructureSolver {
 public:
  explicit StructureParticipant(structure::Scene scene);
  StructureParticipant(const std::filesystem::path& sceneFile,
                       const std::vector<std::string>& overrides = {});

  /// Interface in the reference configuration: its points are the interface nodes, in the order of every
  /// per-node array below; its faces are the interface triangles.
  const InterfaceMesh& interfaceMesh() const { return mesh_; }
  int numInterfaceNodes() const { return int(mesh_.points.size()); }

  double time() const { return cd_->time(); }
  /// Structural steps a fluid step of length dt will take (from the current stable step).
  int subcyclesFor(double dt) const;
  long structuralSteps() const { return cd_->steps(); }

  /// Pressure at the interface nodes at the start and the end of the next fluid step [Pa].
  void setPressure(const std::vector<double>& pStart, const std::vector<double>& pEnd);
  /// Integrates [t, t + dt] with the explicit solver (subcycling) under the interpolated pressure.
  void advance(double dt);

  std::vector<double> interfaceDisplacement() const;  ///< 3 per interface node [m]
  std::vector<double> interfaceVelocity() const;      ///< 3 per interface node [m/s], at the last half step
  /// Sum of the interface pressure forces at the current state (for conservation checks) [N].
  std::array<double, 3> interfaceForce() const;

  /// StructureSolver: loads = interface pressure per node at both ends of [t, t+dt]; returns the interface
  /// displacement (3 per node) at t+dt.
  Eigen::VectorXd solve(double t, double dt, const Eigen::VectorXd& loadsStart,
                        const Eigen::VectorXd& loadsEnd) override;
  void saveCheckpoint() override;
  void restoreCheckpoint() override;

  structure::Scene& scene() { return scene_; }
  const structure::CentralDifference& integrator() const { return *cd_; }

 private:
  structure::Scene scene_;
  std::unique_ptr<structure::CentralDifference> cd_;
  InterfaceMesh mesh_;
  std::vector<double> pStart_, pEnd_;
  structure::CentralDifference::Checkpoint checkpoint_;
};

}  // namespace fsi::coupling
