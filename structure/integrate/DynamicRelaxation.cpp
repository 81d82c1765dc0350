#include "structure/integrate/DynamicRelaxation.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#ifdef FSI_HAVE_OPENMP
#include <omp.h>
#endif

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
  // The node loops follow the forces' threading; a tie group's sums span the ranges, so ties keep them
  // serial.
  threadedSweeps_ = !forces_.serial() && constraints_.ties.empty();
  parts_.resize(threadedSweeps_ ? std::size_t(forces_.shares()) : 1);
}

void DynamicRelaxation::forces(double loadFactor) {
  strain_ = forces_.evaluate(model_.nodes, s_.loadTime, loadFactor, true).strainEnergy;
}

void DynamicRelaxation::NodeSums::add(const NodeSums& o) {
  res = std::max(res, o.res);
  reac = std::max(reac, o.reac);
  fmax = std::max(fmax, o.fmax);
  dxNext = std::max(dxNext, o.dxNext);
  ke += o.ke, all += o.all, keNew += o.keNew, num += o.num, den += o.den;
  massIncreases += o.massIncreases;
}

int DynamicRelaxation::sweepBegin(int s) const {
  return threadedSweeps_ ? forces_.nodeBegin(s) : 0;
}

int DynamicRelaxation::sweepEnd(int s) const {
  return threadedSweeps_ ? forces_.nodeEnd(s) : model_.nodes.count;
}

void DynamicRelaxation::before(int begin, int end, const Sweep& sw, NodeSums& out) {
  Nodes& N = model_.nodes;
  double* __restrict x = N.x.data();
  double* __restrict v = N.v.data();
  if (sw.before == Sweep::Before::Backstep) {
    for (int d = 3 * begin; d < 3 * end; ++d) {
      x[d] -= 0.5 * v[d];
      v[d] = 0.0;
    }
    return;
  }
  const double* __restrict fi = N.fint.data();
  const double* __restrict fe = N.fext.data();
  const double* __restrict m = mass_.data();
  const double* __restrict fr = free_.data();
  double* __restrict Rp = Rprev_.data();
  const double cv = sw.cv, cr = sw.cr;
  for (int d = 3 * begin; d < 3 * end; ++d) {
    const double R = fe[d] - fi[d];
    Rp[d] = R;
    v[d] = (cv * v[d] + cr * R / m[d / 3]) * fr[d];
    x[d] += v[d];
  }
  for (const PlaneSlider& sl : constraints_.sliders)
    if (sl.node >= begin && sl.node < end) sl.project(&v[3 * sl.node], &x[3 * sl.node], 1.0);
  double dx = 0;
  for (int d = 3 * begin; d < 3 * end; ++d) dx = std::max(dx, std::abs(v[d]));
  out.dxNext = dx;
}

