#include "structure/run/InstabilityDiagnosis.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>

#include "structure/elements/ElementKind.hpp"

namespace fsi::structure {

namespace {

// "Most strained element: ..." (or the first with a non-finite strain) over the element kinds that report
// one; empty if none does.
std::string mostStrainedElement(const Scene& scene) {
  const Model& m = *scene.model;
  const ElementKind* worstKind = nullptr;
  StrainedElement worst;
  for (const ElementKind* kind : elementKinds()) {
    if (kind->count(m) == 0) continue;
    const std::optional<StrainedElement> s = kind->mostStrained(m, m.nodes.x.data());
    if (!s) continue;
    if (!std::isfinite(s->strain)) {
      worstKind = kind, worst = *s;
      break;
    }
    if (!worstKind || s->strain > worst.strain) worstKind = kind, worst = *s;
  }
  if (!worstKind) return {};
  if (!std::isfinite(worst.strain))
    return fmt::format("First element with a non-finite strain: {}. ", worstKind->describe(m, worst.element));
  // A fabric or a line fails long before 100 % strain: such a strain says the numbers are wrong, not the
  // solver
  constexpr double kAbsurdStrain = 1.0;
  return fmt::format("Most strained element: {} (major strain {:.3g}{}). ",
                     worstKind->describe(m, worst.element), worst.strain,
                     worst.strain > kAbsurdStrain
                         ? ": above 100 %, which no fabric or line survives; check the units (young in Pa, "
                           "thickness and lengths in m) and the size of the load"
                         : "");
}

// A node whose fictitious mass is far above the median moves that much slower in pseudo time: name it and
// its limiting element (a short cable: EA/l), and what to change. Empty if no node stands out.
std::string heaviestNode(const Model& m, const std::vector<double>& mass) {
  if (mass.size() < 3) return {};
  std::vector<double> sorted(mass);
  std::nth_element(sorted.begin(), sorted.begin() + sorted.size() / 2, sorted.end());
  const double median = sorted[sorted.size() / 2];
  const int i = int(std::max_element(mass.begin(), mass.end()) - mass.begin());
  constexpr double kStandsOut = 20.0;  // a mass ratio of 20: the node's modes are ≈ 4.5x slower
  if (!(median > 0) || !(mass[i] >= kStandsOut * median)) return {};
  std::string s = fmt::format("Heaviest node: {} (fictitious mass {:.3g}, {:.3g} times the median)",
                              m.describeNode(i), mass[i], mass[i] / median);
  const ElementKind* kind = nullptr;
  LimitingElement lim;
  for (const ElementKind* k : elementKinds())
    if (const auto l = k->limitingElementAt(m, i); l && (!kind || l->stableDt < lim.stableDt))
      kind = k, lim = *l;
  if (kind)
    s += fmt::format(", made stiff by {} (length {:.3g} m, stable step {:.3g} s)",
                     kind->describe(m, lim.element), lim.size, lim.stableDt);
  s += fmt::format(
      ": its motion is about {:.2g} times slower than the rest's; a longer element there converges faster "
      "(for a "
      "generated parafoil: cascade_fraction away from 0 and 1, or fewer line_elements). ",
      std::sqrt(mass[i] / median));
  return s;
}

}  // namespace

std::string diagnoseInstability(const Scene& scene, const CentralDifference& cd, long goodSteps,
                                double goodTime, bool nonFinite, double created) {
  const Model& m = *scene.model;
  const Nodes& N = m.nodes;
  std::string s = fmt::format("instability at step {} (t = {:.6g} s): ", cd.steps(), cd.time());
  int firstBad = -1, badCount = 0, fastest = 0;
  double vmax = -1;
  for (int i = 0; i < N.count; ++i) {
    bool finite = true;
    double v2 = 0;
    for (int k = 0; k < 3; ++k) {
      finite = finite && std::isfinite(N.x[3 * i + k]) && std::isfinite(N.v[3 * i + k]);
      v2 += N.v[3 * i + k] * N.v[3 * i + k];
    }
    if (!finite) {
      if (firstBad < 0) firstBad = i;
      ++badCount;
    } else if (v2 > vmax) {
      vmax = v2, fastest = i;
    }
  }
  const EnergyLedger& E = cd.energy();
  if (nonFinite && firstBad >= 0) {
    s += fmt::format("non-finite state at {} node(s), first {}. ", badCount, m.describeNode(firstBad));
  } else if (nonFinite && !std::isfinite(cd.stableDt()) && !(cd.maxDt() < 1e299)) {
    s += "no step could be taken: no element bounds the step (no membrane or cable moves) and time.max_dt "
         "is not set. ";
  } else if (E.growth() > kGrowthLimit || !std::isfinite(E.growth())) {
    s += fmt::format(
        "the energy of the step-to-step velocity change ({:.3g} J) is {:.3g} times the energy supplied to "
        "the structure ({:.3g} J), which a stable step cannot produce (limit {:g}): some mode is above the "
        "stability limit; {} helps; fastest {} (|v| = {:.3g} m/s). ",
        E.kinetic - E.kineticProduct, E.growth(), E.supplied, kGrowthLimit,
        scene.time.integrator.fixedDt > 0 ? "a smaller time.fixed_dt" : "a lower time.safety",
        m.describeNode(fastest), std::sqrt(vmax));
  } else if (const double c = created >= 0 ? created : E.createdLast; !(c <= scene.time.energyTolerance)) {
    s += fmt::format(
        "the elements hold {:.3g} J more strain energy than the work done on them, {:.3g} of the energy "
        "supplied (tolerance {:g}): the integration is creating energy, the step being too large for how "
        "fast the forces change (lines snapping taut, elements switching state) or unstable; element "
        "damping (bulk_viscosity) or a lower time.safety helps; fastest {} (|v| = {:.3g} m/s). ",
        c * E.supplied, c, scene.time.energyTolerance, m.describeNode(fastest), std::sqrt(vmax));
  } else {
    s += fmt::format(
        "energy balance error {:.3g} exceeds the tolerance {:g} (the work of some force is not accounted "
        "for); fastest {} (|v| = {:.3g} m/s). ",
        E.balanceError(), scene.time.energyTolerance, m.describeNode(fastest), std::sqrt(vmax));
  }
  s += mostStrainedElement(scene);
  s += fmt::format(
      "Step used {:.4g} s, element stability estimate {:.4g} s. Last stable state: step {} "
      "(t = {:.6g} s).",
      cd.lastDt(), cd.stableDt(), goodSteps, goodTime);
  return s;
}

std::string diagnoseRelaxation(const Scene& scene, const DynamicRelaxation& dr, const RelaxationResult& r) {
  const Model& m = *scene.model;
  const Nodes& N = m.nodes;
  std::string s;
  if (r.reason == StopReason::Unstable)
    s = fmt::format("dynamic relaxation diverged at iteration {} of increment {}: ", r.iterations,
                    r.increment);
  else
    s = fmt::format("dynamic relaxation did not converge in {} iterations (increment {}): ", r.iterations,
                    r.increment);
  if (r.nonFiniteNodes > 0)
    s += fmt::format("non-finite residual at {} node(s), first {}. ", r.nonFiniteNodes,
                     m.describeNode(r.firstNonFiniteNode));
  else if (r.reason == StopReason::Unstable)
    s += fmt::format("residual ‖R‖∞ {:.3g} N, {:.3g} times its {:.3g} N at the start of the attempt. ",
                     r.residual, r.startResidual > 0 ? r.residual / r.startResidual : 0.0, r.startResidual);
  else
    s += fmt::format("residual ratio {:.3g}, KE/U {:.3g}. ", r.residualRatio, r.energyRatio);
  if (r.worstNode >= 0) {
    const int i = r.worstNode;
    double R = 0;
    for (int k = 0; k < 3; ++k) R += std::pow(N.fext[3 * i + k] - N.fint[3 * i + k], 2);
    s += fmt::format("Largest residual at {} (|R| = {:.3g} N, fictitious mass {:.3g}). ", m.describeNode(i),
                     std::sqrt(R), i < int(dr.masses().size()) ? dr.masses()[i] : 0.0);
  }
  s += mostStrainedElement(scene);
  if (!hasSupport(scene.constraints))
    s += "No node is held (no fix, prescribe or slide constraint): the structure has rigid-body modes, and a "
         "load that does not balance itself moves it instead of deforming it, so the residual cannot vanish; "
         "hold at least three nodes that are not on one line. ";
  if (r.reason == StopReason::NotConverged) s += heaviestNode(m, dr.masses());
  // Residual history: start, lowest, and the last few iterations.
  const auto& h = r.history;
  if (!h.empty()) {
    std::size_t lo = 0;
    for (std::size_t k = 0; k < h.size(); ++k)
      if (std::isfinite(h[k].residualRatio) && !(h[k].residualRatio >= h[lo].residualRatio)) lo = k;
    s += fmt::format("Residual ratio history: {:.3g} at iteration {}, lowest {:.3g} at iteration {}, then",
                     h.front().residualRatio, h.front().iteration, h[lo].residualRatio, h[lo].iteration);
    const std::size_t from = h.size() > 5 ? h.size() - 5 : 0;
    for (std::size_t k = from; k < h.size(); ++k)
      s += fmt::format(" {:.3g} ({})", h[k].residualRatio, h[k].iteration);
    s += ". ";
  }
  s += fmt::format("Mass scale λ {:.3g} (started at {:.3g}; {} restart(s), {} node mass increase(s)).",
                   r.finalLambda, r.lambda, r.restarts, r.massIncreases);
  if (r.reason == StopReason::Unstable)
    s += scene.solver.relaxation.autoMass
             ? " The fictitious masses are too light for the stiffness even after the safeguards: raise "
               "solver.lambda."
             : " The fictitious masses are too light for the stiffness: raise solver.lambda, or enable "
               "solver.auto_mass.";
  const StateSnapshot& b = dr.best();
  if (!b.empty())
    s += fmt::format(" Last good state: iteration {} (residual ratio {:.3g}).", b.step,
                     b.scalars.at("residual_ratio"));
  return s;
}

}  // namespace fsi::structure
