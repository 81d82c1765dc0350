#pragma once
// StructureParticipant: the structural solver as one side of a partitioned coupling. It owns a Scene (which
// declares its interface with `coupling: {interface: ...}`), takes the flow's load at the interface nodes,
// advances the structure over a fluid step and returns the interface displacements and velocities.
// Checkpoints let an implicit coupling repeat a step exactly.
//
// Subcycling is the coupling library's (coupling/scheme/Subcycling): the participant is a StructureStepper
// over the structure's CentralDifference, and SubcycledStructure takes N = max(subcycles, ceil(Δt /
// Δt_stable)) equal substeps per window, Δt_stable from the window's start state, with the window's load
// filled in by TimeInterpolation (the scene's `load_in_window`). Before every structural step the participant
// writes the load of that instant into the InterfaceLoad it owns; the InterfacePressure effect it adds to the
// integrator only reads it.
//
// How it runs its windows is fixed when it is made (ParticipantOptions: the kind of solve()'s loads, the
// least number of substeps, time-accurate or equilibrium windows); nothing of it is set afterwards.
//
// The load is a pressure per interface node (follower load on the current geometry) or nodal forces, 3 per
// interface node (the conservative transfer of the fluid's face forces; what the OpenFOAM adapter uses).
// Which of the two solve() receives is stated once (ParticipantOptions::loadKind), never guessed from the
// vector's length.
//
// In equilibrium mode (ParticipantOptions::mode) a window does not integrate the motion over Δt: the
// structure relaxes under the window's end load for N damped pseudo-steps (coupling/scheme/Equilibrium) and
// its clock is then set to the window's end; interfaceVelocity() is the window's displacement change over Δt.
//
// Call sequence per fluid step [t, t + Δt]:
//   setPressure(p(t), p(t+Δt)) or setForces(f(t), f(t+Δt));  advance(Δt);  interfaceDisplacement();
//   (+ restoreCheckpoint() to iterate), or, as a StructureSolver of a CouplingScheme (made with the loads'
//   kind in its options): solve(t, Δt, loads(t), loads(t+Δt)) per pass.

#include <Eigen/Dense>
#include <filesystem>
#include <map>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/scheme/Equilibrium.hpp"
#include "coupling/scheme/Solvers.hpp"
#include "coupling/scheme/Subcycling.hpp"
#include "structure/effects/InterfacePressure.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/io/SceneFrames.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::coupling {

/// advance() found a non-finite state; what() is the diagnosis (structure/run/InstabilityDiagnosis). The
/// checkpoint (start of the window) still holds the last stable state: restoreCheckpoint() returns to it.
class StructureUnstable : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// How a participant runs its windows, given once to its constructor (the adapter's `subcycles`,
/// `structureMode`, `equilibrium*` options; its loads are nodal forces).
struct ParticipantOptions {
  /// What the loads of solve() are: a pressure per interface node, or nodal forces, 3 per node.
  structure::InterfaceLoadKind loadKind = structure::InterfaceLoadKind::Pressure;
  /// At least this many structural steps per fluid step (1 = as the stability limit allows); < 1 makes the
  /// constructor throw std::invalid_argument. Used to show that subcycling does not change a coupled answer
  /// beyond the time-discretisation error.
  int minSubcycles = 1;
  /// Time-accurate (default) or equilibrium windows, the latter with `equilibrium.steps` damped pseudo-steps
  /// per window (< 1 throws std::invalid_argument), started from rest or carried over.
  StructureMode mode = StructureMode::TimeAccurate;
  EquilibriumOptions equilibrium;
};

class StructureParticipant final : public StructureSolver {
 public:
  explicit StructureParticipant(structure::Scene scene, const ParticipantOptions& options = {});
  StructureParticipant(const std::filesystem::path& sceneFile, const std::vector<std::string>& overrides = {},
                       const ParticipantOptions& options = {});
  ~StructureParticipant() override;
  StructureParticipant(StructureParticipant&&) noexcept;
  StructureParticipant& operator=(StructureParticipant&&) noexcept;

  /// Interface in the reference configuration: its points are the interface nodes, in the order of every
  /// per-node array below; its faces are the interface triangles.
  const InterfaceMesh& interfaceMesh() const { return mesh_; }
  int numInterfaceNodes() const { return int(mesh_.points.size()); }

  double time() const { return cd_->time(); }
  /// Sets the structure's clock to `t` (state unchanged): a restart takes the fluid's time, which OpenFOAM
  /// reads from the time directory's name, rounded to its timePrecision (the state file keeps the exact one).
  void alignTime(double t);
  /// Structural steps a fluid step of length dt takes: subcycleCount() of the stable step at the last force
  /// evaluation (advance() evaluates it at the window's start state), at least
  /// ParticipantOptions::minSubcycles.
  int subcyclesFor(double dt) const;
  long structuralSteps() const { return cd_->steps(); }

