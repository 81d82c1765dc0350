#pragma once
// IqnIls: interface quasi-Newton with least-squares inverse Jacobian (`acceleration IQN-ILS`).

#include <deque>

#include "coupling/scheme/Acceleration.hpp"
#include "coupling/scheme/acceleration/AccelerationRegistry.hpp"

namespace fsi::coupling {

struct IqnIlsOptions {
  double initialOmega = 0.1;        ///< relaxation of a window's first iteration
  int reuseSteps = 0;               ///< columns of this many past windows enter the least squares (q)
  int maxColumns = 50;              ///< total columns (current window first, then the newest reused ones)
  double filterTolerance = 1e-8;    ///< drop a column whose part orthogonal to the newer ones is below this
                                    ///< fraction of its norm
  bool relaxFirstIteration = true;  ///< false: a window's first iteration is already a quasi-Newton step
                                    ///< when reused columns exist
  /// A quasi-Newton step with reused columns longer than this many residuals |r| is not trusted (see the
  /// class comment); on the cavity the steps of converging windows were at most 4 |r|, the bad ones 57 and
  /// 1365 |r|.
  double maxStepRatio = 10.0;
};

/// Interface quasi-Newton with an inverse Jacobian from least squares (IQN-ILS, Degroote et al. 2009).
/// Columns are differences of consecutive iterates, newest first: V (residuals) and W (outputs d~).
/// With c = argmin |V c + r_k| (Householder QR), the next input is d~_k + W c: the residual change V c
/// cancels r_k as far as the observed directions allow, and the rest of r_k is taken as is.
///
/// Safeguards, because columns can be stale or noise: a window that ended without converging leaves no
/// columns for reuse and drops the older ones (its columns describe a state the next window no longer has, or
/// only the fluid's solver noise when the tolerance is below it); and a step with reused columns longer than
/// maxStepRatio |r| (or not finite) is recomputed from this window's columns alone (the relaxed step d +
/// omega r if there are none). This window's own steps are not limited: a slow mode (an eigenvalue of the
/// fixed-point map near 1) needs steps many residuals long. Measured (cavity-membrane-2d at tolerance 1e-6,
/// reuse 8): after three non-converged windows the next window's second iteration asked for a step 1365 |r|
/// long (0.10 m against |r| = 7.6e-5), which folded the fluid mesh (docs/COUPLING.md).
class IqnIls final : public Acceleration {
 public:
  explicit IqnIls(IqnIlsOptions options = {});
  Eigen::VectorXd compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) override;
  void onTimeWindowComplete(bool converged) override;
  std::string name() const override;

  /// The past windows' columns kept for reuse: `past_columns` (the column count of each window, newest
  /// first), `past_v` and `past_w` (the columns one after another, newest first).
  State state() const override;
  void restore(const State& state) override;

 private:
  struct Columns {
    std::deque<Eigen::VectorXd> v, w;  // newest first
  };
  Eigen::VectorXd relax(const Eigen::VectorXd& d, const Eigen::VectorXd& r) const;
  /// The least-squares step from this window's columns and (withReused) the past windows' ones; empty if
  /// no column is usable.
  Eigen::VectorXd quasiNewtonStep(const Eigen::VectorXd& r, const Eigen::VectorXd& dTilde, bool withReused);

  IqnIlsOptions opt_;
  Columns current_;
  std::deque<Columns> past_;  // newest window first, at most reuseSteps
  Eigen::VectorXd previousResidual_, previousOutput_;
  int iteration_ = 0;
  // The column filter's count in the last quasi-Newton step (used after filtering, dropped by it). Nothing
  // in the product reads them; the unit tests do, through this seam (tests/unit/test_coupling_schemes.cpp).
  int lastColumnsUsed_ = 0, lastColumnsFiltered_ = 0;
  friend struct IqnIlsTestAccess;
};

/// Its registry entry: name (the value of the option `acceleration`), description, options, factory.
AccelerationEntry iqnIlsEntry();

}  // namespace fsi::coupling
