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
};

/// Interface quasi-Newton with an inverse Jacobian from least squares (IQN-ILS, Degroote et al. 2009).
/// Columns are differences of consecutive iterates, newest first: V (residuals) and W (outputs d~).
/// With c = argmin |V c + r_k| (Householder QR), the next input is d~_k + W c: the residual change V c
/// cancels r_k as far as the observed directions allow, and the rest of r_k is taken as is.
class IqnIls final : public Acceleration {
 public:
  explicit IqnIls(IqnIlsOptions options = {});
  Eigen::VectorXd compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) override;
  void onTimeWindowComplete() override;
  std::string name() const override;

  int lastColumnsUsed() const { return lastColumnsUsed_; }  ///< after filtering, in the last step
  int lastColumnsFiltered() const { return lastColumnsFiltered_; }

 private:
  struct Columns {
    std::deque<Eigen::VectorXd> v, w;  // newest first
  };
  Eigen::VectorXd relax(const Eigen::VectorXd& d, const Eigen::VectorXd& r) const;

  IqnIlsOptions opt_;
  Columns current_;
  std::deque<Columns> past_;  // newest window first, at most reuseSteps
  Eigen::VectorXd previousResidual_, previousOutput_;
  int iteration_ = 0;
  int lastColumnsUsed_ = 0, lastColumnsFiltered_ = 0;
};

/// Its registry entry: name (the value of the option `acceleration`), description, options, factory.
AccelerationEntry iqnIlsEntry();

}  // namespace fsi::coupling
