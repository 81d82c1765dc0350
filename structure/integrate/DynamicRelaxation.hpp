#pragma once
// DynamicRelaxation: the static equilibrium as the end state of a fictitious, damped dynamics (Δt = 1,
// fictitious masses from stiffness bounds), sharing the force kernels of the explicit solver.
//
//   kinetic damping: undamped leapfrog; whenever the kinetic energy drops, the velocities are zeroed
//     (optionally after stepping back to the kinetic-energy peak, x ← x − ½Δt v);
//   viscous damping: v(n+½) = [(2 − c) v(n−½) + 2 M⁻¹R] / (2 + c), with c from a Rayleigh-quotient estimate
//     of the lowest frequency, ω0² = Σ u_i² K̄_ii / Σ u_i² m_i, K̄_ii = −ΔR_i/Δx_i (Underwood: c = 2ω0;
//     Rezaiee-Pajand: c = sqrt(4ω0² − ω0⁴)).
// Converged when max(‖R‖∞ / ‖reactions‖∞, E_kin / E_strain) ≤ ε (R: static residual on free dofs).
// Tie groups (Constraints::ties) move with their summed fictitious mass and residual, and a tied node's
// residual is its share of its group's (TieGroups::shareByMass), so the tie forces count neither as
// residual nor as reactions.
// Safeguards: Underwood's apparent-frequency test |ΔR_i| / (4 m_i |Δx_i|) > 1, failed on three iterations in
// a row, flags a node whose mass is too small for Δt = 1 and raises it by that factor; a divergence (residual
// up 10⁴-fold or non-finite) restarts the increment with 1.5x the masses. Both are counted in the result.
// The iterate with the smallest residual (checked every kBestEvery iterations) is kept for the stop handling:
// a diverged run saves it as its last good state.
// Threads (solver.threads, docs/PERFORMANCE.md "Threaded dynamic relaxation"): an iteration is one parallel
// region, as a central-difference step: the force evaluation's shares (ThreadedForces), a barrier, then each
// thread gathers the forces of its range of nodes and runs every node loop of the iteration over the same
// nodes in one pass (frequency test, residual and kinetic-energy norms, the kinetic-energy trial and, for
// kinetic damping, the update itself into spare arrays that become the state if no reset follows). Norms and
// energies are summed per range and the ranges added in range order after the join: the result depends on
// the thread count (round-off) but never on the scheduling. Serial below kMinParallelItems (as the forces)
// and with tie groups (their group sums are serial passes).

#include <functional>
#include <string>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/effects/ThreadedForces.hpp"
#include "structure/integrate/Constraints.hpp"
#include "structure/integrate/FictitiousMass.hpp"
#include "structure/integrate/StateSnapshot.hpp"
#include "structure/integrate/StopReason.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

struct RelaxationSettings {
  enum class Damping { Kinetic, Viscous };
  enum class Coefficient { Underwood, RezaiePajand };
  Damping damping = Damping::Kinetic;
  FictitiousMassRule mass = FictitiousMassRule::Gerschgorin;
  Coefficient coefficient = Coefficient::Underwood;
  int threads = 1;          ///< threads for the force kernels and the node loops (solver.threads)
  double lambda = 0;        ///< mass scale; 0 = the rule's default (defaultLambda)
  bool backstep = true;     ///< kinetic damping: restart from the estimated energy peak
  double tolerance = 1e-3;  ///< ε
  long maxIterations = 200000;
  int increments = 1;         ///< load applied in this many equal increments
  double loadTime = 0;        ///< time at which load time functions are evaluated
  bool autoMass = true;       ///< raise masses when the apparent-frequency test fails
  bool updateMasses = false;  ///< recompute the masses at every kinetic reset (always for the stress rule)
};

/// Default λ of each rule: the smallest stable value with a margin, no per-mesh tuning.
double defaultLambda(const RelaxationSettings& s);

struct RelaxationRecord {
  long iteration;
  double residualRatio, energyRatio, kinetic, strain;
};

