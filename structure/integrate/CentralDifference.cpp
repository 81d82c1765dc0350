#include "structure/integrate/CentralDifference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fsi::structure {

CentralDifference::CentralDifference(Model& model, std::vector<const Effect*> effects,
                                     Constraints constraints, CentralDifferenceSettings settings,
                                     double startTime)
    : model_(model),
      effects_(std::move(effects)),
      constraints_(std::move(constraints)),
      settings_(settings),
      time_(startTime) {
  constraints_.applyTo(model_.nodes);
  const Nodes& N = model_.nodes;
  double ke = 0;
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) ke += 0.5 * N.mass[i] * N.v[3 * i + k] * N.v[3 * i + k];
  ledger_.initialKinetic = ledger_.kinetic = ke;
}

double CentralDifference::computeForces(bool withEnergy) {
  const ForceContext ctx = evaluateEffects(model_.nodes, effects_, time_, 1.0, withEnergy);
  if (withEnergy) ledger_.strain = ctx.strainEnergy;
  stableDt_ = ctx.minStableDt;
  return ctx.minStableDt;
}

void CentralDifference::evaluateForces(bool withEnergy) {
  computeForces(withEnergy);
}

bool CentralDifference::step(double limitTime, bool monitor) {
  Nodes& N = model_.nodes;
  const double stable = computeForces(monitor);
  double dtNext =
      settings_.fixedDt > 0 ? settings_.fixedDt : std::min(settings_.safety * stable, settings_.maxDt);
  if (!(dtNext > 0) || !std::isfinite(dtNext)) dtNext = settings_.maxDt < 1e299 ? settings_.maxDt : 0.0;
  if (!(dtNext > 0)) return false;  // no element bounds the step and no maximum is set: nothing to integrate
  // Land exactly on the limit in equal steps, not by shortening the last one or two: output times and
  // coupling windows recur, and a step that changes periodically pumps energy into the modes near the
  // stability limit (parametric resonance) although each step is stable. The step count is the same.
  const double remaining = limitTime - time_;
  if (remaining <= dtNext * (1.0 + 1e-9))
    dtNext = remaining;
  else
    dtNext = remaining / std::ceil(remaining / (dtNext * (1.0 + 1e-9)));  // same tolerance: no extra step
  const double dtAvg = 0.5 * (dt_ + dtNext);
  const double a = settings_.massDamping;
  const double c1 = 1.0 - 0.5 * a * dtAvg;
  const double c2 = 1.0 / (1.0 + 0.5 * a * dtAvg);

  double* __restrict x = N.x.data();
  double* __restrict v = N.v.data();
  const double* __restrict fi = N.fint.data();
  const double* __restrict fe = N.fext.data();
  const double* __restrict im = N.invMassDof.data();
  const double* __restrict m = N.mass.data();
  // Trapezoidal work: W += ½(f(n−1) + f(n))·Δx(n). The f(n−1) half was computed last step (pending_).
  double ke = 0, wExt = pendingExt_, wInt = pendingInt_, damp = 0, nextExt = 0, nextInt = 0;
  const double dtOld = dt_;
  for (int i = 0; i < N.count; ++i) {
    double keNode = 0, dampNode = 0;
    for (int k = 0; k < 3; ++k) {
      const int d = 3 * i + k;
      const double vOld = v[d];
      const double vNew = (c1 * vOld + dtAvg * im[d] * (fe[d] - fi[d])) * c2;
      const double before = 0.5 * dtOld * vOld, after = 0.5 * dtNext * vNew;  // halves of Δx(n), Δx(n+1)
      wExt += fe[d] * before;
      wInt += fi[d] * before;
      nextExt += fe[d] * after;
      nextInt += fi[d] * after;
      const double vMid = 0.5 * (vOld + vNew);
      keNode += vMid * vMid;
      dampNode += vMid * vMid;
      v[d] = vNew;
      x[d] += dtNext * vNew;
    }
    ke += 0.5 * m[i] * keNode;
    damp += m[i] * dampNode;
  }

  // Prescribed motions: set the position, derive the velocity, book the reaction's work.
  for (const PrescribedMotion& p : constraints_.prescribed) {
    const int d = 3 * p.node + p.component;
    const double xOld = x[d] - dtNext * v[d];
    const double target = N.X[d] + p.amplitude * p.fn(time_ + dtNext);
    const double vOld = v[d];
    v[d] = (target - xOld) / dtNext;
    x[d] = target;
    const double reaction = fi[d] - fe[d];  // force the support applies, static part
    nextExt += reaction * dtNext * v[d];
    ke += 0.5 * m[p.node] * (0.25 * (vOld + v[d]) * (vOld + v[d]) - vOld * vOld);
  }
  // Oblique symmetry planes: remove the normal component of velocity and of the step just taken.
  for (const PlaneSlider& s : constraints_.sliders) {
    double* vv = v + 3 * s.node;
    double* xx = x + 3 * s.node;
    const double vn = vv[0] * s.normal[0] + vv[1] * s.normal[1] + vv[2] * s.normal[2];
    for (int k = 0; k < 3; ++k) {
      vv[k] -= vn * s.normal[k];
      xx[k] -= dtNext * vn * s.normal[k];
    }
  }

  pendingExt_ = nextExt;
  pendingInt_ = nextInt;
  ledger_.kinetic = ke;
  ledger_.externalWork += wExt;
  ledger_.internalWork += wInt;
  ledger_.massDamping += a * damp * dtAvg;
  time_ += dtNext;
  dt_ = dtNext;
  ++steps_;
  return std::isfinite(ke) && std::isfinite(wInt);
}

void CentralDifference::restore(const std::vector<double>& x, const std::vector<double>& v, double time,
                                double dt, long steps) {
  model_.nodes.x = x;
  model_.nodes.v = v;
  time_ = time;
  dt_ = dt;
  steps_ = steps;
}

CentralDifference::Checkpoint CentralDifference::checkpoint() const {
  return {model_.nodes.x, model_.nodes.v, time_, dt_, pendingExt_, pendingInt_, steps_, ledger_};
}

void CentralDifference::restore(const Checkpoint& c) {
  model_.nodes.x = c.x;
  model_.nodes.v = c.v;
  time_ = c.time;
  dt_ = c.dt;
  pendingExt_ = c.pendingExt;
  pendingInt_ = c.pendingInt;
  steps_ = c.steps;
  ledger_ = c.ledger;
}

}  // namespace fsi::structure
