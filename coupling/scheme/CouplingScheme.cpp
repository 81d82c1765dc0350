#include "coupling/scheme/CouplingScheme.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <string>

namespace fsi::coupling {

std::string unstableStructureAdvice(SchemeKind kind) {
  const std::string smallerStep =
      "lower `time: {safety: ...}` in the scene or raise `subcycles`, and damp the fabric's in-plane "
      "ringing (`bulk_viscosity: {}` on its membranes)";
  if (kind == SchemeKind::Staggered)
    return "With the staggered scheme a structure lighter than the fluid it moves (added mass above its own "
           "mass: fabric in air at low speed, any membrane in water) is unstable at every step size: use "
           "`scheme implicit;` (IQN-ILS acceleration, docs/COUPLING.md). For a heavy structure, " +
           smallerStep + ".";
  return "A light, soft structure strongly coupled to the flow may need a smaller step: " + smallerStep + ".";
}

CouplingScheme::CouplingScheme(const CouplingConfig& config, StructureSolver& structure,
                               std::unique_ptr<Acceleration> acceleration)
    : config_(config), structure_(structure), acceleration_(std::move(acceleration)), history_(1) {
  if (!(config_.timeWindowSize > 0.0))
    throw std::invalid_argument("CouplingScheme: timeWindowSize must be > 0");
  if (config_.extrapolationOrder < 0 || config_.extrapolationOrder > 2)
    throw std::invalid_argument("CouplingScheme: extrapolationOrder must be 0, 1 or 2");
  if (!(config_.loadRelaxation > 0.0 && config_.loadRelaxation <= 1.0))
    throw std::invalid_argument(fmt::format(
        "CouplingScheme: loadRelaxation = {:g}, valid: 0 < loadRelaxation <= 1", config_.loadRelaxation));
  if (config_.kind == SchemeKind::Implicit) {
    if (!acceleration_)
      throw std::invalid_argument("CouplingScheme: the implicit scheme needs an Acceleration");
    if (config_.maxIterations < 1) throw std::invalid_argument("CouplingScheme: maxIterations must be >= 1");
    // A relative residual: 1 or more accepts any first iterate, 0 leaves only the absolute test.
    if (!(config_.relativeTolerance > 0.0 && config_.relativeTolerance < 1.0))
      throw std::invalid_argument(
          fmt::format("CouplingScheme: relativeTolerance = {:g}, valid: 0 < relativeTolerance < 1",
                      config_.relativeTolerance));
    if (!(config_.absoluteTolerance >= 0.0))
      throw std::invalid_argument("CouplingScheme: absoluteTolerance must be >= 0");
  }
}

double CouplingScheme::initialize(double t0, const Eigen::VectorXd& displacement0,
                                  const Eigen::VectorXd& loads0) {
  t0_ = t_ = t0;
  history_.assign(1, displacement0);
  loadsStart_ = loads0;
  input_ = displacement0;
  window_ = iteration_ = 0;
  windowComplete_ = false;
  stats_ = {};
  last_ = {};
  initialized_ = true;
  return config_.timeWindowSize;
}

void CouplingScheme::restoreHistory(const std::vector<Eigen::VectorXd>& newestFirst) {
  requireInitialized("restoreHistory");
  if (newestFirst.empty()) return;
  for (const auto& d : newestFirst)
    if (d.size() != history_.front().size())
      throw CouplingError("CouplingScheme::restoreHistory: displacement of size " + std::to_string(d.size()) +
                          ", expected " + std::to_string(history_.front().size()));
  history_.assign(newestFirst.begin(), newestFirst.begin() + std::min<std::size_t>(3, newestFirst.size()));
  input_ = predictor();
}

void CouplingScheme::restoreLoadsAtWindowStart(const Eigen::VectorXd& loads) {
  requireInitialized("restoreLoadsAtWindowStart");
  if (loads.size() != loadsStart_.size())
    throw CouplingError("CouplingScheme::restoreLoadsAtWindowStart: loads of size " +
                        std::to_string(loads.size()) + ", expected " + std::to_string(loadsStart_.size()));
  loadsStart_ = loads;
}

bool CouplingScheme::isCouplingOngoing() const {
  // Within half a window of the end is the end, as for OpenFOAM's own time loop (it stops once t passes
  // endTime - deltaT/2): round-off in t, or an end time and a step changed part way through that no longer
  // add up to the digit, must not leave the coupling one window short of the fluid's end.
  return initialized_ && t_ < config_.endTime - 0.5 * config_.timeWindowSize;
}

bool CouplingScheme::requiresWritingCheckpoint() const {
  return initialized_ && config_.kind == SchemeKind::Implicit && iteration_ == 0 && isCouplingOngoing();
}

bool CouplingScheme::requiresReadingCheckpoint() const {
  return initialized_ && config_.kind == SchemeKind::Implicit && iteration_ > 0;
}

void CouplingScheme::requireInitialized(const char* what) const {
  if (!initialized_) throw CouplingError(std::string("CouplingScheme::") + what + " before initialize()");
}

Eigen::VectorXd CouplingScheme::predictor() const {
  const int order = std::min<int>(config_.extrapolationOrder, int(history_.size()) - 1);
  switch (order) {
    case 0:
      return history_[0];
    case 1:
      return 2.0 * history_[0] - history_[1];
    default:
      return 3.0 * history_[0] - 3.0 * history_[1] + history_[2];
  }
}

void CouplingScheme::completeWindow(const Eigen::VectorXd& loads, const Eigen::VectorXd& dEnd, int iterations,
                                    bool converged, double res, double rel) {
  last_ = WindowReport{window_, t_, config_.timeWindowSize, iterations, converged, res, rel};
  ++stats_.windows;
  stats_.iterations += iterations;
  stats_.maxIterations = std::max(stats_.maxIterations, iterations);
  if (!converged) ++stats_.notConverged;

  // Time from the window count, not by summation, so long runs do not drift.
  ++window_;
  t_ = t0_ + window_ * config_.timeWindowSize;
  loadsStart_ = loads;
  history_.insert(history_.begin(), dEnd);
  if (history_.size() > 3) history_.pop_back();
  iteration_ = 0;
  windowComplete_ = true;
  if (acceleration_ && config_.kind == SchemeKind::Implicit) acceleration_->onTimeWindowComplete(converged);
  input_ = predictor();
}

double CouplingScheme::advance(const Eigen::VectorXd& loads) {
  requireInitialized("advance");
  if (!isCouplingOngoing()) throw CouplingError("CouplingScheme::advance: coupling has ended");
  if (loads.size() != loadsStart_.size())
    throw CouplingError("CouplingScheme::advance: loads have size " + std::to_string(loads.size()) +
                        ", expected " + std::to_string(loadsStart_.size()));
  const double dt = config_.timeWindowSize;
  // What the structure gets: relaxed towards the load it got last (the window's start), never towards an
  // iterate of this window, so an implicit window still iterates to a fixed point.
  const double w = config_.loadRelaxation;
  const Eigen::VectorXd applied = w == 1.0 ? loads : Eigen::VectorXd(w * loads + (1.0 - w) * loadsStart_);

  if (config_.kind == SchemeKind::Staggered) {
    const Eigen::VectorXd dEnd = structure_.solve(t_, dt, loadsStart_, applied);
    if (!dEnd.allFinite())
      throw CouplingError("CouplingScheme: non-finite structure displacement in window " +
                          std::to_string(window_));
    completeWindow(applied, dEnd, 1, true, 0.0, 0.0);
    return dt;
  }

  // Every pass of a window starts the structure from the same saved state.
  if (iteration_ == 0)
    structure_.saveCheckpoint();
  else
    structure_.restoreCheckpoint();
  const Eigen::VectorXd dTilde = structure_.solve(t_, dt, loadsStart_, applied);
  if (dTilde.size() != input_.size())
    throw CouplingError("CouplingScheme: structure returned " + std::to_string(dTilde.size()) +
                        " displacement values, expected " + std::to_string(input_.size()));
  const double res = (dTilde - input_).norm();
  const double ref = dTilde.norm();
  if (!std::isfinite(res) || !std::isfinite(ref))
    throw CouplingError("CouplingScheme: non-finite interface residual in window " + std::to_string(window_) +
                        ", iteration " + std::to_string(iteration_));
  const double rel = ref > 0.0 ? res / ref : (res > 0.0 ? std::numeric_limits<double>::infinity() : 0.0);
  const bool converged = res <= config_.relativeTolerance * ref || res <= config_.absoluteTolerance;
  const int iterations = iteration_ + 1;

  windowComplete_ = false;
  if (converged || iterations >= config_.maxIterations) {
    if (!converged && config_.throwOnNonConvergence)
      throw CouplingError("CouplingScheme: window " + std::to_string(window_) + " not converged after " +
                          std::to_string(iterations) + " iterations (relative residual " +
                          std::to_string(rel) + ")");
    completeWindow(applied, dTilde, iterations, converged, res, rel);
    return dt;
  }
  input_ = acceleration_->compute(input_, dTilde);
  iteration_ = iterations;
  return dt;
}

WindowReport runTimeWindow(CouplingScheme& scheme, FluidSolver& fluid) {
  if (!scheme.isCouplingOngoing()) throw CouplingError("runTimeWindow: coupling has ended");
  do {
    if (scheme.requiresWritingCheckpoint()) fluid.saveCheckpoint();
    const Eigen::VectorXd loads = fluid.solve(scheme.time(), scheme.timeWindowSize(), scheme.displacement());
    scheme.advance(loads);
    if (scheme.requiresReadingCheckpoint()) fluid.restoreCheckpoint();
  } while (!scheme.isTimeWindowComplete());
  return scheme.lastWindow();
}

}  // namespace fsi::coupling
