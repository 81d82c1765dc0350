#pragma once
// Acceleration of the interface fixed-point iteration d -> d~ = S(F(d)) of an implicit coupling scheme.
// Given the input d that the fluid used and the structure's answer d~, an Acceleration proposes the next
// input. The residual is r = d~ - d. All variants work on plain vectors and know nothing of the solvers.
//
// Call pattern (done by CouplingScheme): compute() once per coupling iteration, onTimeWindowComplete() once
// when the window is accepted. Derivations and the measured iteration counts are in docs/COUPLING.md.

#include <Eigen/Dense>
#include <deque>
#include <memory>
#include <string>

namespace fsi::coupling {

class Acceleration {
 public:
  virtual ~Acceleration() = default;
  /// Next input of the current window from the input `d` and the structure's output `dTilde`.
  virtual Eigen::VectorXd compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) = 0;
  /// The window was accepted: the next compute() is the first iteration of a new window.
  virtual void onTimeWindowComplete() = 0;
  virtual std::string name() const = 0;
};

/// d_new = d + omega * r. Converges on the added-mass problem only for 0 < omega < 2 / (1 + lambda_max).
class ConstantRelaxation final : public Acceleration {
 public:
  explicit ConstantRelaxation(double omega);
  Eigen::VectorXd compute(const Eigen::VectorXd& d, const Eigen::VectorXd& dTilde) override;
  void onTimeWindowComplete() override {}
  std::string name() const override { return "constant"; }
  double omega() const { return omega_; }

 private:
  double omega_;
};

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
  void onTimeWindowComplete() override;
  std::string name() const override { return "aitken"; }
  double omega() const { return omega_; }

 private:
  double clampOmega(double w) const;

  AitkenOptions opt_;
  double omega_;
  bool firstWindow_ = true;
  int iteration_ = 0;
  Eigen::VectorXd previousResidual_;
};

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

enum class AccelerationKind { Constant, Aitken, IqnIls };

struct AccelerationConfig {
  AccelerationKind kind = AccelerationKind::IqnIls;
  double omega = 0.5;  ///< constant relaxation factor (Constant only)
  AitkenOptions aitken;
  IqnIlsOptions iqn;
};

std::unique_ptr<Acceleration> makeAcceleration(const AccelerationConfig& config);

}  // namespace fsi::coupling