void DynamicRelaxation::after(int begin, int end, const Sweep& sw, double dxMax, NodeSums& out) {
  Nodes& N = model_.nodes;
  const double* __restrict x = N.x.data();
  const double* __restrict v = N.v.data();
  const double* __restrict X = N.X.data();
  const double* __restrict fi = N.fint.data();
  const double* __restrict fe = N.fext.data();
  const double* __restrict fr = free_.data();
  double* __restrict m = mass_.data();
  double* __restrict Rp = Rprev_.data();
  unsigned char* __restrict strikes = strikes_.data();
  const bool kinetic = s_.damping == RelaxationSettings::Damping::Kinetic;
  const bool tied = !constraints_.ties.empty();
  const double h = sw.h;
  double res = 0, reac = 0, fmax = 0, ke = 0, all = 0, keNew = 0, num = 0, den = 0, dxNext = 0;
  int raised = 0;
  // Apparent-frequency test (Underwood) and, for viscous damping, the Rayleigh-quotient ω0² of node i, after
  // an update: may raise m[i], which the norms and the trial of the same node then use.
  auto underwood = [&](int i) {
    double dR2 = 0, dx2 = 0;
    for (int k = 0; k < 3; ++k) {
      const int d = 3 * i + k;
      if (fr[d] == 0.0) continue;
      const double dR = (fe[d] - fi[d]) - Rp[d];
      dR2 += dR * dR;
      dx2 += v[d] * v[d];
      if (!kinetic && std::abs(v[d]) > 1e-12 * dxMax) {
        const double u = x[d] - X[d];
        num += u * u * (-dR / v[d]);
        den += u * u * m[i];
      }
    }
    if (s_.autoMass && dx2 > 1e-12 * dxMax * dxMax) {
      const double ratio = std::sqrt(dR2 / dx2) / (4.0 * m[i]);
      strikes[i] = ratio > 1.0 ? static_cast<unsigned char>(std::min(strikes[i] + 1, 255)) : 0;
      if (strikes[i] >= 3) {
        m[i] *= 1.2 * ratio;
        strikes[i] = 0;
        ++raised;
      }
    }
  };
  // Static residual on free dofs, reactions on constrained ones (R: the residual, tie forces left out).
  // std::max drops a NaN, so the sum `all` carries any non-finite residual to the divergence test.
  auto norms = [&](int i, const double* R) {
    for (int k = 0; k < 3; ++k) {
      const int d = 3 * i + k;
      const double Rd = R ? R[d] : fe[d] - fi[d];
      all += Rd;
      fmax = std::max(fmax, std::abs(fe[d]));
      if (fr[d] != 0.0) {
        res = std::max(res, std::abs(Rd));
        ke += 0.5 * m[i] * v[d] * v[d];
      } else {
        reac = std::max(reac, std::abs(Rd));
      }
    }
  };
  if (!tied) {
    double* __restrict vn = vNext_.data();
    double* __restrict xn = xNext_.data();
    // One pass: every loop of the iteration over these nodes.
    for (int i = begin; i < end; ++i) {
      if (sw.underwood) underwood(i);
      norms(i, nullptr);
      if (sw.trial)
        for (int k = 0; k < 3; ++k) {
          const int d = 3 * i + k;
          const double R = fe[d] - fi[d];
          const double vNew = (v[d] + h * R / m[i]) * fr[d];
          keNew += 0.5 * m[i] * vNew * vNew;
          if (sw.speculate) {
            Rp[d] = R;
            vn[d] = vNew;
            xn[d] = x[d] + vNew;
            dxNext = std::max(dxNext, std::abs(vNew));
          }
        }
    }
    if (sw.speculate && !constraints_.sliders.empty()) {
      bool moved = false;
      for (const PlaneSlider& sl : constraints_.sliders)
        if (sl.node >= begin && sl.node < end)
          sl.project(&vn[3 * sl.node], &xn[3 * sl.node], 1.0), moved = true;
      if (moved) {
        dxNext = 0;
        for (int d = 3 * begin; d < 3 * end; ++d) dxNext = std::max(dxNext, std::abs(vn[d]));
      }
    }
  } else {
    // Tie groups (serial, all nodes): the norms see each tied node's share of its group's residual, the trial
    // the tied motion.
    if (sw.underwood)
      for (int i = begin; i < end; ++i) underwood(i);
    sharedResidual();
    for (int i = begin; i < end; ++i) norms(i, resid_.data());
    if (sw.trial) {
      const int nd = 3 * N.count;
      vTrial_.resize(std::size_t(nd));
      for (int d = 0; d < nd; ++d) vTrial_[d] = (v[d] + h * (fe[d] - fi[d]) / m[d / 3]) * fr[d];
      constraints_.ties.project(m, vTrial_.data(), nullptr, 0.0);
      for (int d = 0; d < nd; ++d) keNew += 0.5 * m[d / 3] * vTrial_[d] * vTrial_[d];
    }
  }
  out.res = res, out.reac = reac, out.fmax = fmax, out.ke = ke, out.all = all, out.keNew = keNew;
  out.num = num, out.den = den, out.dxNext = dxNext, out.massIncreases = raised;
}

DynamicRelaxation::NodeSums DynamicRelaxation::evaluate(double loadFactor, const Sweep& sw, bool withForces) {
  Nodes& N = model_.nodes;
  const int shares = int(parts_.size());
  const bool update = sw.before == Sweep::Before::Update;
  if (!withForces) {
    for (int s = 0; s < shares; ++s) after(sweepBegin(s), sweepEnd(s), sw, dxMax_, parts_[std::size_t(s)]);
  } else if (!threadedSweeps_) {
    double dxMax = dxMax_;
    if (sw.before != Sweep::Before::None) {
      before(0, N.count, sw, parts_[0]);
      dxMax = parts_[0].dxNext;
      if (update && !constraints_.ties.empty()) {
        // A tie group moves with its summed (fictitious) mass and residual: the mass-weighted mean of its
        // members' updates.
        constraints_.ties.project(mass_.data(), N.v.data(), N.x.data(), 1.0);
        dxMax = 0;
        for (double vd : N.v) dxMax = std::max(dxMax, std::abs(vd));
      }
    }
    forces(loadFactor);
    after(0, N.count, sw, dxMax, parts_[0]);
  } else {
#ifdef FSI_HAVE_OPENMP
    const ForceContext base = forceContextFor(N, s_.loadTime, loadFactor, true);
#pragma omp parallel num_threads(shares)
    {
      // As CentralDifference::forcesAndSweep: a thread takes several shares if the runtime gives fewer
      // threads than asked. The moves before the forces need a barrier (the shares' elements read the
      // neighbours' nodes); the gather and the node loops after them see the same nodes, so none there.
      const int nt = omp_get_num_threads(), t = omp_get_thread_num();
      double dxMax = dxMax_;
      if (sw.before != Sweep::Before::None) {
        for (int s = t; s < shares; s += nt) before(sweepBegin(s), sweepEnd(s), sw, parts_[std::size_t(s)]);
#pragma omp barrier
        if (update) {  // max |v| over all nodes (exact in any order)
          dxMax = 0;
          for (const NodeSums& p : parts_) dxMax = std::max(dxMax, p.dxNext);
        }
      }
      forces_.evaluateShares(t, nt, base);
#pragma omp barrier
      for (int s = t; s < shares; s += nt) {
        forces_.gather(s, base.fint, base.fext);
        after(sweepBegin(s), sweepEnd(s), sw, dxMax, parts_[std::size_t(s)]);
      }
    }
#endif
    strain_ = forces_.strainEnergy();
  }
  // The ranges' sums in range order: the result does not depend on the scheduling.
  NodeSums total = parts_[0];
  for (std::size_t s = 1; s < parts_.size(); ++s) total.add(parts_[s]);
  if (sw.speculate) dxMax_ = total.dxNext;
  return total;
}

