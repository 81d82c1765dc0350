#include "coupling/StructureParticipant.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>

#include "coupling/interface/SceneInterface.hpp"
#include "coupling/scheme/TimeInterpolation.hpp"
#include "structure/io/StateFile.hpp"
#include "structure/model/Error.hpp"
#include "structure/run/InstabilityDiagnosis.hpp"
#include "structure/run/Simulation.hpp"

namespace fsi::coupling {

using structure::Scene;

StructureParticipant::StructureParticipant(const std::filesystem::path& sceneFile,
                                           const std::vector<std::string>& overrides,
                                           const ParticipantOptions& options)
    : StructureParticipant(structure::loadScene(sceneFile, overrides), options) {}

// One structural substep of the window as SubcycledStructure asks for it: the CentralDifference steps up to
// the substep's end (normally one step; more if the stable step fell since the window's start), each under
// the window's load at the instant where it evaluates the forces, written into the participant's load.
class StructureParticipant::Substeps final : public StructureStepper {
 public:
  Substeps(const Scene& scene, structure::CentralDifference& cd, structure::InterfaceLoad& load)
      : scene_(scene), cd_(cd), load_(load) {}

  double stableTimeStep() const override {
    // The step the integrator itself would take (its safety factor included, SubcyclingOptions::safety = 1).
    const structure::CentralDifferenceSettings& s = scene_.time.integrator;
    if (s.fixedDt > 0) return s.fixedDt;
    const double stable = s.safety * cd_.stableDt();
    return std::isfinite(stable) ? std::min(stable, s.maxDt) : s.maxDt;
  }

  void step(double t, double h, const Eigen::VectorXd& f0, const Eigen::VectorXd& f1) override {
    Eigen::Map<Eigen::VectorXd> load(load_.values.data(), Eigen::Index(load_.values.size()));
    const double tEnd = t + h;
    while (cd_.time() < tEnd * (1 - 1e-14) - 1e-300) {
      if (cd_.time() <= t)
        load = f0;
      else
        load = f0 + std::min(1.0, (cd_.time() - t) / h) * (f1 - f0);
      // The strain energy (for the energy table, one row per window) is evaluated on the window's last step
      // only: the substeps are equal, so the last one is within 1.5 steps of the window's end.
      const bool monitor = cd_.lastDt() == 0 || windowEnd - cd_.time() <= 1.5 * cd_.lastDt();
      lastStepMonitored = monitor;
      if (!cd_.step(tEnd, monitor))
        throw StructureUnstable(structure::diagnoseInstability(scene_, cd_, checkpoint_.step,
                                                               checkpoint_.time,
                                                               /*nonFinite=*/true));
    }
  }

  /// Before a window of length dt: a stable step that collapsed (a crushed element, a blow-up on its way) is
  /// the structure's instability, reported as such rather than as billions of substeps.
  void checkStableStep(double dt) const {
    const double stable = stableTimeStep();
    if (stable > 0 && dt / stable <= 1e9) return;
    throw StructureUnstable(
        fmt::format("the stable step fell to {:g} s for a window of {:g} s; ", stable, dt) +
        structure::diagnoseInstability(scene_, cd_, checkpoint_.step, checkpoint_.time,
                                       /*nonFinite=*/!std::isfinite(stable)));
  }

  Eigen::VectorXd interfaceDisplacement() const override {
    const structure::Nodes& N = scene_.model->nodes;
    const std::vector<int>& nodes = scene_.couplingInterface->nodes;
    Eigen::VectorXd u(3 * Eigen::Index(nodes.size()));
    for (std::size_t i = 0; i < nodes.size(); ++i)
      for (int k = 0; k < 3; ++k) u[Eigen::Index(3 * i) + k] = N.x[3 * nodes[i] + k] - N.X[3 * nodes[i] + k];
    return u;
  }
  void saveCheckpoint() override { cd_.checkpoint(checkpoint_); }
  void restoreCheckpoint() override { cd_.restore(checkpoint_); }
  const structure::StateSnapshot& checkpointState() const { return checkpoint_; }

