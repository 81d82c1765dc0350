#include <Eigen/Core>
#include <cmath>

#include "OSspecific.H"
#include "Time.H"
#include "coupling/StructureParticipant.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "fsiRestartState.H"
#include "structure/model/Error.hpp"

namespace Foam {

fileName fsiRestartState::file(const fileName& timePath) {
  return timePath / "uniform" / "fsiStructure.h5";
}

bool fsiRestartState::read(fsi::coupling::StructureParticipant& structure, const Time& time,
                           const dictionary& dict, bool interfaceReferenceRestart, bool undeformedStart,
                           bool fresh) {
  const scalar dt = time.deltaTValue();
  // Restart: the structure continues from the state written with this time directory.
  const fileName state = file(time.timePath());
  if (!isFile(state)) {
    if (interfaceReferenceRestart)
      FatalIOErrorInFunction(dict) << "fsiCoupling: interfaceReference restart needs a restart state, "
                                   << state << ", and there is none (a run from t = 0 uses design)"
                                   << exit(FatalIOError);
    // A FatalIOError: while OpenFOAM loads function objects it turns a plain FatalError into a warning
    // and runs on without the coupling.
    if (!fresh)
      FatalIOErrorInFunction(dict)
          << "fsiCoupling: the run starts at t = " << time.value() << " s but there is no structure state "
          << state << " (a restart needs the state written with that time directory; a new run starts "
          << "at t = 0)" << exit(FatalIOError);
    return false;
  }
  file_ = state;
  arrays_ = structure.readState(std::string(state));
  // The time directory's name is rounded to timePrecision digits; the state file keeps the exact time.
  if (std::abs(structure.time() - time.value()) > 1e-3 * dt)
    FatalIOErrorInFunction(dict) << "fsiCoupling: structure state " << state
                                 << " is at t = " << structure.time() << " s, the fluid at " << time.value()
                                 << " s" << exit(FatalIOError);
  structure.alignTime(time.value());
  Info << "[fsi] structure restarted from " << time.timeName() << "/uniform/" << state.name() << endl;
  // interfaceReference restart: a mesh that starts undeformed was made around the canopy of this state;
  // a deformed one (a plain restart of the same mesh) keeps the reference its state file carries.
  const auto ref = arrays_.find("interface_reference");
  const bool newMesh = interfaceReferenceRestart && undeformedStart;
  const auto remeshRef = arrays_.find("remesh_reference");
  if (newMesh && remeshRef != arrays_.end()) {
    interfaceReference_ = remeshRef->second;  // the skin the new mesh was snapped to
  } else if (newMesh) {
    interfaceReference_ = structure.interfaceDisplacement();
  } else if (ref != arrays_.end()) {
    interfaceReference_ = ref->second;
  }
  if (!interfaceReference_.empty()) {
    if (interfaceReference_.size() != 3 * std::size_t(structure.numInterfaceNodes()))
      FatalIOErrorInFunction(dict) << "fsiCoupling: structure state " << state << ": interface_reference has "
                                   << label(interfaceReference_.size()) << " values for "
                                   << structure.numInterfaceNodes() << " interface nodes"
                                   << exit(FatalIOError);
    Info << "[fsi] the fluid mesh is undeformed at the canopy's state of t = "
         << (newMesh ? time.timeName() : word("an earlier restart"))
         << " (interfaceReference restart): the projection is set up on that shape" << endl;
  }
  return true;
}

void fsiRestartState::restoreScheme(fsi::coupling::CouplingScheme& scheme, int interfaceNodes,
                                    bool implicit) const {
  if (file_.empty()) return;
  // Values are finite (StructureParticipant::readState checks every array); here: presence and sizes. Thrown
  // as InputError: the set-up's handler stops the run with it (a FatalIOError, which OpenFOAM does not turn
  // into a warning while it loads function objects).
  const std::string where = "structure state " + std::string(file_) + ": the dataset /arrays/";
  const std::size_t n = 3 * std::size_t(interfaceNodes);
  auto array = [&](const std::string& name, std::size_t size) -> const std::vector<double>& {
    const auto it = arrays_.find(name);
    if (it == arrays_.end())
      throw fsi::InputError(
          where + name +
          " is missing (a restart state holds it; the file is damaged or was not written by "
          "a coupled run)");
    if (size > 0 && it->second.size() != size)
      throw fsi::InputError(where + name + " has " + std::to_string(it->second.size()) +
                            " values, expected " + std::to_string(size) + " (3 per interface node)");
    return it->second;
  };
  const std::vector<double>& count = array("interface_history_count", 1);
  if (!(count[0] >= 1 && count[0] <= 3 && count[0] == std::floor(count[0])))
    throw fsi::InputError(where + "interface_history_count is " + std::to_string(count[0]) +
                          ", expected 1, 2 or 3");
  std::vector<Eigen::VectorXd> history;
  for (int k = 0; k < int(count[0]); ++k) {
    const std::vector<double>& h = array("interface_history_" + std::to_string(k), n);
    history.emplace_back(Eigen::Map<const Eigen::VectorXd>(h.data(), Eigen::Index(h.size())));
  }
  scheme.restoreHistory(history);
  // The load the structure got last: with loadRelaxation < 1 the next one is relaxed towards it.
  const std::vector<double>& applied = array("applied_loads", n);
  scheme.restoreLoadsAtWindowStart(
      Eigen::Map<const Eigen::VectorXd>(applied.data(), Eigen::Index(applied.size())));
  // The acceleration's carried state (IQN-ILS' reused columns, Aitken's factor): the restarted run iterates
  // like the uninterrupted one. A state written by a staggered run (or one whose acceleration carries
  // nothing) has none: the acceleration starts afresh, as at t = 0.
  fsi::coupling::Acceleration::State acc;
  const std::string prefix = "acceleration_";
  for (const auto& [key, values] : arrays_)
    if (key.compare(0, prefix.size(), prefix) == 0) acc[key.substr(prefix.size())] = values;
  if (!implicit) return;
  if (acc.empty()) {
    if (!scheme.accelerationState().empty())
      Info << "[fsi] the state " << file_
           << " carries no acceleration history (written by a staggered run or "
           << "another acceleration): the acceleration starts afresh" << endl;
    return;
  }
  try {
    scheme.restoreAccelerationState(acc);
  } catch (const std::exception& e) {
    throw fsi::InputError(where + "acceleration_*: " + e.what() +
                          " (written by another acceleration? `acceleration` must be the one the state was "
                          "written with)");
  }
}

void fsiRestartState::write(const fileName& file, const fsi::coupling::StructureParticipant& structure,
                            const fsi::coupling::CouplingScheme& scheme,
                            const std::vector<double>& interfaceReference,
                            const std::vector<double>* remeshReference) {
  mkDir(file.path());
  std::map<std::string, std::vector<double>> arrays;
  const auto& h = scheme.history();
  for (std::size_t k = 0; k < h.size(); ++k)
    arrays["interface_history_" + std::to_string(k)] =
        std::vector<double>(h[k].data(), h[k].data() + h[k].size());
  arrays["interface_history_count"] = {double(h.size())};
  for (const auto& [key, values] : scheme.accelerationState()) arrays["acceleration_" + key] = values;
  const Eigen::VectorXd& applied = scheme.loadsAtWindowStart();
  arrays["applied_loads"] = std::vector<double>(applied.data(), applied.data() + applied.size());
  if (!interfaceReference.empty()) arrays["interface_reference"] = interfaceReference;
  if (remeshReference) arrays["remesh_reference"] = *remeshReference;
  structure.writeState(std::string(file), arrays);
}

}  // namespace Foam
