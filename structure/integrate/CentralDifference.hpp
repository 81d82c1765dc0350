#pragma once
// CentralDifference: explicit leapfrog integration with lumped mass and a variable step.
//
//   v(n+½) = [(1 − αΔ/2) v(n−½) + Δ M⁻¹(f_ext − f_int)(x(n), v(n−½))] / (1 + αΔ/2),  Δ = (Δt(n) + Δt(n+1))/2
//   x(n+1) = x(n) + Δt(n+1) v(n+½)
// Mass damping α is treated implicitly (it never limits the step). Δt(n+1) = safety · min_e L_e/c_e,
// recomputed every step by the element effects from the current geometry, unless a fixed step is given.
// Energies are gathered in the same sweep as the update (no extra pass over the nodes); the bookkeeping is
// exact at every step (EnergyLedger), support reactions of prescribed motions and sliding planes included.
// A tie group (Constraints::ties) advances its tied part with its summed mass and force,
//   V(n+½) = [(1 − αΔ/2) Σm t(v(n−½)) + Δ Σ t(f_ext − f_int)] / ((1 + αΔ/2) Σm),
// one velocity for all its nodes; the part along the extrusion stays each node's own.

#include <memory>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/effects/ThreadedForces.hpp"
#include "structure/integrate/Constraints.hpp"
#include "structure/integrate/EnergyLedger.hpp"
#include "structure/integrate/StateSnapshot.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

struct CentralDifferenceSettings {
  double safety = 0.9;     ///< fraction of the element stability limit
  double fixedDt = 0;      ///< > 0: use this step and ignore the stability estimate (for studies/tests)
  double maxDt = 1e300;    ///< upper bound on the step
  double massDamping = 0;  ///< Rayleigh α [1/s]
  int threads = 1;         ///< threads for the force kernels and the node sweep (scene key solver.threads)
};

class CentralDifference {
 public:
  CentralDifference(Model& model, std::vector<const Effect*> effects, Constraints constraints,
                    CentralDifferenceSettings settings, double startTime = 0.0);

  /// Advances one step, never past `limitTime`, which it reaches in equal steps. `monitor` also evaluates
  /// the strain energy.
  /// Returns false if the state became non-finite (the caller diagnoses and stops). Growth of the energy
  /// (an unstable step) is reported by energy().growth(), which the caller checks after every step.
  bool step(double limitTime, bool monitor);

  double time() const { return time_; }
  double lastDt() const { return dt_; }
  double stableDt() const { return stableDt_; }  ///< element estimate at the last force evaluation
  long steps() const { return steps_; }
  double maxDt() const { return settings_.maxDt; }
  const EnergyLedger& energy() const { return ledger_; }
  const Constraints& constraints() const { return constraints_; }
  /// Kinetic damping (equilibrium coupling, coupling/scheme/Equilibrium): every velocity v(n+½) to zero. The
  /// kinetic energy removed is booked as dissipation (with the mass damping's), so the balance stays exact;
  /// the next step starts from rest like a run's first (half a step's kick).
  void stopMotion();
  /// Moves the clock to `t` without moving the structure: the pseudo-steps of an equilibrium coupling's
  /// relaxation are not physical time, and the window ends at the fluid's time.
  void setTime(double t) { time_ = t; }
  /// Re-evaluates forces at the current state (for reactions and output); does not advance.
  void evaluateForces(bool withEnergy);
  /// The energy created in the elements through the current state x(n+1), as EnergyLedger::created() at a
  /// monitoring step: evaluates the forces and the strain energy here and completes the internal work with
  /// the trapezoidal half ½Δt f_int(n+1)·v(n+½) of the last step. For the checks at outputs and at the end of
  /// a run, whatever the monitoring interval; the next step evaluates its forces anew, so the trajectory does
  /// not change.
  double createdAtCurrentState();
  /// Starts again from a saved state whose bookkeeping is not known (a restart file): x, v at the half step,
  /// time, last step size. The energy ledger starts again from this state (KE0 = ½ v·M v, U0 its strain
  /// energy, which is also the current one; no work booked), and the step estimate is that of this state.
  void restore(const std::vector<double>& x, const std::vector<double>& v, double time, double dt,
               long steps);

  /// Everything needed to repeat a stretch of time exactly (implicit coupling re-iterates a fluid step; a run
  /// returns to its last good state): the state, the ledger and the step estimate. Scalars and arrays of the
  /// snapshot are the caller's and left as they are.
  StateSnapshot checkpoint() const;
  /// Saves into an existing snapshot, reusing its storage (no allocation once sized).
  void checkpoint(StateSnapshot& c) const;
  /// Returns to a checkpoint: state, ledger and step estimate as they were when it was taken.
  void restore(const StateSnapshot& c);

 public:
  /// The node sweep's energy sums (step()).
  struct SweepSums {
    double ke = 0, prod = 0, vv = 0, extOld = 0, intOld = 0, extNew = 0, intNew = 0;
    void add(const SweepSums& o);
  };

 private:
  double computeForces(bool withEnergy);
  /// Δt(n+1) from the elements' stable step; NaN if nothing bounds it.
  double nextDt(double stable, double limitTime) const;
  /// Threads: the forces and the node sweep in one parallel region (ThreadedForces.hpp). Returns Δt(n+1)
  /// (NaN: not swept) and the sweep's sums.
  double forcesAndSweep(double limitTime, bool monitor, SweepSums& sums);
  /// Records U0 at the current state; returns the element step estimate of that evaluation.
  double recordInitialStrain();

  Model& model_;
  std::vector<const Effect*> effects_;
  Constraints constraints_;
  CentralDifferenceSettings settings_;
  ThreadedForces forces_;
  std::vector<SweepSums> sweepParts_;  ///< one per share of forces_ (threads)
  EnergyLedger ledger_;
  double time_ = 0;
  double dt_ = 0;  ///< Δt(n) = t(n) − t(n−1); 0 before the first step (half-step start)
  double stableDt_ = 0;
  long steps_ = 0;
  // Velocities v(n−½) of the constrained dofs, saved before the sweep overwrites them (the support
  // reactions' work needs them), and for tied nodes also x(n). Sized once.
  std::vector<double> prescribedOld_, sliderOld_, tieOld_;
  std::vector<double> tieMass_;  ///< summed mass of each tie group
};

}  // namespace fsi::structure