  double windowEnd = 0;            ///< end of the window being solved
  bool lastStepMonitored = false;  ///< the last structural step evaluated the strain energy

 private:
  const Scene& scene_;
  structure::CentralDifference& cd_;
  structure::InterfaceLoad& load_;
  structure::StateSnapshot checkpoint_;  ///< start of the window: the last stable state
};

// Equilibrium mode: the CentralDifference takes steps of its own stable size under the frozen window load,
// whatever the fluid's Δt; kinetic damping and the window's end are EquilibriumStructure's decisions.
class StructureParticipant::Relaxation final : public RelaxationStepper {
 public:
  Relaxation(const Scene& scene, structure::CentralDifference& cd, structure::InterfaceLoad& load,
             Substeps& substeps)
      : scene_(scene), cd_(cd), load_(load), substeps_(substeps) {}

  void freezeLoads(const Eigen::VectorXd& loads) override {
    load_.values.assign(loads.data(), loads.data() + loads.size());
  }
  double relaxStep() override {
    // A limit far ahead: the integrator takes its own stable step (it lands on a limit in equal steps; 1024
    // of them change the step by less than 0.1 %).
    const double limit = cd_.time() + 1024.0 * substeps_.stableTimeStep();
    substeps_.lastStepMonitored = false;  // recordHistory() evaluates the strain energy itself
    if (!cd_.step(limit, false))
      throw StructureUnstable(structure::diagnoseInstability(scene_, cd_, substeps_.checkpointState().step,
                                                             substeps_.checkpointState().time,
                                                             /*nonFinite=*/true));
    return cd_.energy().kinetic;
  }
  void stopMotion() override { cd_.stopMotion(); }
  void endWindow(double t, const Eigen::VectorXd& velocity) override {
    cd_.setTime(t);
    velocity_ = velocity;
  }
  Eigen::VectorXd interfaceDisplacement() const override { return substeps_.interfaceDisplacement(); }
  void saveCheckpoint() override { substeps_.saveCheckpoint(); }
  void restoreCheckpoint() override { substeps_.restoreCheckpoint(); }
  const Eigen::VectorXd& velocity() const { return velocity_; }

