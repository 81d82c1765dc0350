#include "structure/integrate/DynamicRelaxation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>

namespace fsi::structure {

double defaultLambda(const RelaxationSettings& s) {
  switch (s.mass) {
    case FictitiousMassRule::Gerschgorin:
      return 0.7;
    case FictitiousMassRule::StressBound:
      return 10.0;
    case FictitiousMassRule::RezaiePajand:
      return 0.6;
  }
  return 0.6;
}

DynamicRelaxation::DynamicRelaxation(Model& model, std::vector<const Effect*> effects,
                                     Constraints constraints, RelaxationSettings settings)
    : model_(model),
      effects_(std::move(effects)),
      constraints_(std::move(constraints)),
      s_(settings),
      forces_(effects_, settings.threads, model.nodes.count) {
  constraints_.applyTo(model_.nodes);
  free_.resize(3 * model_.nodes.count);
  for (std::size_t d = 0; d < free_.size(); ++d) free_[d] = model_.nodes.invMassDof[d] != 0.0 ? 1.0 : 0.0;
}

void DynamicRelaxation::forces(double loadFactor) {
  strain_ = forces_.evaluate(model_.nodes, s_.loadTime, loadFactor, true).strainEnergy;
}

RelaxationResult DynamicRelaxation::run(const std::function<void(int, const RelaxationResult&)>& onIncrement,
                                        const std::function<bool()>& interrupted) {
  Nodes& N = model_.nodes;
  const int nd = 3 * N.count;
  RelaxationResult r;
  r.lambda = s_.lambda > 0 ? s_.lambda : defaultLambda(s_);
  const bool kinetic = s_.damping == RelaxationSettings::Damping::Kinetic;
  std::vector<double> Rprev(nd, 0.0);
  // Consecutive failures of the apparent-frequency test per node: a neighbour's large move can fail it once,
  // a node that is really too light fails it every iteration (its error grows like a Nyquist mode).
  std::vector<unsigned char> strikes(N.count, 0);
  std::fill(N.v.begin(), N.v.end(), 0.0);

  double lambda = r.lambda;
  for (int inc = 1; inc <= s_.increments; ++inc) {
    const double lf = double(inc) / s_.increments;
    const std::vector<double> xStart = N.x;
    bool converged = false;
    r.increment = inc;
    best_.x.clear();  // keeps its storage
    // An attempt relaxes the increment from its start; a divergence ends it and starts another one with
    // heavier masses.
    for (bool restart = true; restart;) {
      restart = false;
      for (const PrescribedMotion& p : constraints_.prescribed)
        N.x[3 * p.node + p.component] = N.X[3 * p.node + p.component] + lf * p.amplitude * p.fn(s_.loadTime);
      mass_ = fictitiousMasses(model_, N.x.data(), s_.mass, lambda);
      // A node with no stiffness at all (e.g. only slack cables) still needs a mass.
      double mmax = 0;
      for (double m : mass_) mmax = std::max(mmax, m);
      for (double& m : mass_) m = std::max(m, 1e-9 * mmax);
      std::fill(N.v.begin(), N.v.end(), 0.0);
      forces(lf);
      bool fresh = true;  // next velocity update is a half step (start or restart)
      double kePrev = 0, c = 0, res0 = -1;
      while (true) {
        // Static residual on free dofs, reactions on constrained ones. std::max drops a NaN, so a separate
        // sum carries any non-finite residual to the divergence test.
        // A tied node's residual is its share of its group's (the tie forces are no residual).
        const bool tied = !constraints_.ties.empty();
        if (tied) sharedResidual();
        double res = 0, reac = 0, fmax = 0, ke = 0, all = 0;
        for (int i = 0; i < N.count; ++i)
          for (int k = 0; k < 3; ++k) {
            const int d = 3 * i + k;
            const double R = tied ? resid_[d] : N.fext[d] - N.fint[d];
            all += R;
            fmax = std::max(fmax, std::abs(N.fext[d]));
            if (free_[d] != 0.0) {
              res = std::max(res, std::abs(R));
              ke += 0.5 * mass_[i] * N.v[d] * N.v[d];
            } else {
              reac = std::max(reac, std::abs(R));
            }
          }
        const bool finite = std::isfinite(all) && std::isfinite(strain_) && std::isfinite(ke);
        const double scale = reac > 0 ? reac : (fmax > 0 ? fmax : 1.0);
        r.residual = finite ? res : std::numeric_limits<double>::quiet_NaN();
        r.residualRatio = r.residual / scale;
        r.energyRatio = strain_ > 0 ? ke / strain_ : (ke > 0 ? std::numeric_limits<double>::infinity() : 0.0);
        r.history.push_back({r.iterations, r.residualRatio, r.energyRatio, ke, strain_});
        if (res0 < 0) res0 = res;
        // Divergence (masses too light for the stiffness the structure develops): restart the increment
        // with 1.5x the masses rather than fail; give up only after the masses grew 25-fold.
        if (!finite || res > 1e4 * res0) {
          if (s_.autoMass && lambda < 25.0 * r.lambda) {
            lambda *= 1.5;
            ++r.restarts;
            N.x = xStart;
            std::fill(N.v.begin(), N.v.end(), 0.0);
            std::fill(strikes.begin(), strikes.end(), 0);
            restart = true;
            break;
          }
          r.reason = StopReason::Unstable;
          r.startResidual = res0;
          r.finalLambda = lambda;
          locateResidual(r);
          r.message = fmt::format("diverged at iteration {} (residual {} from {:.3g} N at the start)",
                                  r.iterations, finite ? fmt::format("{:.3g} N", res) : "non-finite", res0);
          return r;
        }
        if (r.iterations % kBestEvery == 0 || best_.empty())
          keepIfBest(r.iterations, inc, lf, r.residualRatio);
        if (std::max(r.residualRatio, r.energyRatio) <= s_.tolerance) {
          converged = true;
          break;
        }
        if (r.iterations >= s_.maxIterations) break;
        if (interrupted && interrupted()) {
          r.reason = StopReason::Interrupted;
          r.finalLambda = lambda;
          r.message = "interrupted";
          return r;
        }
        ++r.iterations;

        const double h = fresh ? 0.5 : 1.0;
        if (kinetic) {
          double keNew = 0;
          if (tied) {
            // The kinetic energy of the tied motion the update is about to give.
            vTrial_.resize(std::size_t(nd));
            for (int d = 0; d < nd; ++d)
              vTrial_[d] = (N.v[d] + h * (N.fext[d] - N.fint[d]) / mass_[d / 3]) * free_[d];
            constraints_.ties.project(mass_.data(), vTrial_.data(), nullptr, 0.0);
            for (int d = 0; d < nd; ++d) keNew += 0.5 * mass_[d / 3] * vTrial_[d] * vTrial_[d];
          } else {
            for (int d = 0; d < nd; ++d) {
              const double vn = (N.v[d] + h * (N.fext[d] - N.fint[d]) / mass_[d / 3]) * free_[d];
              keNew += 0.5 * mass_[d / 3] * vn * vn;
            }
          }
          if (!fresh && keNew < kePrev) {
            // Kinetic-energy peak passed: zero the velocities (after stepping back to the peak).
            ++r.kineticResets;
            if (s_.backstep)
              for (int d = 0; d < nd; ++d) N.x[d] -= 0.5 * N.v[d];
            std::fill(N.v.begin(), N.v.end(), 0.0);
            fresh = true;
            kePrev = 0;
            if (s_.mass == FictitiousMassRule::StressBound || s_.updateMasses) {
              mass_ = fictitiousMasses(model_, N.x.data(), s_.mass, lambda);
              for (double& m : mass_) m = std::max(m, 1e-9 * mmax);
            }
            if (s_.backstep) forces(lf);
            continue;
          }
          kePrev = keNew;
        }
        const double cv = kinetic ? 1.0 : (2.0 - c) / (2.0 + c);
        const double cr = kinetic ? h : (fresh ? 0.5 : 2.0 / (2.0 + c));
        for (int d = 0; d < nd; ++d) {
          const double R = N.fext[d] - N.fint[d];
          Rprev[d] = R;
          N.v[d] = (cv * N.v[d] + cr * R / mass_[d / 3]) * free_[d];
          N.x[d] += N.v[d];
        }
        for (const PlaneSlider& sl : constraints_.sliders)
          sl.project(&N.v[3 * sl.node], &N.x[3 * sl.node], 1.0);
        // A tie group moves with its summed (fictitious) mass and residual: the mass-weighted mean of its
        // members' updates.
        if (tied) constraints_.ties.project(mass_.data(), N.v.data(), N.x.data(), 1.0);
        fresh = false;
        forces(lf);

        // Apparent-frequency test (Underwood) and, for viscous damping, the Rayleigh-quotient ω0².
        double dxMax = 0;
        for (int d = 0; d < nd; ++d) dxMax = std::max(dxMax, std::abs(N.v[d]));
        double num = 0, den = 0;
        for (int i = 0; i < N.count; ++i) {
          double dR2 = 0, dx2 = 0;
          for (int k = 0; k < 3; ++k) {
            const int d = 3 * i + k;
            if (free_[d] == 0.0) continue;
            const double dR = (N.fext[d] - N.fint[d]) - Rprev[d];
            dR2 += dR * dR;
            dx2 += N.v[d] * N.v[d];
            if (!kinetic && std::abs(N.v[d]) > 1e-12 * dxMax) {
              const double u = N.x[d] - N.X[d];
              num += u * u * (-dR / N.v[d]);
              den += u * u * mass_[i];
            }
          }
          if (s_.autoMass && dx2 > 1e-12 * dxMax * dxMax) {
            const double ratio = std::sqrt(dR2 / dx2) / (4.0 * mass_[i]);
            strikes[i] = ratio > 1.0 ? static_cast<unsigned char>(std::min(strikes[i] + 1, 255)) : 0;
            if (strikes[i] >= 3) {
              mass_[i] *= 1.2 * ratio;
              strikes[i] = 0;
              ++r.massIncreases;
            }
          }
        }
        if (!kinetic && den > 0) {
          const double w2 = std::max(0.0, num / den);
          c = s_.coefficient == RelaxationSettings::Coefficient::Underwood
                  ? 2.0 * std::sqrt(w2)
                  : std::sqrt(std::max(0.0, 4 * w2 - w2 * w2));
        }
      }
    }
    if (!converged) {
      r.reason = StopReason::NotConverged;
      r.finalLambda = lambda;
      locateResidual(r);
      r.message = fmt::format(
          "increment {} of {} did not converge in {} iterations (residual ratio {:.3g}, "
          "KE/U {:.3g})",
          inc, s_.increments, s_.maxIterations, r.residualRatio, r.energyRatio);
      return r;
    }
    if (onIncrement) onIncrement(inc, r);
  }
  r.reason = StopReason::Static;
  r.finalLambda = lambda;
  return r;
}

void DynamicRelaxation::keepIfBest(long iteration, int increment, double loadFactor, double residualRatio) {
  if (!best_.empty() && !(residualRatio < best_.scalars["residual_ratio"])) return;
  best_.x.assign(model_.nodes.x.begin(), model_.nodes.x.end());
  best_.v.assign(model_.nodes.v.begin(), model_.nodes.v.end());
  best_.step = iteration;
  best_.time = loadFactor;  // the pseudo time of a relaxation's frames
  best_.dt = 1.0;
  best_.scalars["residual_ratio"] = residualRatio;
  best_.scalars["load_factor"] = loadFactor;
  best_.scalars["increment"] = increment;
}

void DynamicRelaxation::sharedResidual() {
  const Nodes& N = model_.nodes;
  resid_.resize(N.fext.size());
  for (std::size_t d = 0; d < resid_.size(); ++d) resid_[d] = N.fext[d] - N.fint[d];
  constraints_.ties.shareByMass(mass_.data(), resid_.data());
}

void DynamicRelaxation::locateResidual(RelaxationResult& r) {
  const Nodes& N = model_.nodes;
  const bool tied = !constraints_.ties.empty();
  if (tied) sharedResidual();
  r.worstNode = -1;
  r.nonFiniteNodes = 0;
  r.firstNonFiniteNode = -1;
  double worst = -1;
  for (int i = 0; i < N.count; ++i) {
    double r2 = 0;
    for (int k = 0; k < 3; ++k) {
      const int d = 3 * i + k;
      const double R = (tied ? resid_[d] : N.fext[d] - N.fint[d]) * free_[d];
      r2 += R * R;
    }
    if (!std::isfinite(r2) || !std::isfinite(N.x[3 * i] + N.x[3 * i + 1] + N.x[3 * i + 2])) {
      if (r.firstNonFiniteNode < 0) r.firstNonFiniteNode = i;
      ++r.nonFiniteNodes;
    } else if (r2 > worst) {
      worst = r2;
      r.worstNode = i;
    }
  }
}

}  // namespace fsi::structure
