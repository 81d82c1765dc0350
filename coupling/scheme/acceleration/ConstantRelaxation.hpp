#pragma once
// ConstantRelaxation: the fixed relaxation d + omega r of the implicit scheme (`acceleration constant`).

#include "coupling/scheme/Acceleration.hpp"
#include "coupling/scheme/acceleration/AccelerationRegistry.hpp"

namespace fsi::coupling {

/// d_new = d + omega * r. Converges on the added-mass problem only for 0 < omega < 2 / (1 + lambda_max).
class ConstantRelaxation final : public Acceleration {
 public:
  explicit ConstantRelaxation(double omega);
  Eigen::VectorXd compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) override;
  void onTimeWindowComplete(bool /*converged*/) override {}
  std::string name() const override { return "constant"; }
  double omega() const { return omega_; }

 private:
  double omega_;
};

/// Its registry entry: name (the value of the option `acceleration`), description, options, factory.
AccelerationEntry constantRelaxationEntry();

}  // namespace fsi::coupling
