#pragma once
// Aitken: Aitken's dynamic relaxation (`acceleration aitken`).

#include "coupling/scheme/Acceleration.hpp"
#include "coupling/scheme/acceleration/AccelerationRegistry.hpp"

namespace fsi::coupling {

struct AitkenOptions {
  double initialOmega = 0.5;  ///< omega of the first iteration of the first window
  double minOmega = 1e-6;     ///< bounds on |omega| (the sign is kept)
  double maxOmega = 1.0;      ///< 1 suits added-mass problems (all Jacobian eigenvalues negative)
};

/// Aitken's dynamic relaxation: omega_k = -omega_{k-1} r_{k-1}.(r_k - r_{k-1}) / |r_k - r_{k-1}|^2, a secant
/// step projected on one direction. The first iteration of a later window starts from the previous
/// window's last omega when that is smaller than initialOmega (it is the better estimate of the Jacobian).
class Aitken final : public Acceleration {
 public:
  explicit Aitken(AitkenOptions options = {});
  Eigen::VectorXd compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) override;
  void onTimeWindowComplete(bool converged) override;
  std::string name() const override { return "aitken"; }
  double omega() const { return omega_; }
  /// The last window's factor (the next window starts from it) and whether a window was completed.
  State state() const override;
  void restore(const State& state) override;

 private:
  double clampOmega(double w) const;

  AitkenOptions opt_;
  double omega_;
  bool firstWindow_ = true;
  int iteration_ = 0;
  Eigen::VectorXd previousResidual_;
};

/// Its registry entry: name (the value of the option `acceleration`), description, options, factory.
AccelerationEntry aitkenEntry();

}  // namespace fsi::coupling
