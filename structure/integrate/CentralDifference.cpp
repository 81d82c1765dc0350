#include "structure/integrate/CentralDifference.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

#ifdef FSI_HAVE_OPENMP
#include <omp.h>
#endif

namespace fsi::structure {

namespace {
double halfVelocityEnergy(const Nodes& N) {
  double ke = 0;
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) ke += 0.5 * N.mass[i] * N.v[3 * i + k] * N.v[3 * i + k];
  return ke;
}

using SweepSums = CentralDifference::SweepSums;
struct SweepCoefficients {
  double c1, c2, dtAvg, dtNext;
};

// v(n+½) and x(n+1) of nodes [begin, end), and their sums.
void sweepNodes(int begin, int end, const SweepCoefficients& c, double* __restrict x, double* __restrict v,
                const double* __restrict fi, const double* __restrict fe, const double* __restrict im,
                const double* __restrict m, SweepSums& out) {
  const double c1 = c.c1, c2 = c.c2, dtAvg = c.dtAvg, dtNext = c.dtNext;
  double ke = 0, prod = 0, vv = 0, extOld = 0, intOld = 0, extNew = 0, intNew = 0;
  for (int i = begin; i < end; ++i) {
    double keNode = 0, prodNode = 0, vvNode = 0;
    for (int k = 0; k < 3; ++k) {
      const int d = 3 * i + k;
      const double vOld = v[d];
      const double vNew = (c1 * vOld + dtAvg * im[d] * (fe[d] - fi[d])) * c2;
      extOld += fe[d] * vOld;
      intOld += fi[d] * vOld;
      extNew += fe[d] * vNew;
      intNew += fi[d] * vNew;
      const double vMid = 0.5 * (vOld + vNew);
      keNode += vMid * vMid;
      prodNode += vOld * vNew;
      vvNode += vNew * vNew;
      v[d] = vNew;
      x[d] += dtNext * vNew;
    }
    ke += 0.5 * m[i] * keNode;
    prod += m[i] * prodNode;
    vv += m[i] * vvNode;
  }
  out = {ke, prod, vv, extOld, intOld, extNew, intNew};
}

SweepCoefficients coefficients(double dtPrev, double dtNext, double massDamping) {
  const double dtAvg = 0.5 * (dtPrev + dtNext);
  return {1.0 - 0.5 * massDamping * dtAvg, 1.0 / (1.0 + 0.5 * massDamping * dtAvg), dtAvg, dtNext};
}

EnergyLedger ledgerFrom(double kinetic) {
  EnergyLedger e;
  e.initialKinetic = e.kinetic = e.kineticProduct = e.supplied = kinetic;
  return e;
}
}  // namespace

void CentralDifference::SweepSums::add(const SweepSums& o) {
  ke += o.ke, prod += o.prod, vv += o.vv, extOld += o.extOld, intOld += o.intOld, extNew += o.extNew,
      intNew += o.intNew;
}

CentralDifference::CentralDifference(Model& model, std::vector<const Effect*> effects,
                                     Constraints constraints, CentralDifferenceSettings settings,
                                     double startTime)
    : model_(model),
      effects_(std::move(effects)),
      constraints_(std::move(constraints)),
      settings_(settings),
      forces_(effects_, settings.threads, model.nodes.count),
      sweepParts_(std::size_t(forces_.shares())),
      time_(startTime) {
  // A dof listed twice (a node in two selected sets) follows its last entry; one entry per dof books the
  // support reaction once.
  auto& pm = constraints_.prescribed;
  std::set<int> seen;
  std::vector<PrescribedMotion> unique;
  for (auto it = pm.rbegin(); it != pm.rend(); ++it)
    if (seen.insert(3 * it->node + it->component).second) unique.push_back(*it);
  pm.assign(unique.rbegin(), unique.rend());
  prescribedOld_.resize(2 * pm.size());
  sliderOld_.resize(3 * constraints_.sliders.size());
  const TieGroups& ties = constraints_.ties;
  tieOld_.resize(6 * ties.nodes.size());
  tieMass_.assign(std::size_t(ties.groups()), 0.0);
  for (int g = 0; g < ties.groups(); ++g)
    for (int j = ties.start[g]; j < ties.start[g + 1]; ++j) tieMass_[g] += model_.nodes.mass[ties.nodes[j]];
  constraints_.applyTo(model_.nodes);
  ledger_ = ledgerFrom(halfVelocityEnergy(model_.nodes));
  recordInitialStrain();
}