 private:
  const Scene& scene_;
  structure::CentralDifference& cd_;
  structure::InterfaceLoad& load_;
  Substeps& substeps_;
  Eigen::VectorXd velocity_;
};

StructureParticipant::StructureParticipant(Scene scene, const ParticipantOptions& options)
    : scene_(std::make_unique<Scene>(std::move(scene))), kind_(options.loadKind) {
  if (options.minSubcycles < 1)
    throw std::invalid_argument("StructureParticipant: subcycles = " + std::to_string(options.minSubcycles) +
                                ", valid: >= 1");
  if (!scene_->couplingInterface)
    throw InputError(scene_->file.string() +
                     ": a coupled structure needs `coupling: {interface: <triangles>}`");
  if (scene_->solver.type != structure::SolverControl::Type::ExplicitDynamics)
    throw InputError(scene_->file.string() +
                     ": a coupled structure runs explicit dynamics (no `solver` section)");
  const Scene::CouplingInterface& ci = *scene_->couplingInterface;
  load_ = std::make_unique<structure::InterfaceLoad>();
  load_->values.assign(ci.nodes.size(), 0.0);
  interface_ = std::make_unique<structure::InterfacePressure>(ci.triangles, ci.nodes, *load_);
  std::vector<const structure::Effect*> effects = scene_->effectList();
  effects.push_back(interface_.get());
  scene_->enabledEffects.push_back(interface_->name());
  cd_ = std::make_unique<structure::CentralDifference>(*scene_->model, std::move(effects),
                                                       scene_->constraints, scene_->time.integrator);
  mesh_ = sceneInterface(*scene_);  // reference coordinates, points in the order of the interface nodes
  loadStart_ = loadEnd_ = Eigen::VectorXd::Zero(
      Eigen::Index(structure::valuesPerInterface(kind_, std::size_t(numInterfaceNodes()))));
  stepper_ = std::make_unique<Substeps>(*scene_, *cd_, *load_);
  SubcyclingOptions sub;
  sub.interpolation = ci.loadInWindow;
  sub.safety = 1.0;  // Substeps::stableTimeStep() is the integrator's step, safety included
  sub.minSubsteps = options.minSubcycles;
  subcycled_ = std::make_unique<SubcycledStructure>(*stepper_, sub);
  if (options.mode == StructureMode::Equilibrium) {
    relaxation_ = std::make_unique<Relaxation>(*scene_, *cd_, *load_, *stepper_);
    // checks the step count
    equilibrium_ = std::make_unique<EquilibriumStructure>(*relaxation_, options.equilibrium);
  }
  cd_->evaluateForces(false);
  saveCheckpoint();
}

StructureParticipant::~StructureParticipant() = default;
StructureParticipant::StructureParticipant(StructureParticipant&&) noexcept = default;
StructureParticipant& StructureParticipant::operator=(StructureParticipant&&) noexcept = default;

int StructureParticipant::subcyclesFor(double dt) const {
  return subcycled_->substepsFor(dt);
}

void StructureParticipant::setWindowLoads(structure::InterfaceLoadKind kind, const double* start,
                                          const double* end, std::size_t size) {
  const std::size_t n = std::size_t(numInterfaceNodes()), expected = structure::valuesPerInterface(kind, n);
  if (size != expected)
    throw std::invalid_argument("StructureParticipant: " + std::to_string(size) + " load values for " +
                                structure::toString(kind) + " on " + std::to_string(n) +
                                " interface nodes; expected " + std::to_string(expected) +
                                (kind == structure::InterfaceLoadKind::Pressure
                                     ? " (nodal forces need ParticipantOptions::loadKind NodalForces)"
                                     : ""));
  kind_ = kind;
  loadStart_ = Eigen::Map<const Eigen::VectorXd>(start, Eigen::Index(size));
  loadEnd_ = Eigen::Map<const Eigen::VectorXd>(end, Eigen::Index(size));
}

void StructureParticipant::setPressure(const std::vector<double>& pStart, const std::vector<double>& pEnd) {
  if (pStart.size() != pEnd.size())
    throw std::invalid_argument(
        "StructureParticipant: pressures at the window's start and end differ in size");
  setWindowLoads(structure::InterfaceLoadKind::Pressure, pStart.data(), pEnd.data(), pStart.size());
}

void StructureParticipant::setForces(const std::vector<double>& fStart, const std::vector<double>& fEnd) {
  if (fStart.size() != fEnd.size())
    throw std::invalid_argument("StructureParticipant: forces at the window's start and end differ in size");
  setWindowLoads(structure::InterfaceLoadKind::NodalForces, fStart.data(), fEnd.data(), fStart.size());
}

EquilibriumReport StructureParticipant::equilibriumReport() const {
  return equilibrium_ ? equilibrium_->lastReport() : EquilibriumReport{};
}

double StructureParticipant::staticResidualRatio() {
  cd_->evaluateForces(false);
  const structure::Nodes& N = scene_->model->nodes;
  // f_int − f_ext with the tie forces of tie groups left out (a tied node's share of its group's).
  cd_->constraints().reactions(N, residual_);
  double res = 0, reaction = 0, applied = 0;
  for (std::size_t d = 0; d < N.x.size(); ++d) {
    const double R = -residual_[d];
    applied = std::max(applied, std::abs(N.fext[d]));
    // A constrained dof has no inverse mass (as for the dynamic relaxation's free-dof mask).
    if (N.invMassDof[d] != 0.0)
      res = std::max(res, std::abs(R));
    else
      reaction = std::max(reaction, std::abs(R));
  }
  const double scale = reaction > 0 ? reaction : (applied > 0 ? applied : 1.0);
  return res / scale;
}

void StructureParticipant::advance(double dt) {
  advanceTo(cd_->time() + dt);
}

void StructureParticipant::advanceTo(double t1) {
  const double t0 = cd_->time();
  stepper_->windowEnd = t1;
  // The effect reads values of the window's kind; resized only when the kind changes.
  load_->kind = kind_;
  load_->values.resize(std::size_t(loadStart_.size()));
  // The stable step of the window's start state decides the substep count, the same for every coupling
  // iteration of the window (it starts from the same checkpoint). The next step evaluates its forces anew.
  cd_->evaluateForces(false);
  if (equilibrium_) {
    // Time functions of the scene (ramps, prescribed motions) are evaluated from the window's end on: the
    // clock runs on through the pseudo-steps and is set back to t1 at the end.
    cd_->setTime(t1);
    equilibrium_->solve(t0, t1 - t0, loadStart_, loadEnd_);
    windowVelocity_ = relaxation_->velocity();
    return;
  }
  stepper_->checkStableStep(t1 - t0);
  subcycled_->solve(t0, t1 - t0, loadStart_, loadEnd_);
}

std::vector<double> StructureParticipant::interfaceDisplacement() const {
  const Eigen::VectorXd u = stepper_->interfaceDisplacement();
  return std::vector<double>(u.data(), u.data() + u.size());
}

std::vector<double> StructureParticipant::interfaceVelocity() const {
  if (equilibrium_ && windowVelocity_.size() > 0)
    return std::vector<double>(windowVelocity_.data(), windowVelocity_.data() + windowVelocity_.size());
  const structure::Nodes& N = scene_->model->nodes;
  const auto& nodes = interface_->nodes();
  std::vector<double> v(3 * nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (int k = 0; k < 3; ++k) v[3 * i + k] = N.v[3 * nodes[i] + k];
  return v;
}

std::array<double, 3> StructureParticipant::interfaceForce() const {
  structure::InterfaceLoad atEnd;
  atEnd.kind = kind_;
  const Eigen::VectorXd end =
      equilibrium_ ? loadEnd_  // the frozen load of the relaxation
                   : TimeInterpolation(subcycled_->options().interpolation, loadStart_, loadEnd_).at(1.0);
  atEnd.values.assign(end.data(), end.data() + end.size());
  std::vector<double> fe(3 * scene_->model->nodes.count, 0.0), fi(fe);
  structure::ForceContext ctx;
  ctx.time = cd_->time();
  ctx.x = scene_->model->nodes.x.data();
  ctx.v = scene_->model->nodes.v.data();
  ctx.fext = fe.data();
  ctx.fint = fi.data();
  interface_->addForces(ctx, atEnd);
  std::array<double, 3> F{0, 0, 0};
  for (std::size_t d = 0; d < fe.size(); ++d) F[d % 3] += fe[d];
  return F;
}

Eigen::VectorXd StructureParticipant::solve(double t, double dt, const Eigen::VectorXd& loadsStart,
                                            const Eigen::VectorXd& loadsEnd) {
  if (std::abs(t - time()) > 1e-9 * std::max(dt, 1e-300))
    throw std::logic_error("StructureParticipant::solve: window starts at " + std::to_string(t) +
                           " s but the structure is at " + std::to_string(time()) + " s");
  if (loadsStart.size() != loadsEnd.size())
    throw std::invalid_argument(
        "StructureParticipant::solve: loads at the window's start and end differ in size");
  setWindowLoads(kind_, loadsStart.data(), loadsEnd.data(), std::size_t(loadsStart.size()));
  advanceTo(t + dt);  // the window's end from the scheme's clock, not the structure's running sum
  return stepper_->interfaceDisplacement();
}

void StructureParticipant::saveCheckpoint() {
  stepper_->saveCheckpoint();
}
void StructureParticipant::restoreCheckpoint() {
  stepper_->restoreCheckpoint();
}

namespace {
const char* const kLedgerKey = "energy_ledger";
const std::vector<std::string> kEnergyColumns{
    "time", "kinetic", "strain", "external_work", "internal_work", "mass_damping", "balance_error", "dt"};
}  // namespace

void StructureParticipant::writeState(const std::filesystem::path& file,
                                      const std::map<std::string, std::vector<double>>& arrays) const {
  structure::StateSnapshot s;
  s.arrays = arrays;
  const structure::StateSnapshot c = cd_->checkpoint();
  const auto E = c.ledger.values();
  s.arrays[kLedgerKey] = std::vector<double>(E.begin(), E.end());
  s.time = cd_->time();
  s.step = cd_->steps();
  s.dt = cd_->lastDt();
  s.x = scene_->model->nodes.x;
  s.v = scene_->model->nodes.v;
  structure::writeState(file, s);
}

void StructureParticipant::alignTime(double t) {
  cd_->restore(scene_->model->nodes.x, scene_->model->nodes.v, t, cd_->lastDt(), cd_->steps());
}

std::map<std::string, std::vector<double>> StructureParticipant::readState(
    const std::filesystem::path& file) {
  const structure::StateSnapshot s = structure::readState(file);
  // A non-finite value would reach the projection and the fluid's mesh motion (a floating-point trap there):
  // refused here, naming the dataset and the entry.
  auto finite = [&](const std::vector<double>& values, const std::string& dataset) {
    for (std::size_t i = 0; i < values.size(); ++i)
      if (!std::isfinite(values[i]))
        throw InputError(file.string() + ": restart state: " + dataset + "[" + std::to_string(i) + "] is " +
                         std::to_string(values[i]) + " (not finite): the file is damaged");
  };
  finite({s.time}, "/@time");
  finite({s.dt}, "/@dt");
  finite(s.x, "/x");
  finite(s.v, "/v");
  for (const auto& [name, values] : s.arrays) finite(values, "/arrays/" + name);
  for (const auto& [name, value] : s.scalars) finite({value}, "/scalars/" + name);
  const std::size_t n = scene_->model->nodes.x.size();
  if (s.x.size() != n || s.v.size() != n)
    throw InputError(file.string() + ": restart state has " + std::to_string(s.x.size() / 3) +
                     " nodes but the scene " + scene_->file.string() + " has " + std::to_string(n / 3));
  cd_->restore(s.x, s.v, s.time, s.dt, s.step);
  std::map<std::string, std::vector<double>> arrays = s.arrays;
  const auto ledger = arrays.find(kLedgerKey);
  if (ledger != arrays.end()) {
    // Energies continue from the state's (a state file without them restarts the ledger at zero).
    const std::vector<double>& L = ledger->second;
    constexpr std::size_t nFields = structure::EnergyLedger::kFields;
    if (L.size() != nFields)
      throw InputError(file.string() + ": " + kLedgerKey + " has " + std::to_string(L.size()) +
                       " values, expected " + std::to_string(nFields) +
                       " (a state written by another version)");
    structure::StateSnapshot c = cd_->checkpoint();
    std::array<double, nFields> values{};
    std::copy(L.begin(), L.end(), values.begin());
    c.ledger.setValues(values);
    cd_->restore(c);
    arrays.erase(ledger);
  }
  cd_->evaluateForces(false);
  // Finite but absurd positions (an element stretched a hundred orders of magnitude, or collapsed) leave no
  // stable step: named here, not as a bare failure of the subcycling later.
  const double stable = cd_->stableDt();
  if (std::isfinite(stable) && !(stable > 0.0))
    throw InputError(file.string() +
                     ": restart state: the positions /x give the elements no stable time step " +
                     "(an element collapsed or stretched beyond reach): the file is damaged");
  for (double f : scene_->model->nodes.fint)
    if (!std::isfinite(f))
      throw InputError(file.string() + ": restart state: the positions /x give non-finite element forces " +
                       "(an element stretched beyond reach): the file is damaged");
  saveCheckpoint();
  return arrays;
}

void StructureParticipant::openResults(const std::filesystem::path& h5File, std::optional<double> keepUntil) {
  frames_ = std::make_unique<structure::SceneFrames>(*scene_->model, scene_->constraints,
                                                     scene_->output.fields, h5File, keepUntil);
  probeNames_.assign(1, "time");
  for (const auto& p : scene_->probes) probeNames_.push_back(p.name);
  energyRows_.assign(kEnergyColumns.size(), {});
  probeRows_.assign(probeNames_.size(), {});
  if (!keepUntil) return;
  // A restart continues the tables, without the rows later than the restart.
  auto restore = [&](const char* table, const std::vector<std::string>& columns,
                     std::vector<std::vector<double>>& rows) {
    auto [names, data] = frames_->writer().readTable(table);
    if (names.empty()) return;
    if (names != columns) {
      std::string had, has;
      for (const auto& n : names) had += " " + n;
      for (const auto& n : columns) has += " " + n;
      throw InputError(h5File.string() + ": table " + table + " has the columns" + had +
                       " but this run's are" + has +
                       " (the scene changed); move the file away to start a new series");
    }
    for (std::size_t k = 0; k < data.front().size(); ++k)
      if (data.front()[k] <= *keepUntil)
        for (std::size_t i = 0; i < rows.size(); ++i) rows[i].push_back(data[i][k]);
  };
  restore("energy", kEnergyColumns, energyRows_);
  restore("probes", probeNames_, probeRows_);
}

bool StructureParticipant::writeResults(double time) {
  if (!frames_) throw std::logic_error("StructureParticipant::writeResults before openResults");
  // One frame per time: e.g. the last stable state of a blow-up may be the frame written at that time.
  if (frames_->lastTime() >= time - 1e-12 * std::max(1.0, std::abs(time))) return false;
  frames_->write(time, cd_->steps());
  frames_->writer().writeTable("energy", kEnergyColumns, energyRows_);
  frames_->writer().writeTable("probes", probeNames_, probeRows_);
  return true;
}

void StructureParticipant::noteRestart(double time) {
  if (!frames_) throw std::logic_error("StructureParticipant::noteRestart before openResults");
  std::vector<double> times;
  for (const double t : frames_->writer().rootAttribute("restart_times"))
    if (t < time) times.push_back(t);
  times.push_back(time);
  frames_->writer().writeRootAttribute("restart_times", times);
}

std::map<std::string, double> StructureParticipant::recordHistory(double time) {
  if (!frames_) throw std::logic_error("StructureParticipant::recordHistory before openResults");
  if (!stepper_->lastStepMonitored)
    cd_->evaluateForces(true);  // rare: the window's last step had no strain energy
  const structure::EnergyLedger& E = cd_->energy();
  const double row[] = {time,           E.kinetic,     E.strain,         E.externalWork,
                        E.internalWork, E.massDamping, E.balanceError(), cd_->lastDt()};
  for (std::size_t i = 0; i < energyRows_.size(); ++i) energyRows_[i].push_back(row[i]);
  std::map<std::string, double> probes = structure::evaluateProbes(*scene_);
  probeRows_[0].push_back(time);
  for (std::size_t i = 1; i < probeNames_.size(); ++i) probeRows_[i].push_back(probes.at(probeNames_[i]));
  return probes;
}

int StructureParticipant::framesWritten() const {
  return frames_ ? frames_->writer().stepsWritten() : 0;
}

}  // namespace fsi::coupling
