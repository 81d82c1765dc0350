#pragma once
// Acceleration of the interface fixed-point iteration d -> d~ = S(F(d)) of an implicit coupling scheme.
// Given the input d that the fluid used and the structure's answer d~, an Acceleration proposes the next
// input. The residual is r = d~ - d. All variants work on plain vectors and know nothing of the solvers.
//
// Call pattern (done by CouplingScheme): compute() once per coupling iteration, onTimeWindowComplete() once
// when the window is accepted. The variants are one class per file in coupling/scheme/acceleration/,
// registered by name in AccelerationRegistry.cpp (docs/ARCHITECTURE.md: how to add one). Derivations and the
// measured iteration counts are in docs/COUPLING.md.

#include <Eigen/Dense>
#include <map>
#include <string>
#include <vector>

namespace fsi::coupling {

class Acceleration {
 public:
  virtual ~Acceleration() = default;
  /// Next input of the current window from the input `d` and the structure's output `dTilde`.
  virtual Eigen::VectorXd compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) = 0;
  /// The window was accepted (`converged`: within the tolerance, or stopped at maxIterations): the next
  /// compute() is the first iteration of a new window.
  virtual void onTimeWindowComplete(bool converged) = 0;
  virtual std::string name() const = 0;

  /// What the variant carries from one window to the next (between windows: after
  /// onTimeWindowComplete()), as named arrays for a restart state; empty if it carries nothing.
  using State = std::map<std::string, std::vector<double>>;
  virtual State state() const { return {}; }
  /// Continue from state() of an earlier run (between windows). A state that does not fit (a missing or
  /// inconsistent array, a non-finite value) throws InputError naming the array.
  virtual void restore(const State& /*state*/) {}
};

}  // namespace fsi::coupling