  /// What the loads of solve() are (ParticipantOptions::loadKind). setPressure/setForces set it too.
  structure::InterfaceLoadKind loadKind() const { return kind_; }
  /// Pressure at the interface nodes at the start and the end of the next fluid step [Pa].
  void setPressure(const std::vector<double>& pStart, const std::vector<double>& pEnd);
  /// Nodal forces (3 per interface node, xyz) at the start and the end of the next fluid step [N].
  void setForces(const std::vector<double>& fStart, const std::vector<double>& fEnd);
  StructureMode structureMode() const {
    return equilibrium_ ? StructureMode::Equilibrium : StructureMode::TimeAccurate;
  }
  /// The last window's relaxation (equilibrium mode; all zero otherwise).
  EquilibriumReport equilibriumReport() const;
  /// Static residual at the current state under the window's end load: max |f_ext − f_int| over the free dofs
  /// over the largest support reaction (or the largest applied force without supports), as the structure's
  /// dynamic relaxation measures it; 0 at equilibrium. Evaluates the forces (does not move the structure).
  double staticResidualRatio();
  /// Integrates [t, t + dt] with the explicit solver (subcycling) under the interpolated pressure; throws
  /// StructureUnstable (with a diagnosis) if the state becomes non-finite.
  void advance(double dt);
  /// The same up to exactly tEnd: solve() ends each window on the scheme's window end, so the structure's
  /// clock does not drift from the fluid's by summing window sizes.
  void advanceTo(double tEnd);

  std::vector<double> interfaceDisplacement() const;  ///< 3 per interface node [m]
  /// 3 per interface node [m/s]: at the last half step; in equilibrium mode the last window's displacement
  /// change over its length.
  std::vector<double> interfaceVelocity() const;
  /// Sum of the interface forces at the current state (for conservation checks) [N], under the window's load
  /// at its end as the window rule sees it (the mean of both ends for `mean`, the end value otherwise).
  std::array<double, 3> interfaceForce() const;

  /// StructureSolver: loads of loadKind() at both ends of [t, t+dt] (pressure: numInterfaceNodes() values,
  /// nodal forces: 3 per node; any other length throws std::invalid_argument); returns the interface
  /// displacement (3 per node) at t+dt.
  Eigen::VectorXd solve(double t, double dt, const Eigen::VectorXd& loadsStart,
                        const Eigen::VectorXd& loadsEnd) override;
  void saveCheckpoint() override;
  void restoreCheckpoint() override;

  /// Restart file (HDF5, structure/io/StateFile): positions, velocities, time, step size and step count, the
  /// energy ledger (so energies continue across a restart), plus any `arrays` of the caller (e.g. the
  /// coupling scheme's displacement history; the key "energy_ledger" is the participant's).
  void writeState(const std::filesystem::path& file,
                  const std::map<std::string, std::vector<double>>& arrays = {}) const;
  /// Continues from a restart file and returns its arrays; throws fsi::InputError naming the file when it
  /// does not fit the scene.
  std::map<std::string, std::vector<double>> readState(const std::filesystem::path& file);

  /// Results series (HDF5 + XDMF) of the whole structure: open once, then one frame per call. With
  /// `keepUntil` (a restart) the series in h5File continues: its frames and table rows later than keepUntil
  /// are dropped first, and its energy and probe tables go on.
  void openResults(const std::filesystem::path& h5File, std::optional<double> keepUntil = std::nullopt);
  /// One frame labelled `time` (the fluid's time of this state), and the tables as recorded so far.
  /// Returns false (and writes nothing) if the series already ends at or after `time`.
  bool writeResults(double time);
  bool writeResults() { return writeResults(time()); }
  /// Adds the "restart_times" entry `time` to the results file, dropping later (stale) entries.
  void noteRestart(double time);
  /// One row of the energy table (time, kinetic, strain, external_work, internal_work, mass_damping,
  /// balance_error, dt) and of the probe table (time, each probe) at the current state, labelled `time`;
  /// returns the probe values. Energies are those of the window's last structural step.
  std::map<std::string, double> recordHistory(double time);
  /// Frames in the results series (including those kept from an earlier run).
  int framesWritten() const;

  structure::Scene& scene() { return *scene_; }
  const structure::CentralDifference& integrator() const { return *cd_; }

 private:
  class Substeps;    // the StructureStepper over cd_ (StructureParticipant.cpp)
  class Relaxation;  // the RelaxationStepper over cd_ (equilibrium mode)
  void setWindowLoads(structure::InterfaceLoadKind kind, const double* start, const double* end,
                      std::size_t size);

  // Held on the heap, like everything the stepper, the effect and the integrator refer to, so that a
  // participant can be moved.
  std::unique_ptr<structure::Scene> scene_;
  // The load the interface effect reads, written before every structural step by the stepper; declared
  // before the effect and the integrator that refer to it.
  std::unique_ptr<structure::InterfaceLoad> load_;
  std::unique_ptr<structure::InterfacePressure> interface_;
  std::unique_ptr<structure::CentralDifference> cd_;
  std::unique_ptr<Substeps> stepper_;  // also holds the checkpoint
  std::unique_ptr<SubcycledStructure> subcycled_;
  std::unique_ptr<Relaxation> relaxation_;             // equilibrium mode only
  std::unique_ptr<EquilibriumStructure> equilibrium_;  // equilibrium mode only
  Eigen::VectorXd windowVelocity_;                     // equilibrium mode: (d_end − d_start) / Δt
  InterfaceMesh mesh_;
  structure::InterfaceLoadKind kind_ = structure::InterfaceLoadKind::Pressure;
  Eigen::VectorXd loadStart_, loadEnd_;  ///< the window's loads, of kind_
  std::unique_ptr<structure::SceneFrames> frames_;
  // Histories for /tables/energy and /tables/probes of the results file, column by column.
  std::vector<std::string> probeNames_;
  std::vector<std::vector<double>> energyRows_, probeRows_;
  std::vector<double> residual_;  ///< staticResidualRatio's scratch (node reactions)
};

}  // namespace fsi::coupling
