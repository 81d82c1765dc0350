#include "coupling/StructureParticipant.hpp"

#include <cmath>

#include "coupling/interface/SceneInterface.hpp"
#include "structure/io/StateFile.hpp"
#include "structure/model/Error.hpp"
#include "structure/run/InstabilityDiagnosis.hpp"

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

void StructureParticipant::advance(double dt) {
  const double t0 = cd_->time(), t1 = t0 + dt;
  if (forces_)
    scene_.interfacePressure->setForceWindow(t0, t1, loadStart_, loadEnd_, scene_.interfaceLoadRule);
  else
    scene_.interfacePressure->setWindow(t0, t1, loadStart_, loadEnd_, scene_.interfaceLoadRule);
  const double scenarioMaxDt = scene_.time.integrator.maxDt;
  cd_->setMaxDt(minSubcycles_ > 1 ? std::min(scenarioMaxDt, dt / minSubcycles_ * (1 + 1e-12))
                                  : scenarioMaxDt);
  while (cd_->time() < t1 * (1 - 1e-14) - 1e-300) {
    if (!cd_->step(t1, false))
      throw StructureUnstable(structure::diagnoseInstability(scene_, *cd_, checkpoint_.steps,
                                                             checkpoint_.time,
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
  advance(dt);
  const std::vector<double> u = interfaceDisplacement();
  return Eigen::Map<const Eigen::VectorXd>(u.data(), Eigen::Index(u.size()));
}

void StructureParticipant::saveCheckpoint() {
  checkpoint_ = cd_->checkpoint();
}
void StructureParticipant::restoreCheckpoint() {
  cd_->restore(checkpoint_);
}

void StructureParticipant::writeState(const std::filesystem::path& file,
                                      const std::map<std::string, std::vector<double>>& arrays) const {
  structure::StateSnapshot s;
  s.arrays = arrays;
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
  cd_->evaluateForces(false);
  saveCheckpoint();
  return s.arrays;
}

void StructureParticipant::openResults(const std::filesystem::path& h5File) {
  frames_ = std::make_unique<structure::SceneFrames>(scene_, h5File);
}

void StructureParticipant::writeResults() {
  if (!frames_) throw std::logic_error("StructureParticipant::writeResults before openResults");
  frames_->write(cd_->time(), cd_->steps());
}

}  // namespace fsi::coupling