double CentralDifference::recordInitialStrain() {
  // A separate evaluation: the steps' own force evaluations stay exactly those of a run without it (the
  // kernels that sum the energy may round differently).
  const ForceContext ctx = forces_.evaluate(model_.nodes, time_, 1.0, true);
  ledger_.initialStrain = ctx.strainEnergy;
  ledger_.updateSupplied();
  return ctx.minStableDt;
}

double CentralDifference::computeForces(bool withEnergy) {
  const ForceContext ctx = forces_.evaluate(model_.nodes, time_, 1.0, withEnergy);
  if (withEnergy) ledger_.strain = ctx.strainEnergy;
  stableDt_ = ctx.minStableDt;
  return ctx.minStableDt;
}

void CentralDifference::evaluateForces(bool withEnergy) {
  computeForces(withEnergy);
}

double CentralDifference::createdAtCurrentState() {
  computeForces(true);
  const Nodes& N = model_.nodes;
  double power = 0;
  for (int d = 0; d < 3 * N.count; ++d) power += N.fint[d] * N.v[d];
  EnergyLedger e = ledger_;
  e.internalWork += ledger_.pendingInt + 0.5 * dt_ * power;
  return e.created();
}

double CentralDifference::nextDt(double stable, double limitTime) const {
  double dtNext =
      settings_.fixedDt > 0 ? settings_.fixedDt : std::min(settings_.safety * stable, settings_.maxDt);
  if (!(dtNext > 0) || !std::isfinite(dtNext)) dtNext = settings_.maxDt < 1e299 ? settings_.maxDt : 0.0;
  // No element bounds the step and no maximum is set: nothing to integrate.
  if (!(dtNext > 0)) return std::numeric_limits<double>::quiet_NaN();
  // Land exactly on the limit in equal steps, not by shortening the last one or two: output times and
  // coupling windows recur, and a step that changes periodically pumps energy into the modes near the
  // stability limit (parametric resonance) although each step is stable. The step count is the same.
  const double remaining = limitTime - time_;
  if (remaining <= dtNext * (1.0 + 1e-9)) return remaining;
  return remaining / std::ceil(remaining / (dtNext * (1.0 + 1e-9)));  // same tolerance: no extra step
}

double CentralDifference::forcesAndSweep(double limitTime, bool monitor, SweepSums& sums) {
  Nodes& N = model_.nodes;
  const ForceContext base = forceContextFor(N, time_, 1.0, monitor);
  double dtNext = std::numeric_limits<double>::quiet_NaN();
#ifdef FSI_HAVE_OPENMP
  double* __restrict x = N.x.data();
  double* __restrict v = N.v.data();
  const double* __restrict im = N.invMassDof.data();
  const double* __restrict m = N.mass.data();
  const int shares = forces_.shares();
#pragma omp parallel num_threads(shares)
  {
    // The runtime may give fewer threads than asked (nested regions, OMP_THREAD_LIMIT): a thread then takes
    // several shares.
    const int nt = omp_get_num_threads(), t = omp_get_thread_num();
    forces_.evaluateShares(t, nt, base);
#pragma omp barrier
    // Every thread derives the same step from the shares' stable steps (a minimum: exact in any order), then
    // completes the forces of its nodes and moves them: the gather and the sweep see the same nodes, so no
    // barrier between them.
    const double dt = nextDt(forces_.minStableDt(), limitTime);
    if (!std::isnan(dt)) {
      const SweepCoefficients coef = coefficients(dt_, dt, settings_.massDamping);
      for (int s = t; s < shares; s += nt) {
        forces_.gather(s, base.fint, base.fext);
        sweepNodes(forces_.nodeBegin(s), forces_.nodeEnd(s), coef, x, v, base.fint, base.fext, im, m,
                   sweepParts_[std::size_t(s)]);
      }
    }
    if (t == 0) dtNext = dt;
  }
#endif
  stableDt_ = forces_.minStableDt();
  if (monitor) ledger_.strain = forces_.strainEnergy();
  // The ranges' sums in range order: a run is reproducible.
  if (!std::isnan(dtNext))
    for (const SweepSums& p : sweepParts_) sums.add(p);
  return dtNext;
}