struct RelaxationResult {
  long iterations = 0;
  /// Static (converged), Unstable (diverged), Interrupted or NotConverged (iteration limit).
  StopReason reason = StopReason::NotConverged;
  double residualRatio = 0, energyRatio = 0;
  double residual = 0;       ///< ‖R‖∞ on free dofs at the last evaluation [N]
  double startResidual = 0;  ///< ‖R‖∞ at the start of the failing attempt [N]
  int increment = 0;         ///< increment being relaxed when the run stopped (1-based)
  int worstNode = -1;        ///< node with the largest finite residual at the last evaluation
  int nonFiniteNodes = 0;    ///< nodes whose residual was non-finite at the last evaluation
  int firstNonFiniteNode = -1;
  int massIncreases = 0;  ///< nodes whose mass the safeguard raised (summed over the run)
  int kineticResets = 0;
  int restarts = 0;        ///< increments restarted with 1.5x the masses after a divergence
  double lambda = 0;       ///< initial mass scale
  double finalLambda = 0;  ///< after restarts
  std::vector<RelaxationRecord> history;
  std::string message;
};

class DynamicRelaxation {
 public:
  DynamicRelaxation(Model& model, std::vector<const Effect*> effects, Constraints constraints,
                    RelaxationSettings settings);
  /// Runs all increments. `onIncrement(k, result)` is called after each converged increment (for output);
  /// `interrupted()` is polled every iteration.
  RelaxationResult run(const std::function<void(int, const RelaxationResult&)>& onIncrement = {},
                       const std::function<bool()>& interrupted = {});
  const std::vector<double>& masses() const { return mass_; }
  /// The iterate with the smallest residual ratio of the last increment attempted (its start included), as
  /// a state: step = its iteration, time = scalars["load_factor"] = its load factor, dt = 1,
  /// scalars["residual_ratio"], scalars["increment"]. Empty if none was kept.
  const StateSnapshot& best() const { return best_; }
  static constexpr long kBestEvery = 32;

 private:
  /// What an evaluation does around the force evaluation, node by node.
  struct Sweep {
    enum class Before { None, Update, Backstep };
    Before before = Before::None;  ///< Update: v ← (cv·v + cr·R/m), x ← x + v; Backstep: x ← x − ½v, v ← 0
    double cv = 1, cr = 1;
    bool underwood = false;  ///< after an update: apparent-frequency test and the Rayleigh-quotient sums
    bool trial = false;      ///< kinetic damping: E_kin of the next update with coefficient h
    double h = 1;
    bool speculate = false;  ///< and that update itself into vNext_, xNext_ (and R into Rprev_)
  };
  /// Sums and maxima over a range of nodes (one per thread's share; the ranges are added in order).
  struct alignas(64) NodeSums {
    double res = 0, reac = 0, fmax = 0, ke = 0, all = 0, keNew = 0, num = 0, den = 0, dxNext = 0;
    int massIncreases = 0;
    void add(const NodeSums& o);
  };
  /// `sw.before` on every node, the forces at load factor lf (none if !withForces), then the node loops of
  /// `sw` at the new state; returns their sums over all nodes.
  NodeSums evaluate(double loadFactor, const Sweep& sw, bool withForces = true);
  /// The node work of one range before and after the forces.
  void before(int begin, int end, const Sweep& sw, NodeSums& out);
  void after(int begin, int end, const Sweep& sw, double dxMax, NodeSums& out);
  int sweepBegin(int s) const;
  int sweepEnd(int s) const;
  void forces(double loadFactor);
  void keepIfBest(long iteration, int increment, double loadFactor, double residualRatio);
  /// Largest-residual node and non-finite residuals at the current state (for a stopped run's report).
  void locateResidual(RelaxationResult& r);
  /// resid_ = f_ext − f_int with the tie forces left out (TieGroups::shareByMass, fictitious masses).
  void sharedResidual();
  Model& model_;
  std::vector<const Effect*> effects_;
  Constraints constraints_;
  RelaxationSettings s_;
  ThreadedForces forces_;
  std::vector<double> mass_;            ///< fictitious mass per node
  std::vector<double> free_;            ///< 1 for a free dof, 0 for a constrained one
  std::vector<double> resid_, vTrial_;  ///< tie groups only: shared residual, trial velocities
  std::vector<double> Rprev_;           ///< residual before the last update (frequency test)
  std::vector<double> vNext_, xNext_;   ///< kinetic damping: the next update, computed with the trial
  std::vector<unsigned char> strikes_;  ///< consecutive failures of the frequency test per node
  double dxMax_ = 0;                    ///< max |v| of the update in vNext_
  bool threadedSweeps_ = false;         ///< node loops in the force evaluation's parallel region
  std::vector<NodeSums> parts_;         ///< one per share of the node loops
  double strain_ = 0;
  StateSnapshot best_;
};

}  // namespace fsi::structure
