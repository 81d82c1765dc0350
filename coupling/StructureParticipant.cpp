#include "coupling/StructureParticipant.hpp"

#include <array>
#include <cmath>

#include "coupling/interface/SceneInterface.hpp"
#include "structure/io/StateFile.hpp"
#include "structure/model/Error.hpp"
#include "structure/run/InstabilityDiagnosis.hpp"
#include "structure/run/Simulation.hpp"

namespace fsi::coupling {

using structure::Scene;

StructureParticipant::StructureParticipant(const std::filesystem::path& sceneFile,
                                           const std::vector<std::string>& overrides)
    : StructureParticipant(structure::loadScene(sceneFile, overrides)) {}

StructureParticipant::StructureParticipant(Scene scene) : scene_(std::move(scene)) {
  if (!scene_.interfacePressure)
    throw InputError(scene_.file.string() +
                     ": a coupled structure needs `coupling: {interface: <triangles>}`");
  if (scene_.solver.type != structure::SolverControl::Type::ExplicitDynamics)
    throw InputError(scene_.file.string() +
                     ": a coupled structure runs explicit dynamics (no `solver` section)");
  cd_ = std::make_unique<structure::CentralDifference>(*scene_.model, scene_.effectList(), scene_.constraints,
                                                       scene_.time.integrator);
  mesh_ =
      sceneInterface(scene_);  // reference coordinates, points in the order of the pressure effect's nodes
  const auto& nodes = scene_.interfacePressure->nodes();
  loadStart_.assign(nodes.size(), 0.0);
  loadEnd_.assign(nodes.size(), 0.0);
  cd_->evaluateForces(false);
  saveCheckpoint();
}

int StructureParticipant::subcyclesFor(double dt) const {
  const double stable = scene_.time.integrator.fixedDt > 0 ? scene_.time.integrator.fixedDt
                                                           : scene_.time.integrator.safety * cd_->stableDt();
  return std::max({1, minSubcycles_, int(std::ceil(dt / stable - 1e-9))});
}

void StructureParticipant::setPressure(const std::vector<double>& pStart, const std::vector<double>& pEnd) {
  // Effective now (interfaceForce reflects it); advance() re-times the window.
  scene_.interfacePressure->setWindow(time(), time(), pStart, pEnd, scene_.interfaceLoadRule);
  loadStart_ = pStart;
  loadEnd_ = pEnd;
  forces_ = false;
}

void StructureParticipant::setForces(const std::vector<double>& fStart, const std::vector<double>& fEnd) {
  scene_.interfacePressure->setForceWindow(time(), time(), fStart, fEnd, scene_.interfaceLoadRule);
  loadStart_ = fStart;
  loadEnd_ = fEnd;
  forces_ = true;
}

void StructureParticipant::setMinSubcycles(int n) {
  if (n < 1)
    throw std::invalid_argument("StructureParticipant: subcycles = " + std::to_string(n) + ", valid: >= 1");
  minSubcycles_ = n;
}

void StructureParticipant::advance(double dt) {
  advanceTo(cd_->time() + dt);
}

void StructureParticipant::advanceTo(double t1) {
  const double t0 = cd_->time(), dt = t1 - t0;
  if (forces_)
    scene_.interfacePressure->setForceWindow(t0, t1, loadStart_, loadEnd_, scene_.interfaceLoadRule);
  else
    scene_.interfacePressure->setWindow(t0, t1, loadStart_, loadEnd_, scene_.interfaceLoadRule);
  const double scenarioMaxDt = scene_.time.integrator.maxDt;
  cd_->setMaxDt(minSubcycles_ > 1 ? std::min(scenarioMaxDt, dt / minSubcycles_ * (1 + 1e-12))
                                  : scenarioMaxDt);
  while (cd_->time() < t1 * (1 - 1e-14) - 1e-300) {
    // The strain energy (for the energy table, one row per window) is evaluated on the window's last step
    // only: the integrator lands on t1 in equal steps, so the last one is within 1.5 steps of the end.
    const bool monitor = cd_->lastDt() == 0 || t1 - cd_->time() <= 1.5 * cd_->lastDt();
    lastStepMonitored_ = monitor;
    if (!cd_->step(t1, monitor))
      throw StructureUnstable(structure::diagnoseInstability(scene_, *cd_, checkpoint_.step, checkpoint_.time,
                                                             /*nonFinite=*/true));
  }
}

std::vector<double> StructureParticipant::interfaceDisplacement() const {
  const structure::Nodes& N = scene_.model->nodes;
  const auto& nodes = scene_.interfacePressure->nodes();
  std::vector<double> u(3 * nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (int k = 0; k < 3; ++k) u[3 * i + k] = N.x[3 * nodes[i] + k] - N.X[3 * nodes[i] + k];
  return u;
}

std::vector<double> StructureParticipant::interfaceVelocity() const {
  const structure::Nodes& N = scene_.model->nodes;
  const auto& nodes = scene_.interfacePressure->nodes();
  std::vector<double> v(3 * nodes.size());
  for (std::size_t i = 0; i < nodes.size(); ++i)
    for (int k = 0; k < 3; ++k) v[3 * i + k] = N.v[3 * nodes[i] + k];
  return v;
}

std::array<double, 3> StructureParticipant::interfaceForce() const {
  std::vector<double> fe(3 * scene_.model->nodes.count, 0.0), fi(fe);
  structure::ForceContext ctx;
  ctx.time = cd_->time();
  ctx.x = scene_.model->nodes.x.data();
  ctx.v = scene_.model->nodes.v.data();
  ctx.fext = fe.data();
  ctx.fint = fi.data();
  scene_.interfacePressure->addForces(ctx);
  std::array<double, 3> F{0, 0, 0};
  for (std::size_t d = 0; d < fe.size(); ++d) F[d % 3] += fe[d];
  return F;
}

Eigen::VectorXd StructureParticipant::solve(double t, double dt, const Eigen::VectorXd& loadsStart,
                                            const Eigen::VectorXd& loadsEnd) {
  if (std::abs(t - time()) > 1e-9 * std::max(dt, 1e-300))
    throw std::logic_error("StructureParticipant::solve: window starts at " + std::to_string(t) +
                           " s but the structure is at " + std::to_string(time()) + " s");
  const std::vector<double> a(loadsStart.data(), loadsStart.data() + loadsStart.size());
  const std::vector<double> b(loadsEnd.data(), loadsEnd.data() + loadsEnd.size());
  if (a.size() == 3 * std::size_t(numInterfaceNodes()) && numInterfaceNodes() > 0)
    setForces(a, b);
  else
    setPressure(a, b);
  advanceTo(t + dt);  // the window's end from the scheme's clock, not the structure's running sum
  const std::vector<double> u = interfaceDisplacement();
  return Eigen::Map<const Eigen::VectorXd>(u.data(), Eigen::Index(u.size()));
}

void StructureParticipant::saveCheckpoint() {
  checkpoint_ = cd_->checkpoint();
}
void StructureParticipant::restoreCheckpoint() {
  cd_->restore(checkpoint_);
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
  s.x = scene_.model->nodes.x;
  s.v = scene_.model->nodes.v;
  structure::writeState(file, s);
}

std::map<std::string, std::vector<double>> StructureParticipant::readState(
    const std::filesystem::path& file) {
  const structure::StateSnapshot s = structure::readState(file);
  const std::size_t n = scene_.model->nodes.x.size();
  if (s.x.size() != n || s.v.size() != n)
    throw InputError(file.string() + ": restart state has " + std::to_string(s.x.size() / 3) +
                     " nodes but the scene " + scene_.file.string() + " has " + std::to_string(n / 3));
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
  saveCheckpoint();
  return arrays;
}

void StructureParticipant::openResults(const std::filesystem::path& h5File, std::optional<double> keepUntil) {
  frames_ = std::make_unique<structure::SceneFrames>(scene_, h5File, keepUntil);
  probeNames_.assign(1, "time");
  for (const auto& p : scene_.probes) probeNames_.push_back(p.name);
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
  if (!lastStepMonitored_) cd_->evaluateForces(true);  // rare: the window's last step had no strain energy
  const structure::EnergyLedger& E = cd_->energy();
  const double row[] = {time,           E.kinetic,     E.strain,         E.externalWork,
                        E.internalWork, E.massDamping, E.balanceError(), cd_->lastDt()};
  for (std::size_t i = 0; i < energyRows_.size(); ++i) energyRows_[i].push_back(row[i]);
  std::map<std::string, double> probes = structure::evaluateProbes(scene_);
  probeRows_[0].push_back(time);
  for (std::size_t i = 1; i < probeNames_.size(); ++i) probeRows_[i].push_back(probes.at(probeNames_[i]));
  return probes;
}

int StructureParticipant::framesWritten() const {
  return frames_ ? frames_->writer().stepsWritten() : 0;
}

}  // namespace fsi::coupling