bool CentralDifference::step(double limitTime, bool monitor) {
  Nodes& N = model_.nodes;
  double* __restrict x = N.x.data();
  double* __restrict v = N.v.data();
  const double* __restrict fi = N.fint.data();
  const double* __restrict fe = N.fext.data();
  const double* __restrict im = N.invMassDof.data();
  const double* __restrict m = N.mass.data();
  const double* __restrict X = N.X.data();

  // v(n−½) and x(n) of the constrained dofs, which the sweep below overwrites.
  for (std::size_t j = 0; j < constraints_.prescribed.size(); ++j) {
    const PrescribedMotion& p = constraints_.prescribed[j];
    prescribedOld_[2 * j] = v[3 * p.node + p.component];
    prescribedOld_[2 * j + 1] = x[3 * p.node + p.component];
  }
  for (std::size_t j = 0; j < constraints_.sliders.size(); ++j)
    for (int k = 0; k < 3; ++k) sliderOld_[3 * j + k] = v[3 * constraints_.sliders[j].node + k];
  const TieGroups& ties = constraints_.ties;
  for (std::size_t j = 0; j < ties.nodes.size(); ++j)
    for (int k = 0; k < 3; ++k) {
      tieOld_[6 * j + k] = v[3 * ties.nodes[j] + k];
      tieOld_[6 * j + 3 + k] = x[3 * ties.nodes[j] + k];
    }

  // One sweep: update, physical KE of the mid-step velocity, Σ m v(n−½)·v(n+½), Σ m v(n+½)², and the
  // forces' power at both half-step velocities (the two halves of this evaluation's work).
  SweepSums sums;
  double dtNext;
  if (forces_.serial()) {
    dtNext = nextDt(computeForces(monitor), limitTime);
    if (!std::isnan(dtNext))
      sweepNodes(0, N.count, coefficients(dt_, dtNext, settings_.massDamping), x, v, fi, fe, im, m, sums);
  } else {
    dtNext = forcesAndSweep(limitTime, monitor, sums);
  }
  if (std::isnan(dtNext)) return false;
  const SweepCoefficients coef = coefficients(dt_, dtNext, settings_.massDamping);
  const double dtAvg = coef.dtAvg, c1 = coef.c1, c2 = coef.c2;
  const double a = settings_.massDamping;
  double ke = sums.ke, prod = sums.prod, vv = sums.vv, extOld = sums.extOld, intOld = sums.intOld,
         extNew = sums.extNew, intNew = sums.intNew;

  // Constrained dofs: replace the sweep's free velocity vCur by the constrained one in the sums, and book the
  // work of the support reaction R, defined by M(v(n+½) − v(n−½)) = Δ(f_ext − f_int − α M v̄ + R), in the
  // same two halves as every other force.
  double reactOld = 0, reactNew = 0;
  // The prescribed dofs' share of the half-step start correction below (their velocity jump is an impulse).
  double pReactOld = 0, pReactNew = 0, pExt = 0, pInt = 0, pDamp = 0, pKick = 0;
  auto replace = [&](int d, double mi, double vOld, double vCur, double vNew) {
    ke += 0.125 * mi * ((vOld + vNew) * (vOld + vNew) - (vOld + vCur) * (vOld + vCur));
    prod += mi * vOld * (vNew - vCur);
    vv += mi * (vNew * vNew - vCur * vCur);
    extNew += fe[d] * (vNew - vCur);
    intNew += fi[d] * (vNew - vCur);
  };
  // Prescribed motions: set the position, derive the velocity.
  for (std::size_t j = 0; j < constraints_.prescribed.size(); ++j) {
    const PrescribedMotion& p = constraints_.prescribed[j];
    const int d = 3 * p.node + p.component;
    const double mi = m[p.node];
    const double vOld = prescribedOld_[2 * j], xOld = prescribedOld_[2 * j + 1], vCur = v[d];
    const double target = X[d] + p.amplitude * p.fn(time_ + dtNext);
    const double vNew = (target - xOld) / dtNext;
    v[d] = vNew;
    x[d] = target;
    replace(d, mi, vOld, vCur, vNew);
    const double rDelta = mi * (vNew - vOld) + 0.5 * a * dtAvg * mi * (vOld + vNew) - dtAvg * (fe[d] - fi[d]);
    pReactOld += 0.5 * rDelta * vOld;
    pReactNew += 0.5 * rDelta * vNew;
    pExt += fe[d] * (vNew - vOld);
    pInt += fi[d] * (vNew - vOld);
    pDamp += mi * 0.5 * (vOld + vNew) * (vNew - vOld);
    pKick += 0.5 * mi * (vNew - vOld) * (vNew - vOld);
  }
  reactOld += pReactOld;
  reactNew += pReactNew;
  // Oblique symmetry planes: remove the normal component of velocity and of the step just taken. The
  // reaction is normal to the plane, so its work is that of removing the normal velocity.
  for (std::size_t j = 0; j < constraints_.sliders.size(); ++j) {
    const PlaneSlider& s = constraints_.sliders[j];
    double* vs = v + 3 * s.node;
    const double vCur[3] = {vs[0], vs[1], vs[2]};
    s.project(vs, x + 3 * s.node, dtNext);
    const double mi = m[s.node];
    for (int k = 0; k < 3; ++k) {
      const double vOld = sliderOld_[3 * j + k], vNew = vs[k];
      replace(3 * s.node + k, mi, vOld, vCur[k], vNew);
      const double rDelta = mi * (1.0 + 0.5 * a * dtAvg) * (vNew - vCur[k]);
      reactOld += 0.5 * rDelta * vOld;
      reactNew += 0.5 * rDelta * vNew;
    }
  }

  // Tie groups: the group's tied velocity from its summed mass and force (the M-weighted mean of its
  // members' free updates, computed from the sums so that every member gets the same number); the sweep's
  // values are replaced as for the constraints above, and the tie force R defined the same way is booked
  // with the reactions: its work on tied motions is zero (Σ R = 0 across d, R ⟂ d), so what is booked is
  // round-off, and the balance stays an identity.
  for (int g = 0; g < ties.groups(); ++g) {
    double mv[3] = {0, 0, 0}, f[3] = {0, 0, 0};
    for (int j = ties.start[g]; j < ties.start[g + 1]; ++j) {
      const int i = ties.nodes[j];
      for (int k = 0; k < 3; ++k) {
        mv[k] += m[i] * tieOld_[6 * j + k];
        f[k] += fe[3 * i + k] - fi[3 * i + k];
      }
    }
    double sum[3], V[3];
    for (int k = 0; k < 3; ++k) sum[k] = (c1 * mv[k] + dtAvg * f[k]) * c2 / tieMass_[g];
    ties.tiedPart(g, sum, V);
    for (int j = ties.start[g]; j < ties.start[g + 1]; ++j) {
      const int i = ties.nodes[j];
      const double mi = m[i];
      double vCur[3], t[3];
      for (int k = 0; k < 3; ++k) vCur[k] = v[3 * i + k];
      ties.tiedPart(g, vCur, t);
      for (int k = 0; k < 3; ++k) {
        const int d = 3 * i + k;
        const double vOld = tieOld_[6 * j + k], vNew = (vCur[k] - t[k]) + V[k];
        v[d] = vNew;
        x[d] = tieOld_[6 * j + 3 + k] + dtNext * vNew;
        replace(d, mi, vOld, vCur[k], vNew);
        const double rDelta = mi * (1.0 + 0.5 * a * dtAvg) * (vNew - vCur[k]);
        reactOld += 0.5 * rDelta * vOld;
        reactNew += 0.5 * rDelta * vNew;
      }
    }
  }

  // ½Δ G·v(n∓½) per force; mass damping −α M v̄ with Σ m v̄·v(n−½) = ½(A + B), Σ m v̄·v(n+½) = ½(B + C),
  // A = Σ m v(n−½)², B = Σ m v(n−½)·v(n+½), C = Σ m v(n+½)² (A from the mid-step sum: 8 KE = A + 2B + C).
  const double h = 0.5 * dtAvg;
  const double A = 8.0 * ke - 2.0 * prod - vv;
  double wExt = h * extOld + reactOld, wInt = h * intOld, wDamp = 0.5 * a * h * (A + prod);
  const double nextExt = h * extNew + reactNew, nextInt = h * intNew, nextDamp = 0.5 * a * h * (prod + vv);
  if (dt_ == 0) {
    // Half-step start, v(−½) = v(0): the first half of each work is taken as ½Δ(0) G·v(½) (as for a
    // virtual v(−½) = v(0) − δv), and the initial kinetic energy as KE0 − ½ δv·M δv, δv = v(½) − v(0).
    // Then the work booked through x(n) is the trapezoidal ∫ f·dx from x(0) (exact for a constant force).
    // Not for prescribed dofs: their jump to the prescribed velocity is an impulse, whose work is
    // ½ R Δ·(v(0) + v(½)) as booked (the kinetic energy the support gives the node).
    ledger_.startKick += 0.5 * (A - 2.0 * prod + vv) - pKick;  // once per start from rest
    wExt = nextExt - h * pExt - pReactNew + pReactOld;
    wInt = nextInt - h * pInt;
    wDamp = nextDamp - a * h * pDamp;
  }

  ledger_.kinetic = ke;
  ledger_.kineticProduct = 0.5 * prod;
  ledger_.externalWork += ledger_.pendingExt + wExt;
  ledger_.internalWork += ledger_.pendingInt + wInt;
  ledger_.massDamping += ledger_.pendingDamp + wDamp;
  ledger_.pendingExt = nextExt;
  ledger_.pendingInt = nextInt;
  ledger_.pendingDamp = nextDamp;
  ledger_.updateSupplied();
  if (monitor) {
    ledger_.createdLast = ledger_.created();
    ledger_.maxCreated = std::max(ledger_.maxCreated, ledger_.createdLast);
  }
  time_ += dtNext;
  dt_ = dtNext;
  ++steps_;
  return std::isfinite(ke) && std::isfinite(prod) && std::isfinite(wInt) && std::isfinite(wExt);
}

