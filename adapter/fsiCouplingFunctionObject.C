#include <Eigen/Core>
#include <cmath>
#include <sstream>
#include <string>

#include "OFstream.H"
#include "addToRunTimeSelectionTable.H"
#include "coupling/StructureParticipant.hpp"
#include "coupling/effects/CouplingEffects.hpp"
#include "coupling/scheme/CouplingOptions.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "fsiCouplingFunctionObject.H"
#include "fsiCouplingReport.H"
#include "fsiFloatingPointTraps.H"
#include "fsiInterfaceDisplacementPointPatchVectorField.H"
#include "fsiInterfaceTransfer.H"
#include "fsiPorousWallVelocityFvPatchVectorField.H"
#include "fsiRankWait.H"
#include "fsiRestartState.H"
#include "fsiStopRequest.H"
#include "movingWallVelocityFvPatchVectorField.H"
#include "surfaceFields.H"
#include "turbulenceModel.H"
#include "volFields.H"

namespace Foam {
namespace functionObjects {

defineTypeNameAndDebug(fsiCoupling, 0);
addToRunTimeSelectionTable(functionObject, fsiCoupling, dictionary);

namespace {
using Clock = fsiCouplingReport::Clock;
double seconds(Clock::time_point a, Clock::time_point b) {
  return fsiCouplingReport::seconds(a, b);
}
}  // namespace

fsiCoupling::fsiCoupling(const word& name, const Time& runTime, const dictionary& dict)
    : fvMeshFunctionObject(name, runTime, dict), wallStart_(Clock::now()) {
  read(dict);
}

fsiCoupling::~fsiCoupling() = default;

bool fsiCoupling::read(const dictionary& dict) {
  fvMeshFunctionObject::read(dict);
  config_ = readCouplingConfig(dict, mesh_, time_);
  if (!structure_ && !scheme_ && !transfer_)
    for (const std::string& w : config_.options.warnings()) Info << "[fsi] warning: " << w.c_str() << endl;
  if (mesh_.foundObject<volScalarField>("p_rgh"))
    FatalIOErrorInFunction(dict)
        << "fsiCoupling: this solver uses p_rgh (buoyancy); the interface load needs "
        << "the static pressure p of an incompressible solver such as pimpleFoam" << exit(FatalIOError);
  if (!mesh_.foundObject<volScalarField>("p"))
    FatalIOErrorInFunction(dict) << "fsiCoupling: no pressure field p" << exit(FatalIOError);
  if (config_.coupled() && !structure_ && !scheme_ && !transfer_) {
    // The safety net: whatever start-up throws ends the run with a message naming the dictionary.
    try {
      startCoupling(dict);
    } catch (const Foam::error&) {
      throw;
    } catch (const std::exception& e) {
      FatalIOErrorInFunction(dict) << "fsiCoupling: " << e.what() << exit(FatalIOError);
    }
  }
  return true;
}

vector fsiCoupling::pressureForce() const {
  return interfaceForce(false);
}

vector fsiCoupling::interfaceForce(bool withViscous) const {
  vector F = Zero;
  forAll(config_.patchIDs, i) F +=
      sum(fsiFaceForces(mesh_, config_.patchIDs[i], config_.rho, config_.pRef, withViscous)());
  reduce(F, sumOp<vector>());
  return F;
}

void fsiCoupling::checkSetUp(const dictionary& dict) const {
  if (time_.controlDict().lookupOrDefault<Switch>("adjustTimeStep", false))
    FatalIOErrorInFunction(dict)
        << "fsiCoupling: `adjustTimeStep yes` in controlDict: coupling windows have a "
        << "fixed size; set deltaT and adjustTimeStep no" << exit(FatalIOError);
  if (config_.viscous && !mesh_.foundObject<turbulenceModel>(turbulenceModel::propertiesName))
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
  forAll(config_.patchIDs, i) {
    const label id = config_.patchIDs[i];
    if (!isA<fsiInterfaceDisplacementPointPatchVectorField>(pd.boundaryField()[id]))
      FatalIOErrorInFunction(dict) << "fsiCoupling: pointDisplacement on patch " << config_.patches[i]
                                   << " is of type " << pd.boundaryField()[id].type()
                                   << "; the coupling sets it: use type fsiInterfaceDisplacement in "
                                   << "0/pointDisplacement" << exit(FatalIOError);
    if (!isA<movingWallVelocityFvPatchVectorField>(U.boundaryField()[id]) &&
        !isA<fsiPorousWallVelocityFvPatchVectorField>(U.boundaryField()[id]))
      FatalIOErrorInFunction(dict) << "fsiCoupling: U on patch " << config_.patches[i] << " is of type "
                                   << U.boundaryField()[id].type()
                                   << "; a moving interface needs movingWallVelocity (or fsiPorousWall, a "
                                   << "permeable one)" << exit(FatalIOError);
  }
}

void fsiCoupling::startMeshGuard(const dictionary& dict, const pointVectorField& pd) {
  const fsiCouplingConfig& c = config_;
  if (c.meshGuard) meshGuard_.reset(new fsiMeshGuard(mesh_, c.patchIDs, pd, c.minVolumeRatio));
  if (c.remeshBelow > 0 && (!meshGuard_ || c.remeshBelow <= c.minVolumeRatio))
    FatalIOErrorInFunction(dict) << "fsiCoupling: remeshBelow " << c.remeshBelow
                                 << " needs meshGuard yes and a value above minVolumeRatio "
                                 << c.minVolumeRatio << " (the guard's stop)" << exit(FatalIOError);
  if (meshGuard_) meshGuard_->setRemeshBelow(c.remeshBelow);
  if (!c.remeshSurface.empty() && c.patchIDs.size() != 1)
    FatalIOErrorInFunction(dict) << "fsiCoupling: remeshSurface is the skin of one interface patch; this run "
                                 << "couples " << c.patchIDs.size() << " patches" << exit(FatalIOError);
  // The fluid's skin is moved with the smoothed displacement, the remeshSurface would not be: the new mesh
  // would not continue the old one's wall.
  if (!c.remeshSurface.empty() && c.smoothingLength > 0)
    FatalIOErrorInFunction(dict)
        << "fsiCoupling: remeshSurface with smoothingLength > 0 is not supported (the "
        << "surface is moved without the smoothing); leave remeshSurface out to "
        << "write the patch's own skin" << exit(FatalIOError);
}

void fsiCoupling::startCoupling(const dictionary& dict) {
  checkSetUp(dict);
  const auto& pd = mesh_.lookupObject<pointVectorField>("pointDisplacement");
  transfer_ = std::make_unique<fsiInterfaceTransfer>(mesh_, config_, pd);
  startMeshGuard(dict, pd);
  // restoreMeshPoints is an option of the implicit scheme only (the staggered one never repeats a step).
  checkpoint_.reset(new fsiFluidCheckpoint(
      mesh_, config_.verifyCheckpoint || !config_.implicit || config_.restoreMeshPoints));
  report_ = std::make_unique<fsiCouplingReport>(time_, config_, wallStart_);
  // A mesh made around the deformed canopy starts undeformed: its interface displacement is zero.
  const bool undeformedStart = transfer_->undeformedStart(pd);
  fsiRestartState restart;
  if (Pstream::master()) startStructure(dict, restart, undeformedStart);

  // Loads at t0 and the first interface displacement (the first step has no execute() before it moves).
  vector fluidTotal;
  const std::vector<double> loads = transfer_->structureLoads(fluidTotal, structure_.get(), scheme_.get());
  if (Pstream::master()) startScheme(dict, loads, restart);
  if (config_.implicit || config_.verifyCheckpoint) checkpoint_->save();
  if (config_.implicit) {
    Info << "fsiCoupling: the fluid checkpoint holds " << checkpoint_->fieldNames() << endl;
    // The last window must be repeatable: Time::run() ends the loop at endTime before a restored step could
    // run again, so the solver gets one spare step and the object stops the run when the last window is
    // accepted.
    const_cast<Time&>(time_).setEndTime(report_->endTime() + time_.deltaTValue());
  }
  transfer_->sendDisplacement(scheme_.get());
  // The transfer's parts count the windows only, like the transfer's time.
  report_->tSetup = seconds(wallStart_, Clock::now());
  transfer_->timers() = {};
  started_ = true;
  fsiStopRequest::install();
}

void fsiCoupling::startStructure(const dictionary& dict, fsiRestartState& restart, bool undeformedStart) {
  const fsiFloatingPointTrapsOff noTraps;
  // Every construction below reports a bad input through an exception: none may leave the solver
  // uncaught (Foam::error, which derives from std::exception too, passes through unchanged).
  try {
    try {
      fsi::coupling::registerCouplingEffects();  // pressure_field & co. in every scene the adapter loads
      structure_ = std::make_unique<fsi::coupling::StructureParticipant>(
          std::string(config_.scene), std::vector<std::string>{}, config_.participant);
    } catch (const Foam::error&) {
      throw;
    } catch (const std::exception& e) {
      FatalIOErrorInFunction(dict) << "fsiCoupling: structure scene " << config_.scene << ": " << e.what()
                                   << exit(FatalIOError);
    }
    restart.read(*structure_, time_, dict, config_.interfaceReferenceRestart, undeformedStart,
                 report_->fresh());
    transfer_->setUp(*structure_, restart.interfaceReference(), dict);
    scheme_ = std::make_unique<fsi::coupling::CouplingScheme>(
        fsi::coupling::couplingConfig(config_.options, time_.deltaTValue(), report_->endTime()), *structure_,
        config_.implicit ? fsi::coupling::makeAcceleration(config_.options) : nullptr);
    report_->open(*structure_);
  } catch (const Foam::error&) {
    throw;
  } catch (const std::exception& e) {
    FatalIOErrorInFunction(dict) << "fsiCoupling: " << e.what() << exit(FatalIOError);
  }
  report_->startup(*structure_);
}

void fsiCoupling::startScheme(const dictionary& dict, const std::vector<double>& loads,
                              const fsiRestartState& restart) {
  try {
    const std::vector<double> d0 = structure_->interfaceDisplacement();
    scheme_->initialize(time_.value(), Eigen::Map<const Eigen::VectorXd>(d0.data(), Eigen::Index(d0.size())),
                        Eigen::Map<const Eigen::VectorXd>(loads.data(), Eigen::Index(loads.size())));
    restart.restoreScheme(*scheme_, structure_->numInterfaceNodes(), config_.implicit);
  } catch (const std::exception& e) {
    FatalIOErrorInFunction(dict) << "fsiCoupling: " << e.what() << exit(FatalIOError);
  }
}

void fsiCoupling::writeStructure() {
  if (!Pstream::master()) return;
  structure_->writeResults(fsiNamedTime(time_, time_.value()));
  report_->writeTiming(*structure_, *scheme_);  // a killed run keeps its timing so far
  // The restart state goes with the fluid's fields: a time directory holding only it (the end of a run
  // that is not a write time) would be taken by `startFrom latestTime` and fail for want of fields.
  if (!time_.writeTime()) return;
  fsiRestartState::write(fsiRestartState::file(time_.timePath()), *structure_, *scheme_,
                         transfer_->interfaceReference(),
                         remeshRequested_ ? &transfer_->lastSent() : nullptr);
}

void fsiCoupling::keepLastStableState(bool restore) {
  if (restore) structure_->restoreCheckpoint();
  structure_->writeResults(fsiNamedTime(time_, scheme_->time()));
  structure_->writeState(std::string(time_.globalPath() / "structure" / "last_stable_state.h5"));
}

void fsiCoupling::checkMesh() {
  if (!meshGuard_) return;
  const fsiMeshGuard::Report r = meshGuard_->check();
  if (!r.failed) {
    const scalar below = meshGuard_->remeshBelow();
    if (r.remesh) {
      remeshRequested_ = true;
      std::ostringstream why;
      if (r.badPyramids > 0)
        why << r.badPyramids << " wrong-oriented face(s), the first at (" << r.badFaceCentre.x() << ' '
            << r.badFaceCentre.y() << ' ' << r.badFaceCentre.z() << "); ";
      why << "smallest cell volume ratio " << r.minRatio;
      if (r.minRatio < below) why << " < remeshBelow " << below;
      why << " (cell at (" << r.centre.x() << ' ' << r.centre.y() << ' ' << r.centre.z() << "))";
      remeshReason_ = why.str();
    }
    return;
  }
  // The structure has not taken this pass's load yet: it is at the end of the last accepted window, except
  // after an earlier pass of an implicit window, which its checkpoint (the window's start) undoes.
  if (Pstream::master()) {
    const fsiFloatingPointTrapsOff noTraps;
    try {
      keepLastStableState(config_.implicit && scheme_->iteration() > 0);
    } catch (const std::exception& e) {
      WarningInFunction << "fsiCoupling: writing the structure's last stable state: " << e.what() << endl;
    }
  }
  // Every rank stops with the same message (the window and the structure's time live on the master).
  label window = Pstream::master() ? label(scheme_->window()) : 0;
  scalar stateTime = Pstream::master() ? fsiNamedTime(time_, scheme_->time()) : 0.0;
  Pstream::scatter(window);
  Pstream::scatter(stateTime);
  FatalErrorInFunction << "fsiCoupling: mesh guard: t = " << time_.value() << " s, window " << window << ": "
                       << meshGuard_->describe(r).c_str() << nl
                       << "The structure's last stable state (end of the last accepted window, t = "
                       << stateTime << " s) is in "
                       << time_.globalPath() / "structure" / "last_stable_state.h5"
                       << " and the last frame of structure/results.h5; the fluid's last written time "
                       << "directory is left as it is." << exit(FatalError);
}

void fsiCoupling::checkRemeshAt() {
  const scalar remeshAt = config_.remeshAt;
  if (remeshAt <= 0 || remeshRequested_) return;
  const scalar half = 0.5 * time_.deltaTValue();  // the step's time, not its rounding
  if (report_->segmentStart() >= remeshAt - half || time_.value() < remeshAt - half) return;
  remeshRequested_ = true;
  std::ostringstream why;
  why << "remeshAt " << remeshAt << " s reached";
  remeshReason_ = why.str();
}

bool fsiCoupling::repeatToVerify() {
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
    restoring_ = true;
    checkpoint_->restore();
    restoring_ = false;
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
  return false;
}

void fsiCoupling::advanceScheme(const std::vector<double>& loads) {
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
                         << " and the last frame of structure/results.h5. "
                         << fsi::coupling::unstableStructureAdvice(config_.implicit
                                                                       ? fsi::coupling::SchemeKind::Implicit
                                                                       : fsi::coupling::SchemeKind::Staggered)
                         << exit(FatalError);
  } catch (const std::exception& e) {
    FatalErrorInFunction << "fsiCoupling: t = " << time_.value() << " s: " << e.what() << exit(FatalError);
  }
}

void fsiCoupling::acceptWindow(const vector& fluidTotal, const std::vector<double>& loads, bool finished,
                               int stopSignal) {
  try {
    if (Pstream::master()) report_->window(fluidTotal, loads, finished, *structure_, *scheme_, *transfer_);
    // OpenFOAM writes the fields at the end only when it is one of its write times (and the implicit
    // scheme's spare step moved the end): write the last window now, fields and structure state together,
    // so a continued run can start from it.
    if (remeshRequested_ && !finished) {
      requestRemesh();
    } else if (stopSignal != 0) {
      requestStop(stopSignal);
    } else {
      if (finished && !time_.writeTime()) const_cast<Time&>(time_).writeNow();
      if (time_.writeTime() || finished) writeStructure();
    }
  } catch (const Foam::error&) {
    throw;
  } catch (const std::exception& e) {
    FatalErrorInFunction << "fsiCoupling: t = " << time_.value()
                         << " s: writing the structure's output: " << e.what() << exit(FatalError);
  }
  if ((config_.implicit || config_.verifyCheckpoint) && !finished) checkpoint_->save();
}

bool fsiCoupling::execute() {
  if (!transfer_) {
    Info << "fsiCoupling: t = " << time_.value() << " s, interface pressure force " << pressureForce()
         << " N";
    if (config_.viscous) Info << ", viscous force " << interfaceForce(true) - pressureForce() << " N";
    Info << endl;
    return true;
  }
  if (ended_) return true;
  ++report_->fluidSolves;
  if (config_.verifyCheckpoint && repeatToVerify()) return true;

  // The mesh guard checked this window's mesh when it moved (movePoints), before the fluid solved on it.
  checkRemeshAt();
  const auto t0 = Clock::now();
  vector fluidTotal;
  const std::vector<double> loads = transfer_->structureLoads(fluidTotal, structure_.get(), scheme_.get());
  const auto t1 = Clock::now();
  label repeat = 0, finished = 0;
  if (Pstream::master()) {
    advanceScheme(loads);
    repeat = scheme_->requiresReadingCheckpoint() ? 1 : 0;
    finished = scheme_->isCouplingOngoing() ? 0 : 1;
  }
  // The other ranks sleep while the master runs the structure, so its threads get their cores.
  fsiRankWait::release();
  fsiRankWait::wait();
  Pstream::scatter(repeat);
  Pstream::scatter(finished);
  const auto t2 = Clock::now();
  if (!strayTimeDir_.empty() && isDir(strayTimeDir_)) rmDir(strayTimeDir_);
  strayTimeDir_.clear();
  // A stop request (Ctrl-C, SIGTERM, the stop file) ends the run after an accepted window (collective).
  const int stopSignal = repeat || finished ? 0 : fsiStopRequest::pending(time_.globalPath() / "fsi.stop");
  if (repeat) {
    restoring_ = true;
    checkpoint_->restore();
    restoring_ = false;
    if (!isDir(time_.timePath())) strayTimeDir_ = time_.timePath();
  } else {
    acceptWindow(fluidTotal, loads, finished, stopSignal);
  }
  const auto t3 = Clock::now();
  transfer_->sendDisplacement(scheme_.get());
  const auto t4 = Clock::now();
  report_->tTransfer += seconds(t0, t1) + seconds(t3, t4);
  report_->tStructure += seconds(t1, t2);
  report_->tCheckpoint += seconds(t2, t3);
  if (finished && config_.implicit) {
    // The spare step added at start-up is not run: stop here (this window is written above).
    const_cast<Time&>(time_).setEndTime(time_.value());
    end();
  }
  if (remeshRequested_ || stopped_) end();  // writeAndEnd() has ended the time loop
  return true;
}

void fsiCoupling::requestRemesh() {
  // The window is written like a run's last one: fields and structure state together, so the new mesh's
  // run restarts from them.
  const_cast<Time&>(time_).writeAndEnd();
  writeStructure();
  if (!Pstream::master()) return;
  const fsiFloatingPointTrapsOff noTraps;
  const fileName dir = time_.globalPath() / "structure" / "remesh";
  mkDir(dir);
  try {
    fileName surface;
    if (!config_.remeshSurface.empty()) {
      surface = fileName(config_.remeshSurface).expand();
      if (!surface.isAbsolute()) surface = time_.globalPath() / surface;
    }
    transfer_->writeSkins(dir, surface, *structure_);
  } catch (const std::exception& e) {
    FatalErrorInFunction << "fsiCoupling: writing the skin for remeshing: " << e.what() << exit(FatalError);
  }
  OFstream request(dir / "request");
  // Windows counted from t = 0, like the progress lines (scheme_->window() counts this run segment's).
  request << "time " << time_.timeName() << nl << "window "
          << label(std::lround(time_.value() / time_.deltaTValue())) << nl << "reason "
          << remeshReason_.c_str() << nl;
  Info << "[fsi] remesh: " << remeshReason_.c_str() << " at t = " << time_.timeName()
       << " s: the fields and the structure's state are written, the skin is in " << dir
       << "; the run ends here for a new mesh" << endl;
}

void fsiCoupling::requestStop(int signal) {
  stopped_ = true;
  const_cast<Time&>(time_).writeAndEnd();
  writeStructure();
  if (!Pstream::master()) return;
  const fileName dir = time_.globalPath() / "structure";
  mkDir(dir);
  OFstream note(dir / "interrupted");
  note << "signal " << fsiStopRequest::name(signal).c_str() << nl << "time " << time_.timeName() << nl
       << "window " << label(std::lround(time_.value() / time_.deltaTValue())) << nl;
  Info << "[fsi] stopped on " << fsiStopRequest::name(signal).c_str() << " at t = " << time_.timeName()
       << " s: the fluid's fields and the structure's state are written there; the case's Allrun with "
       << "-continue (or startFrom latestTime) goes on from it" << endl;
}

void fsiCoupling::movePoints(const polyMesh& mesh) {
  // Every motion of the coupled mesh, on every rank at once; not the checkpoint's move back to a mesh
  // already checked. The fvMesh's own geometry is being rebuilt while this runs: the guard reads only the
  // primitive mesh's (recomputed from the new points, and then kept by the fvMesh).
  if (!started_ || restoring_ || ended_ || &mesh != &static_cast<const polyMesh&>(mesh_)) return;
  checkMesh();
}

bool fsiCoupling::write() {
  return true;
}

bool fsiCoupling::end() {
  if (!transfer_ || ended_) return true;
  ended_ = true;
  if (Pstream::master()) report_->summary(*structure_, *scheme_, *transfer_, meshGuard_.get());
  return true;
}

}  // namespace functionObjects
}  // namespace Foam
