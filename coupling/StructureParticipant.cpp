#include "coupling/StructureParticipant.hpp"

#include <cmath>
#include <unordered_map>

#include "structure/model/Error.hpp"

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
  // Interface mesh: the pressure effect's nodes and triangles, in reference coordinates.
  const structure::Nodes& N = scene_.model->nodes;
  const auto& nodes = scene_.interfacePressure->nodes();
  std::unordered_map<int, int> local;
  mesh_.name = "structure";
  for (std::size_t i = 0; i < nodes.size(); ++i) {
    local[nodes[i]] = int(i);
    mesh_.points.push_back({N.X[3 * nodes[i]], N.X[3 * nodes[i] + 1], N.X[3 * nodes[i] + 2]});
  }
  const auto& tris = scene_.interfacePressure->triangles();
  for (std::size_t e = 0; e + 2 < tris.size(); e += 3)
    mesh_.addFace({local.at(tris[e]), local.at(tris[e + 1]), local.at(tris[e + 2])});
  pStart_.assign(nodes.size(), 0.0);
  pEnd_.assign(nodes.size(), 0.0);
  cd_->evaluateForces(false);
  saveCheckpoint();
}

int StructureParticipant::subcyclesFor(double dt) const {
  const double stable = scene_.time.integrator.fixedDt > 0 ? scene_.time.integrator.fixedDt
                                                           : scene_.time.integrator.safety * cd_->stableDt();
  return std::max(1, int(std::ceil(dt / stable - 1e-9)));
}

void StructureParticipant::setPressure(const std::vector<double>& pStart, const std::vector<double>& pEnd) {
  pStart_ = pStart;
  pEnd_ = pEnd;
  // Effective now (interfaceForce reflects it); advance() re-times the window.
  scene_.interfacePressure->setWindow(time(), time(), pStart_, pEnd_, scene_.interfaceLoadRule);
}

void StructureParticipant::advance(double dt) {
  const double t0 = cd_->time(), t1 = t0 + dt;
  scene_.interfacePressure->setWindow(t0, t1, pStart_, pEnd_, scene_.interfaceLoadRule);
  while (cd_->time() < t1 * (1 - 1e-14) - 1e-300) {
    if (!cd_->step(t1, false))
      throw std::runtime_error("structure became unstable at t = " + std::to_string(cd_->time()) + " s");
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
  setPressure(std::vector<double>(loadsStart.data(), loadsStart.data() + loadsStart.size()),
              std::vector<double>(loadsEnd.data(), loadsEnd.data() + loadsEnd.size()));
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

}  // namespace fsi::coupling