void CentralDifference::stopMotion() {
  std::fill(model_.nodes.v.begin(), model_.nodes.v.end(), 0.0);
  // KE× = ½ v(n−½)·M v(n+½) drops to zero with v(n+½): that energy leaves as dissipation. The pending second
  // halves of the last evaluation's work are ½Δ G·v(n+½), zero now (the next step's first halves are zero
  // too, with v(n+½) = 0), so the identity KE×(n+1) − KE×(n) = work booked goes on holding.
  ledger_.massDamping += ledger_.kineticProduct;
  ledger_.kinetic = ledger_.kineticProduct = 0;
  ledger_.pendingExt = ledger_.pendingInt = ledger_.pendingDamp = 0;
  // At rest at x(n), the next step is a half-step start, v(n+½) = ½Δ a(n), as the first step of a run: a
  // whole kick from v(n−½) = 0 would start the motion as if v(n) were ½Δ a(n), over-kicking the modes near
  // the stability limit (up to 1 − (ωΔ)² ≈ −2.2 per restart at 0.9 of the limit: repeated restarts pump
  // them).
  dt_ = 0;
}

void CentralDifference::restore(const std::vector<double>& x, const std::vector<double>& v, double time,
                                double dt, long steps) {
  model_.nodes.x = x;
  model_.nodes.v = v;
  time_ = time;
  dt_ = dt;
  steps_ = steps;
  ledger_ = ledgerFrom(halfVelocityEnergy(model_.nodes));
  // The current strain energy and step estimate are those of the restored state, not of the state left.
  stableDt_ = recordInitialStrain();
  ledger_.strain = ledger_.initialStrain;
}

StateSnapshot CentralDifference::checkpoint() const {
  StateSnapshot c;
  checkpoint(c);
  return c;
}

void CentralDifference::checkpoint(StateSnapshot& c) const {
  c.x.assign(model_.nodes.x.begin(), model_.nodes.x.end());
  c.v.assign(model_.nodes.v.begin(), model_.nodes.v.end());
  c.time = time_;
  c.dt = dt_;
  c.step = steps_;
  c.ledger = ledger_;
  c.stableDt = stableDt_;
}

void CentralDifference::restore(const StateSnapshot& c) {
  model_.nodes.x = c.x;
  model_.nodes.v = c.v;
  time_ = c.time;
  dt_ = c.dt;
  steps_ = c.step;
  ledger_ = c.ledger;
  stableDt_ = c.stableDt;
}

}  // namespace fsi::structure