RelaxationResult DynamicRelaxation::run(const std::function<void(int, const RelaxationResult&)>& onIncrement,
                                        const std::function<bool()>& interrupted) {
  Nodes& N = model_.nodes;
  const int nd = 3 * N.count;
  RelaxationResult r;
  r.lambda = s_.lambda > 0 ? s_.lambda : defaultLambda(s_);
  const bool kinetic = s_.damping == RelaxationSettings::Damping::Kinetic;
  // Kinetic damping without tie groups computes each update with its trial (speculate): the update is then
  // a swap of arrays, and an iteration one pass over the nodes.
  const bool speculate = kinetic && constraints_.ties.empty();
  Rprev_.assign(std::size_t(nd), 0.0);
  if (speculate) vNext_.assign(std::size_t(nd), 0.0), xNext_.assign(std::size_t(nd), 0.0);
  // Consecutive failures of the apparent-frequency test per node: a neighbour's large move can fail it once,
  // a node that is really too light fails it every iteration (its error grows like a Nyquist mode).
  strikes_.assign(std::size_t(N.count), 0);
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
      // After a start or a reset the next velocity update is a half step (fresh).
      Sweep start;
      start.trial = kinetic;
      start.h = 0.5;
      start.speculate = speculate;
      NodeSums sums = evaluate(lf, start);
      bool fresh = true;
      double kePrev = 0, c = 0, res0 = -1;
      while (true) {
        const double res = sums.res, reac = sums.reac, fmax = sums.fmax, ke = sums.ke;
        const bool finite = std::isfinite(sums.all) && std::isfinite(strain_) && std::isfinite(ke);
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
            std::fill(strikes_.begin(), strikes_.end(), 0);
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
          // sums.keNew: the kinetic energy the update is about to give (of the tied motion with ties).
          if (!fresh && sums.keNew < kePrev) {
            // Kinetic-energy peak passed: zero the velocities (after stepping back to the peak).
            ++r.kineticResets;
            Sweep again = start;
            const bool refresh = s_.mass == FictitiousMassRule::StressBound || s_.updateMasses;
            if (s_.backstep && !refresh) {
              again.before = Sweep::Before::Backstep;  // in the evaluation's parallel region
            } else {
              if (s_.backstep)
                for (int d = 0; d < nd; ++d) N.x[d] -= 0.5 * N.v[d];
              std::fill(N.v.begin(), N.v.end(), 0.0);
              if (refresh) {
                mass_ = fictitiousMasses(model_, N.x.data(), s_.mass, lambda);
                for (double& m : mass_) m = std::max(m, 1e-9 * mmax);
              }
            }
            sums = evaluate(lf, again, s_.backstep);
            fresh = true;
            kePrev = 0;
            continue;
          }
          kePrev = sums.keNew;
        }
        Sweep next;
        next.underwood = s_.autoMass || !kinetic;
        next.trial = kinetic;
        next.h = 1.0;
        next.speculate = speculate;
        if (speculate) {
          // The update the trial computed (v, x, sliders; R in Rprev_).
          std::swap(N.v, vNext_);
          std::swap(N.x, xNext_);
        } else {
          next.before = Sweep::Before::Update;
          next.cv = kinetic ? 1.0 : (2.0 - c) / (2.0 + c);
          next.cr = kinetic ? h : (fresh ? 0.5 : 2.0 / (2.0 + c));
        }
        fresh = false;
        sums = evaluate(lf, next);
        r.massIncreases += sums.massIncreases;
        if (!kinetic && sums.den > 0) {
          const double w2 = std::max(0.0, sums.num / sums.den);
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
