#include <Eigen/Core>
#include <cmath>
#include <map>

#include "OFstream.H"
#include "addToRunTimeSelectionTable.H"
#include "coupling/StructureParticipant.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "fsiCouplingFunctionObject.H"
#include "fsiFloatingPointTraps.H"
#include "fsiInterfaceDisplacementPointPatchVectorField.H"
#include "fvcGrad.H"
#include "movingWallVelocityFvPatchVectorField.H"
#include "structure/run/Simulation.hpp"
#include "surfaceFields.H"
#include "turbulenceModel.H"
#include "volFields.H"

namespace Foam {
namespace functionObjects {

defineTypeNameAndDebug(fsiCoupling, 0);
addToRunTimeSelectionTable(functionObject, fsiCoupling, dictionary);

namespace {

using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

fsi::coupling::MassMatrix projectionKind(const dictionary& dict) {
  const word kind = dict.lookupOrDefault<word>("projection", "consistent");
  if (kind == "consistent") return fsi::coupling::MassMatrix::Consistent;
  if (kind == "lumped") return fsi::coupling::MassMatrix::Lumped;
  if (kind == "dual") return fsi::coupling::MassMatrix::Dual;
  FatalIOErrorInFunction(dict) << "fsiCoupling: projection " << kind
                               << " unknown; valid: consistent lumped dual" << exit(FatalIOError);
  return fsi::coupling::MassMatrix::Consistent;
}

fsi::coupling::AccelerationConfig accelerationConfig(const dictionary& dict) {
  fsi::coupling::AccelerationConfig a;
  const word kind = dict.lookupOrDefault<word>("acceleration", "IQN-ILS");
  if (kind == "constant")
    a.kind = fsi::coupling::AccelerationKind::Constant;
  else if (kind == "aitken")
    a.kind = fsi::coupling::AccelerationKind::Aitken;
  else if (kind == "IQN-ILS")
    a.kind = fsi::coupling::AccelerationKind::IqnIls;
  else
    FatalIOErrorInFunction(dict) << "fsiCoupling: acceleration " << kind
                                 << " unknown; valid: constant aitken IQN-ILS" << exit(FatalIOError);
  a.omega = dict.lookupOrDefault<scalar>("omega", 0.5);
  a.aitken.initialOmega = a.omega;
  a.iqn.initialOmega = dict.lookupOrDefault<scalar>("omega", 0.1);
  a.iqn.reuseSteps = dict.lookupOrDefault<label>("reuse", 0);
  return a;
}

}  // namespace

fsiCoupling::fsiCoupling(const word& name, const Time& runTime, const dictionary& dict)
    : fvMeshFunctionObject(name, runTime, dict), wallStart_(Clock::now()) {
  read(dict);
}

fsiCoupling::~fsiCoupling() = default;

bool fsiCoupling::read(const dictionary& dict) {
  fvMeshFunctionObject::read(dict);
  patches_ = wordList(dict.lookup("patches"));
  rho_ = dict.get<scalar>("rho");
  pRef_ = dict.lookupOrDefault<scalar>("pRef", 0.0);
  viscous_ = dict.lookupOrDefault<Switch>("viscous", false);
  patchIDs_.setSize(patches_.size());
  forAll(patches_, i) {
    patchIDs_[i] = mesh_.boundaryMesh().findPatchID(patches_[i]);
    if (patchIDs_[i] < 0)
      FatalIOErrorInFunction(dict) << "fsiCoupling: no patch named " << patches_[i]
                                   << "; the mesh has the patches " << mesh_.boundaryMesh().names()
                                   << exit(FatalIOError);
  }
  if (mesh_.foundObject<volScalarField>("p_rgh"))
    FatalIOErrorInFunction(dict)
        << "fsiCoupling: this solver uses p_rgh (buoyancy); the interface load needs "
        << "the static pressure p of an incompressible solver such as pimpleFoam" << exit(FatalIOError);
  if (!mesh_.foundObject<volScalarField>("p"))
    FatalIOErrorInFunction(dict) << "fsiCoupling: no pressure field p" << exit(FatalIOError);
  if (dict.found("scene") && !structure_ && !scheme_ && interfaces_.empty()) startCoupling(dict);
  return true;
}

tmp<vectorField> fsiCoupling::faceForces(label i, bool withViscous) const {
  const label id = patchIDs_[i];
  const volScalarField& p = mesh_.lookupObject<volScalarField>("p");
  // Incompressible solvers carry kinematic pressure [m²/s²]: scale by rho like the `forces` function object.
  const bool kinematic = p.dimensions() == dimPressure / dimDensity;
  const scalar rho = kinematic ? rho_ : 1.0;
  const vectorField& Sf = mesh_.Sf().boundaryField()[id];
  tmp<vectorField> tf(new vectorField(rho * (p.boundaryField()[id] - pRef_ / rho) * Sf));
  if (withViscous) {
    // Viscous traction as `forces` computes it: Sf & devRhoReff with devReff = -nuEff dev(twoSymm(grad U)).
    const auto& turbulence = mesh_.lookupObject<turbulenceModel>(turbulenceModel::propertiesName);
    const volVectorField& U = mesh_.lookupObject<volVectorField>("U");
    const tmp<volTensorField> gradU = fvc::grad(U);
    const tmp<volScalarField> nuEff = turbulence.nuEff();
    const symmTensorField devReff(-nuEff().boundaryField()[id] * dev(twoSymm(gradU().boundaryField()[id])));
    tf.ref() += rho * (Sf & devReff);
  }
  return tf;
}

vector fsiCoupling::pressureForce() const {
  return interfaceForce(false);
}

vector fsiCoupling::interfaceForce(bool withViscous) const {
  vector F = Zero;
  forAll(patchIDs_, i) F += sum(faceForces(i, withViscous)());
  reduce(F, sumOp<vector>());
  return F;
}

void fsiCoupling::checkSetUp(const dictionary& dict) const {
  if (time_.controlDict().lookupOrDefault<Switch>("adjustTimeStep", false))
    FatalIOErrorInFunction(dict)
        << "fsiCoupling: `adjustTimeStep yes` in controlDict: coupling windows have a "
        << "fixed size; set deltaT and adjustTimeStep no" << exit(FatalIOError);
  if (viscous_ && !mesh_.foundObject<turbulenceModel>(turbulenceModel::propertiesName))
    FatalIOErrorInFunction(dict)
        << "fsiCoupling: `viscous yes` needs the solver's turbulence (or laminar) model"
        << exit(FatalIOError);
  if (!mesh_.foundObject<pointVectorField>("pointDisplacement"))
    FatalIOErrorInFunction(dict)
        << "fsiCoupling: the mesh does not move (no pointDisplacement field): constant/dynamicMeshDict needs "
        << "dynamicFvMesh dynamicMotionSolverFvMesh with a displacement motion solver (e.g. "
        << "displacementLaplacian)" << exit(FatalIOError);
  const auto& pd = mesh_.lookupObject<pointVectorField>("pointDisplacement");
  const auto& U = mesh_.lookupObject<volVectorField>("U");
  forAll(patchIDs_, i) {
    const label id = patchIDs_[i];
    if (!isA<fsiInterfaceDisplacementPointPatchVectorField>(pd.boundaryField()[id]))
      FatalIOErrorInFunction(dict) << "fsiCoupling: pointDisplacement on patch " << patches_[i]
                                   << " is of type " << pd.boundaryField()[id].type()
                                   << "; the coupling sets it: use type fsiInterfaceDisplacement in "
                                   << "0/pointDisplacement" << exit(FatalIOError);
    if (!isA<movingWallVelocityFvPatchVectorField>(U.boundaryField()[id]))
      FatalIOErrorInFunction(dict) << "fsiCoupling: U on patch " << patches_[i] << " is of type "
                                   << U.boundaryField()[id].type()
                                   << "; a moving interface needs movingWallVelocity" << exit(FatalIOError);
  }
}

void fsiCoupling::startCoupling(const dictionary& dict) {
  checkSetUp(dict);
  scene_ = dict.get<fileName>("scene").expand();
  if (!scene_.isAbsolute()) scene_ = time_.globalPath() / scene_;
  const word scheme = dict.lookupOrDefault<word>("scheme", "staggered");
  implicit_ = scheme == "implicit";
  if (scheme != "staggered" && scheme != "implicit")
    FatalIOErrorInFunction(dict) << "fsiCoupling: scheme " << scheme << " unknown; valid: staggered implicit"
                                 << exit(FatalIOError);
  verifyCheckpoint_ = dict.lookupOrDefault<Switch>("verifyCheckpoint", false);
  const label subcycles = dict.lookupOrDefault<label>("subcycles", 1);
  const scalar dt = time_.deltaTValue();
  const scalar endTime = time_.endTime().value();
  const auto& pd = mesh_.lookupObject<pointVectorField>("pointDisplacement");
  for (const label id : patchIDs_) interfaces_.emplace_back(new fsiInterfacePatch(mesh_, id, pd));
  checkpoint_.reset(new fsiFluidCheckpoint(
      mesh_, verifyCheckpoint_ || dict.lookupOrDefault<Switch>("restoreMeshPoints", true)));

  const fileName outDir = time_.globalPath() / "structure";
  std::map<std::string, std::vector<double>> restartArrays;
  if (Pstream::master()) {
    const fsiFloatingPointTrapsOff noTraps;
    try {
      structure_ = std::make_unique<fsi::coupling::StructureParticipant>(std::string(scene_));
    } catch (const std::exception& e) {
      FatalIOErrorInFunction(dict) << "fsiCoupling: structure scene " << scene_ << ": " << e.what()
                                   << exit(FatalIOError);
    }
    structure_->setMinSubcycles(subcycles);
    // Projection structure -> each fluid patch, on the reference geometry.
    fsi::coupling::ProjectionOptions opt;
    opt.mass = projectionKind(dict);
    opt.tolerance =
        dict.lookupOrDefault<scalar>("mapTolerance", 0.25 * structure_->interfaceMesh().meanEdgeLength());
    for (const auto& ip : interfaces_) {
      maps_.emplace_back(
          new fsi::coupling::L2Projection(structure_->interfaceMesh(), ip->referenceMesh(), opt));
      const auto& r = maps_.back()->report();
      Info << "fsiCoupling: patch " << ip->name() << ": " << r.targetNodes << " fluid points <- "
           << r.sourceNodes << " structure nodes, " << fsi::coupling::toString(opt.mass)
           << " L2 projection, largest gap " << r.maxGap << " m, set up in " << r.setupSeconds << " s"
           << endl;
      if (!r.allMapped()) {
        FatalIOErrorInFunction(dict) << "fsiCoupling: " << r.unmappedTargetNodes << " points of patch "
                                     << ip->name() << " are farther than mapTolerance " << opt.tolerance
                                     << " m from the structure's interface (" << scene_ << ")";
        for (const auto& u : r.firstUnmappedPoints)
          FatalIOError << nl << "    (" << u.x[0] << ' ' << u.x[1] << ' ' << u.x[2] << ") at distance "
                       << u.distance;
        FatalIOError << nl << "Check that the patch and the structure's interface are the same surface, or "
                     << "raise mapTolerance." << exit(FatalIOError);
      }
    }
    // Restart: the structure continues from the state written with this time directory.
    const fileName state = stateFile(time_.timePath());
    if (isFile(state)) {
      try {
        restartArrays = structure_->readState(std::string(state));
      } catch (const std::exception& e) {
        FatalErrorInFunction << "fsiCoupling: " << e.what() << exit(FatalError);
      }
      if (std::abs(structure_->time() - time_.value()) > 1e-9 * max(dt, 1.0))
        FatalErrorInFunction << "fsiCoupling: structure state " << state
                             << " is at t = " << structure_->time() << " s, the fluid at " << time_.value()
                             << " s" << exit(FatalError);
      Info << "fsiCoupling: structure restarted from " << state << endl;
    } else if (time_.value() > 0.5 * dt) {
      FatalErrorInFunction
          << "fsiCoupling: the run starts at t = " << time_.value() << " s but there is no structure state "
          << state << " (a restart needs the state written with that time directory; a new run starts "
          << "at t = 0)" << exit(FatalError);
    }

    fsi::coupling::CouplingConfig cfg;
    cfg.kind = implicit_ ? fsi::coupling::SchemeKind::Implicit : fsi::coupling::SchemeKind::Staggered;
    cfg.timeWindowSize = dt;
    cfg.endTime = endTime;
    cfg.extrapolationOrder = dict.lookupOrDefault<label>("extrapolation", 1);
    cfg.relativeTolerance = dict.lookupOrDefault<scalar>("tolerance", 1e-5);
    cfg.maxIterations = dict.lookupOrDefault<label>("maxIterations", 30);
    scheme_ = std::make_unique<fsi::coupling::CouplingScheme>(
        cfg, *structure_, implicit_ ? fsi::coupling::makeAcceleration(accelerationConfig(dict)) : nullptr);
    mkDir(outDir);
    const bool fresh = time_.value() <= 0.5 * dt;
    structure_->openResults(
        std::string(outDir / (fresh ? word("results.h5") : "results_from_" + time_.timeName() + ".h5")));
    log_.reset(
        new OFstream(outDir / (fresh ? word("coupling.csv") : "coupling_from_" + time_.timeName() + ".csv")));
    *log_ << "time,iterations,converged,residual,Fx_fluid,Fy_fluid,Fz_fluid,Fx_structure,Fy_structure,Fz_"
             "structure";
    for (const auto& [name, value] : fsi::structure::evaluateProbes(structure_->scene()))
      *log_ << ',' << name.c_str();
    *log_ << endl;
    log_->precision(12);
    Info << "fsiCoupling: structure " << scene_ << ", " << structure_->numInterfaceNodes()
         << " interface nodes; " << scheme << " coupling, window " << dt << " s, "
         << structure_->subcyclesFor(dt) << " structural steps per window" << endl;
  }

  // Loads at t0 and the first interface displacement (the first step has no execute() before it moves).
  vector fluidTotal;
  const std::vector<double> loads = structureLoads(fluidTotal);
  if (Pstream::master()) {
    const std::vector<double> d0 = structure_->interfaceDisplacement();
    scheme_->initialize(time_.value(), Eigen::Map<const Eigen::VectorXd>(d0.data(), Eigen::Index(d0.size())),
                        Eigen::Map<const Eigen::VectorXd>(loads.data(), Eigen::Index(loads.size())));
  }
  if (Pstream::master()) {
    std::vector<Eigen::VectorXd> history;
    for (int k = 0; k < 3; ++k) {
      const auto it = restartArrays.find("interface_history_" + std::to_string(k));
      if (it != restartArrays.end())
        history.emplace_back(
            Eigen::Map<const Eigen::VectorXd>(it->second.data(), Eigen::Index(it->second.size())));
    }
    scheme_->restoreHistory(history);
  }
  if (implicit_ || verifyCheckpoint_) checkpoint_->save();
  if (implicit_) {
    Info << "fsiCoupling: the fluid checkpoint holds " << checkpoint_->fieldNames() << endl;
    // The last window must be repeatable: Time::run() ends the loop at endTime before a restored step could
    // run again, so the solver gets one spare step and the object stops the run when the last window is
    // accepted.
    const_cast<Time&>(time_).setEndTime(endTime + dt);
  }
  sendDisplacement();
}

std::vector<double> fsiCoupling::structureLoads(vector& fluidTotal) const {
  fluidTotal = Zero;
  std::vector<double> loads;
  if (Pstream::master()) loads.assign(3 * std::size_t(structure_->numInterfaceNodes()), 0.0);
  std::vector<double> fs(loads.size());
  forAll(interfaces_, i) {
    const tmp<vectorField> f = faceForces(i, viscous_);
    fluidTotal += sum(f());
    const std::vector<double> nodal = interfaces_[i]->gatherNodalForces(f());
    if (Pstream::master()) {
      // Conservative transfer: F_structure = Hᵀ F_fluid has the same total force and virtual work.
      maps_[i]->applyTranspose(nodal.data(), fs.data(), 3);
      for (std::size_t k = 0; k < loads.size(); ++k) loads[k] += fs[k];
    }
  }
  reduce(fluidTotal, sumOp<vector>());
  return loads;
}

void fsiCoupling::sendDisplacement() {
  auto& pd = mesh_.lookupObjectRef<pointVectorField>("pointDisplacement");
  std::vector<double> df;
  forAll(interfaces_, i) {
    if (Pstream::master()) {
      const Eigen::VectorXd& ds = scheme_->displacement();
      df.assign(3 * std::size_t(interfaces_[i]->nGlobalPoints()), 0.0);
      maps_[i]->apply(ds.data(), df.data(), 3);
    }
    const vectorField local = interfaces_[i]->scatterPointValues(df);
    refCast<fsiInterfaceDisplacementPointPatchVectorField>(pd.boundaryFieldRef()[patchIDs_[i]])
        .setDisplacement(local);
  }
}

fileName fsiCoupling::stateFile(const fileName& timePath) const {
  return timePath / "uniform" / "fsiStructure.h5";
}

void fsiCoupling::writeStructure() {
  if (!Pstream::master()) return;
  structure_->writeResults();
  const fileName dir = time_.timePath() / "uniform";
  mkDir(dir);
  std::map<std::string, std::vector<double>> arrays;
  const auto& h = scheme_->history();
  for (std::size_t k = 0; k < h.size(); ++k)
    arrays["interface_history_" + std::to_string(k)] =
        std::vector<double>(h[k].data(), h[k].data() + h[k].size());
  structure_->writeState(std::string(stateFile(time_.timePath())), arrays);
}

void fsiCoupling::keepLastStableState() {
  structure_->restoreCheckpoint();
  structure_->writeResults();
  structure_->writeState(std::string(time_.globalPath() / "structure" / "last_stable_state.h5"));
}

void fsiCoupling::logWindow(const vector& fluidTotal, const std::vector<double>& loads) {
  if (!Pstream::master()) return;
  vector structureTotal = Zero;
  for (std::size_t k = 0; k < loads.size(); ++k) structureTotal[k % 3] += loads[k];
  const auto& w = scheme_->lastWindow();
  Info << "fsiCoupling: t = " << time_.value() << " s, window " << w.window << ": " << w.iterations
       << " iteration(s)" << (w.converged || !implicit_ ? "" : " NOT CONVERGED") << ", interface force fluid "
       << fluidTotal << " N, structure " << structureTotal << " N" << endl;
  OFstream& os = *log_;
  os << time_.value() << ',' << w.iterations << ',' << int(w.converged) << ',' << w.relativeResidual;
  for (direction k = 0; k < 3; ++k) os << ',' << fluidTotal[k];
  for (direction k = 0; k < 3; ++k) os << ',' << structureTotal[k];
  for (const auto& [name, value] : fsi::structure::evaluateProbes(structure_->scene())) os << ',' << value;
  os << endl;
}

bool fsiCoupling::execute() {
  if (scene_.empty()) {
    Info << "fsiCoupling: t = " << time_.value() << " s, interface pressure force " << pressureForce()
         << " N";
    if (viscous_) Info << ", viscous force " << interfaceForce(true) - pressureForce() << " N";
    Info << endl;
    return true;
  }
  if (ended_) return true;
  ++fluidSolves_;
  if (verifyCheckpoint_) {
    // Debug: solve every window twice from the checkpoint with the same interface motion and compare.
    const volVectorField& U = mesh_.lookupObject<volVectorField>("U");
    const volScalarField& p = mesh_.lookupObject<volScalarField>("p");
    const surfaceScalarField& phi = mesh_.lookupObject<surfaceScalarField>("phi");
    if (!repeating_) {
      firstPass_.U = U.primitiveField();
      firstPass_.p = p.primitiveField();
      firstPass_.phi = phi.primitiveField();
      firstPass_.V = mesh_.V().field();
      firstPass_.x = mesh_.points();
      checkpoint_->restore();
      repeating_ = true;
      return true;
    }
    repeating_ = false;
    Info << "fsiCoupling: repeated window at t = " << time_.value() << ": max |dU| "
         << gMax(mag(U.primitiveField() - firstPass_.U)) << ", max |dp| "
         << gMax(mag(p.primitiveField() - firstPass_.p)) << ", max |dphi| "
         << gMax(mag(phi.primitiveField() - firstPass_.phi)) << ", max |dV| "
         << gMax(mag(mesh_.V().field() - firstPass_.V)) << ", max |dx| "
         << gMax(mag(mesh_.points() - firstPass_.x)) << endl;
  }

  const auto t0 = Clock::now();
  vector fluidTotal;
  const std::vector<double> loads = structureLoads(fluidTotal);
  const auto t1 = Clock::now();
  label repeat = 0, finished = 0;
  if (Pstream::master()) {
    const fsiFloatingPointTrapsOff noTraps;
    try {
      scheme_->advance(Eigen::Map<const Eigen::VectorXd>(loads.data(), Eigen::Index(loads.size())));
    } catch (const fsi::coupling::StructureUnstable& e) {
      keepLastStableState();
      FatalErrorInFunction << "fsiCoupling: t = " << time_.value() << " s, window " << scheme_->window()
                           << ", iteration " << scheme_->iteration()
                           << ": the structure became unstable: " << e.what() << nl
                           << "The structure's last stable state (start of the window) is in "
                           << time_.globalPath() / "structure" / "last_stable_state.h5"
                           << " and the last frame of structure/results.h5. A light, soft structure "
                           << "strongly coupled to the flow may need a smaller step: lower `time: {safety: "
                           << "...}` in the scene or raise `subcycles`." << exit(FatalError);
    } catch (const std::exception& e) {
      FatalErrorInFunction << "fsiCoupling: t = " << time_.value() << " s: " << e.what() << exit(FatalError);
    }
    repeat = scheme_->requiresReadingCheckpoint() ? 1 : 0;
    finished = scheme_->isCouplingOngoing() ? 0 : 1;
  }
  Pstream::scatter(repeat);
  Pstream::scatter(finished);
  const auto t2 = Clock::now();
  if (!strayTimeDir_.empty() && isDir(strayTimeDir_)) rmDir(strayTimeDir_);
  strayTimeDir_.clear();
  if (repeat) {
    checkpoint_->restore();
    if (!isDir(time_.timePath())) strayTimeDir_ = time_.timePath();
  } else {
    logWindow(fluidTotal, loads);
    if (time_.writeTime() || finished) writeStructure();
    if ((implicit_ || verifyCheckpoint_) && !finished) checkpoint_->save();
  }
  const auto t3 = Clock::now();
  sendDisplacement();
  const auto t4 = Clock::now();
  tTransfer_ += seconds(t0, t1) + seconds(t3, t4);
  tStructure_ += seconds(t1, t2);
  tCheckpoint_ += seconds(t2, t3);
  if (finished && implicit_) {
    // The spare step added at start-up is not run: stop here (fields of this time are already written).
    const_cast<Time&>(time_).setEndTime(time_.value());
    end();
  }
  return true;
}

bool fsiCoupling::write() {
  return true;
}

bool fsiCoupling::end() {
  if (scene_.empty() || ended_) return true;
  ended_ = true;
  const double wall = seconds(wallStart_, Clock::now());
  const double ours = tTransfer_ + tStructure_ + tCheckpoint_;
  if (Pstream::master()) {
    const auto& s = scheme_->statistics();
    Info << "fsiCoupling: " << s.windows << " windows, " << fluidSolves_ << " fluid solves ("
         << s.meanIterations() << " per window, at most " << s.maxIterations << ", " << s.notConverged
         << " not converged); " << structure_->structuralSteps() << " structural steps" << nl
         << "fsiCoupling: wall time " << wall << " s: transfer " << tTransfer_ << " s, structure "
         << tStructure_ << " s, checkpoints " << tCheckpoint_ << " s = " << 100.0 * ours / max(wall, 1e-300)
         << " % of the run" << endl;
    OFstream js(time_.globalPath() / "structure" / "timing.json");
    js << "{\"wall_seconds\": " << wall << ", \"transfer_seconds\": " << tTransfer_
       << ", \"structure_seconds\": " << tStructure_ << ", \"checkpoint_seconds\": " << tCheckpoint_
       << ", \"windows\": " << s.windows << ", \"fluid_solves\": " << fluidSolves_
       << ", \"mean_iterations\": " << s.meanIterations() << ", \"max_iterations\": " << s.maxIterations
       << ", \"not_converged\": " << s.notConverged
       << ", \"structural_steps\": " << structure_->structuralSteps() << ", \"ranks\": " << Pstream::nProcs()
       << "}" << endl;
  }
  return true;
}

}  // namespace functionObjects
}  // namespace Foam
