#include <Eigen/Core>
#include <cmath>
#include <cstdio>
#include <map>
#include <optional>
#include <sstream>
#include <string>

#include "OFstream.H"
#include "addToRunTimeSelectionTable.H"
#include "coupling/CouplingCsv.hpp"
#include "coupling/CouplingTiming.hpp"
#include "coupling/StructureParticipant.hpp"
#include "coupling/effects/CouplingEffects.hpp"
#include "coupling/interface/InterfaceIO.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/SurfaceSmoothing.hpp"
#include "coupling/scheme/CouplingOptions.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "fsiCouplingFunctionObject.H"
#include "fsiCouplingOptions.H"
#include "fsiFloatingPointTraps.H"
#include "fsiInterfaceDisplacementPointPatchVectorField.H"
#include "fsiRankWait.H"
#include "fsiStopRequest.H"
#include "fvcGrad.H"
#include "movingWallVelocityFvPatchVectorField.H"
#include "structure/model/Error.hpp"
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

fsi::coupling::MassMatrix projectionKind(const word& kind) {
  fsi::coupling::MassMatrix m = fsi::coupling::MassMatrix::Consistent;
  fsi::coupling::massMatrixFromName(kind, m);  // the option table allows only these names
  return m;
}

// h:mm:ss, for wall time and ETA on the progress line.
std::string hms(double seconds) {
  const long s = std::lround(std::max(0.0, seconds));
  char buf[32];
  std::snprintf(buf, sizeof buf, "%ld:%02ld:%02ld", s / 3600, (s / 60) % 60, s % 60);
  return buf;
}

}  // namespace

fsiCoupling::fsiCoupling(const word& name, const Time& runTime, const dictionary& dict)
    : fvMeshFunctionObject(name, runTime, dict), wallStart_(Clock::now()) {
  read(dict);
}

fsiCoupling::~fsiCoupling() = default;

bool fsiCoupling::read(const dictionary& dict) {
  fvMeshFunctionObject::read(dict);
  // Every key and value against the option table first: nothing below reads an unchecked entry.
  options_ = std::make_unique<fsi::coupling::OptionValues>(readCouplingOptions(dict));
  const fsi::coupling::OptionValues& o = *options_;
  if (!structure_ && !scheme_ && interfaces_.empty())
    for (const std::string& w : o.warnings()) Info << "[fsi] warning: " << w.c_str() << endl;
  patches_.clear();
  for (const std::string& p : o.words("patches")) patches_.append(word(p));
  rho_ = o.real("rho");
  pRef_ = o.real("pRef");
  viscous_ = o.flag("viscous");
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
  if (o.given("scene") && !structure_ && !scheme_ && interfaces_.empty()) {
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
  const fsi::coupling::OptionValues& o = *options_;
  checkSetUp(dict);
  const fileName sceneGiven = o.text("scene");
  scene_ = fileName(sceneGiven).expand();
  if (!scene_.isAbsolute()) scene_ = time_.globalPath() / scene_;
  implicit_ = o.text("scheme") == "implicit";
  equilibrium_ = fsi::coupling::structureMode(o) == fsi::coupling::StructureMode::Equilibrium;
  verifyCheckpoint_ = o.flag("verifyCheckpoint");
  const scalar dt = time_.deltaTValue();
  endTime_ = time_.endTime().value();
  segmentStart_ = time_.value();
  const auto& pd = mesh_.lookupObject<pointVectorField>("pointDisplacement");
  for (const label id : patchIDs_) interfaces_.emplace_back(new fsiInterfacePatch(mesh_, id, pd));
  if (o.flag("meshGuard")) meshGuard_.reset(new fsiMeshGuard(mesh_, patchIDs_, pd, o.real("minVolumeRatio")));
  if (o.real("remeshBelow") > 0 && (!meshGuard_ || o.real("remeshBelow") <= o.real("minVolumeRatio")))
    FatalIOErrorInFunction(dict) << "fsiCoupling: remeshBelow " << o.real("remeshBelow")
                                 << " needs meshGuard yes and a value above minVolumeRatio "
                                 << o.real("minVolumeRatio") << " (the guard's stop)" << exit(FatalIOError);
  if (meshGuard_) meshGuard_->setRemeshBelow(o.real("remeshBelow"));
  remeshAt_ = o.real("remeshAt");
  if (o.given("remeshSurface") && patchIDs_.size() != 1)
    FatalIOErrorInFunction(dict) << "fsiCoupling: remeshSurface is the skin of one interface patch; this run "
                                 << "couples " << patchIDs_.size() << " patches" << exit(FatalIOError);
  // The fluid's skin is moved with the smoothed displacement, the remeshSurface would not be: the new mesh
  // would not continue the old one's wall.
  if (o.given("remeshSurface") && o.real("smoothingLength") > 0)
    FatalIOErrorInFunction(dict)
        << "fsiCoupling: remeshSurface with smoothingLength > 0 is not supported (the "
        << "surface is moved without the smoothing); leave remeshSurface out to "
        << "write the patch's own skin" << exit(FatalIOError);
  // restoreMeshPoints is an option of the implicit scheme only (the staggered one never repeats a step).
  checkpoint_.reset(
      new fsiFluidCheckpoint(mesh_, verifyCheckpoint_ || !implicit_ || o.flag("restoreMeshPoints")));
  // Progress: every window of a short run, about 40 lines for a long one; windows counted from t = 0.
  const label windowsTotal = max(label(1), label(std::lround(endTime_ / dt)));
  progressEvery_ =
      o.given("progress") ? label(o.integer("progress")) : max(label(1), (windowsTotal + 39) / 40);

  // A mesh made around the deformed canopy starts undeformed: its interface displacement is zero.
  scalar startDisplacement = 0;
  for (const label id : patchIDs_)
    startDisplacement = max(startDisplacement, max(mag(pd.boundaryField()[id].patchInternalField())));
  reduce(startDisplacement, maxOp<scalar>());
  const bool undeformedStart = startDisplacement == 0;
  const fileName outDir = time_.globalPath() / "structure";
  const bool fresh = time_.value() <= 0.5 * dt;
  const scalar t0 = namedTime(time_.value());
  std::map<std::string, std::vector<double>> restartArrays;
  if (Pstream::master()) {
    const fsiFloatingPointTrapsOff noTraps;
    // Every construction below reports a bad input through an exception: none may leave the solver
    // uncaught (Foam::error, which derives from std::exception too, passes through unchanged).
    try {
      try {
        fsi::coupling::registerCouplingEffects();  // pressure_field & co. in every scene the adapter loads
        structure_ = std::make_unique<fsi::coupling::StructureParticipant>(std::string(scene_));
      } catch (const Foam::error&) {
        throw;
      } catch (const std::exception& e) {
        FatalIOErrorInFunction(dict) << "fsiCoupling: structure scene " << scene_ << ": " << e.what()
                                     << exit(FatalIOError);
      }
      // subcycles is an option of time-accurate windows only, equilibriumSteps of equilibrium ones.
      if (o.has("subcycles")) structure_->setMinSubcycles(int(o.integer("subcycles")));
      if (equilibrium_)
        structure_->setStructureMode(fsi::coupling::StructureMode::Equilibrium,
                                     fsi::coupling::equilibriumOptions(o));
      // The fluid's load arrives as nodal forces (structureLoads: the conservative transfer Hᵀ f).
      structure_->setLoadKind(fsi::structure::InterfaceLoadKind::NodalForces);
      // Restart: the structure continues from the state written with this time directory.
      const fileName state = stateFile(time_.timePath());
      if (isFile(state)) {
        restartArrays = structure_->readState(std::string(state));
        // The time directory's name is rounded to timePrecision digits; the state file keeps the exact time.
        if (std::abs(structure_->time() - time_.value()) > 1e-3 * dt)
          FatalIOErrorInFunction(dict)
              << "fsiCoupling: structure state " << state << " is at t = " << structure_->time()
              << " s, the fluid at " << time_.value() << " s" << exit(FatalIOError);
        structure_->alignTime(time_.value());
        Info << "[fsi] structure restarted from " << time_.timeName() << "/uniform/" << state.name() << endl;
        // interfaceReference restart: a mesh that starts undeformed was made around the canopy of this state;
        // a deformed one (a plain restart of the same mesh) keeps the reference its state file carries.
        const auto ref = restartArrays.find("interface_reference");
        const bool newMesh = o.text("interfaceReference") == "restart" && undeformedStart;
        const auto remeshRef = restartArrays.find("remesh_reference");
        if (newMesh && remeshRef != restartArrays.end()) {
          interfaceReference_ = remeshRef->second;  // the skin the new mesh was snapped to
        } else if (newMesh) {
          interfaceReference_ = structure_->interfaceDisplacement();
        } else if (ref != restartArrays.end()) {
          interfaceReference_ = ref->second;
        }
        if (!interfaceReference_.empty()) {
          if (interfaceReference_.size() != 3 * std::size_t(structure_->numInterfaceNodes()))
            FatalIOErrorInFunction(dict)
                << "fsiCoupling: structure state " << state << ": interface_reference has "
                << label(interfaceReference_.size()) << " values for " << structure_->numInterfaceNodes()
                << " interface nodes" << exit(FatalIOError);
          Info << "[fsi] the fluid mesh is undeformed at the canopy's state of t = "
               << (newMesh ? time_.timeName() : word("an earlier restart"))
               << " (interfaceReference restart): the projection is set up on that shape" << endl;
        }
      } else if (o.text("interfaceReference") == "restart") {
        FatalIOErrorInFunction(dict) << "fsiCoupling: interfaceReference restart needs a restart state, "
                                     << state << ", and there is none (a run from t = 0 uses design)"
                                     << exit(FatalIOError);
      } else if (!fresh) {
        // A FatalIOError: while OpenFOAM loads function objects it turns a plain FatalError into a warning
        // and runs on without the coupling.
        FatalIOErrorInFunction(dict)
            << "fsiCoupling: the run starts at t = " << time_.value() << " s but there is no structure state "
            << state << " (a restart needs the state written with that time directory; a new run starts "
            << "at t = 0)" << exit(FatalIOError);
      }

      // Projection structure -> each fluid patch, on the reference geometry: the structure's design shape, or
      // the shape at which the fluid mesh was made (interfaceReference).
      fsi::coupling::ProjectionOptions opt;
      opt.mass = projectionKind(o.text("projection"));
      opt.gapCorrection = o.flag("gapCorrection");
      opt.keepSide = o.flag("keepSide");
      {
        const std::string& d = o.text("defectCorrection");  // the option table allows only these
        opt.defectCorrection = d == "on"    ? fsi::coupling::ProjectionOptions::Defect::On
                               : d == "off" ? fsi::coupling::ProjectionOptions::Defect::Off
                                            : fsi::coupling::ProjectionOptions::Defect::Auto;
      }
      opt.quadratureLevel =
          o.isWord("quadratureLevel") ? fsi::coupling::kAutoQuadrature : int(o.integer("quadratureLevel"));
      fsi::coupling::InterfaceMesh structureReference = structure_->interfaceMesh();
      for (std::size_t n = 0; n < structureReference.points.size() && !interfaceReference_.empty(); ++n)
        for (std::size_t k = 0; k < 3; ++k) structureReference.points[n][k] += interfaceReference_[3 * n + k];
      opt.tolerance = o.given("mapTolerance") ? o.real("mapTolerance")
                                              : 0.25 * structure_->interfaceMesh().meanEdgeLength();
      projectionOptions_ = opt;
      for (const auto& ip : interfaces_) {
        maps_.emplace_back(new fsi::coupling::L2Projection(structureReference, ip->referenceMesh(), opt));
        const auto& r = maps_.back()->report();
        Info << "[fsi] patch " << ip->name() << ": " << r.targetNodes << " fluid points <- " << r.sourceNodes
             << " structure nodes, " << fsi::coupling::toString(maps_.back()->mass())
             << " L2 projection (level " << r.quadratureLevel << (r.defectCorrection ? "+defect" : "")
             << "), largest gap " << r.maxGap << " m";
        if (r.residedPoints > 0)
          Info << ", " << r.residedPoints << " quadrature points moved to their own side of the skin";
        Info << ", set up in " << r.setupSeconds << " s" << endl;
        if (o.real("smoothingLength") > 0) {
          smoothing_.emplace_back(
              new fsi::coupling::SurfaceSmoothing(ip->referenceMesh(), o.real("smoothingLength")));
          Info << "[fsi] patch " << ip->name() << ": displacement smoothed over " << o.real("smoothingLength")
               << " m (loads through the transpose)" << endl;
        }
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
      if (o.flag("conserveMoment")) {
        momentConservation_ = std::make_unique<fsi::coupling::MomentConservation>(
            fsi::coupling::MomentConservation::onSurface(structure_->interfaceMesh()));
        Info
            << "[fsi] moment conserved: the loads get the couple that restores the fluid's moment (its size: "
               "the log's window lines)"
            << endl;
      }
      scheme_ = std::make_unique<fsi::coupling::CouplingScheme>(
          fsi::coupling::couplingConfig(o, dt, endTime_), *structure_,
          implicit_ ? fsi::coupling::makeAcceleration(o) : nullptr);

      // Output: one series per run. A restart continues results.h5, coupling.csv and timing.json after
      // dropping what lies later than the restart time (a restart from an earlier time leaves no stale
      // future); everything within half a window of t0 belongs to t0.
      mkDir(outDir);
      const std::optional<double> keepUntil = fresh ? std::nullopt : std::optional<double>(t0 + 0.5 * dt);
      structure_->openResults(std::string(outDir / "results.h5"), keepUntil);
      if (fresh) {
        structure_->recordHistory(t0);  // the state at t = 0 opens the energy and probe tables
      } else {
        structure_->noteRestart(t0);
      }
      structure_->writeResults(t0);  // t = 0, or the restart time if the earlier run has no frame there
      std::string header =
          "time,iterations,converged,residual,Fx_fluid,Fy_fluid,Fz_fluid,Fx_structure,Fy_structure,Fz_"
          "structure,Mx_fluid,My_fluid,Mz_fluid,Mx_structure,My_structure,Mz_structure";
      for (const auto& [name, value] : fsi::structure::evaluateProbes(structure_->scene()))
        header += ',' + name;
      // Equilibrium mode: what each window's relaxation did, and how near equilibrium it ended.
      if (equilibrium_) header += ",subcycles,kinetic_resets,equilibrium_residual";
      csv_ = std::make_unique<fsi::coupling::CouplingCsv>(
          std::string(outDir / "coupling.csv"), header,
          fresh ? std::nullopt
                : std::optional<fsi::coupling::CsvRestart>(
                      fsi::coupling::CsvRestart{*keepUntil, time_.timeName()}));
      timing_ = std::make_unique<fsi::coupling::CouplingTiming>(
          std::string(outDir / "timing.json"), fresh ? std::nullopt : std::optional<double>(t0), 0.5 * dt);
      stepsAtStart_ = structure_->structuralSteps();
    } catch (const Foam::error&) {
      throw;
    } catch (const std::exception& e) {
      FatalIOErrorInFunction(dict) << "fsiCoupling: " << e.what() << exit(FatalIOError);
    }

    Info << "[fsi] structure " << sceneGiven.c_str() << ": " << structure_->numInterfaceNodes()
         << " interface nodes, ";
    if (equilibrium_) {
      Info << "equilibrium mode: " << o.integer("equilibriumSteps")
           << " damped pseudo-steps per window (kinetic damping";
      if (o.text("equilibriumStart") == "carry") {
        Info << ", the motion carried across windows";
        if (o.real("equilibriumCarryFrom") > 0)
          Info << " from t = " << o.real("equilibriumCarryFrom") << " s, from rest before";
      }
      Info << ")";
    } else {
      Info << structure_->subcyclesFor(dt) << " structural steps per window of " << dt << " s";
    }
    if (o.real("loadRelaxation") < 1) Info << ", load relaxation " << o.real("loadRelaxation");
    Info << endl;
    if (implicit_) {
      const std::string& acc = o.text("acceleration");
      Info << "[fsi] implicit coupling, " << acc.c_str() << " (omega " << o.real("omega");
      if (o.has("reuse")) Info << ", reuse " << o.integer("reuse");
      Info << "), tolerance " << o.real("tolerance") << ", at most " << o.integer("maxIterations")
           << " iterations, extrapolation " << o.integer("extrapolation") << endl;
    } else {
      Info << "[fsi] staggered coupling, extrapolation " << o.integer("extrapolation") << endl;
    }
    if (!fresh)
      Info << "[fsi] restart at t = " << time_.timeName() << ": structure/results.h5 ("
           << structure_->framesWritten() << " frames up to here), coupling.csv and timing.json continue"
           << endl;
    Info << "[fsi] t = " << time_.timeName() << " to " << endTime_ << " s, " << windowsTotal << " windows; ";
    if (progressEvery_ > 0)
      Info << "progress every " << progressEvery_ << " window(s)" << endl;
    else
      Info << "no progress lines" << endl;
  }

  // Loads at t0 and the first interface displacement (the first step has no execute() before it moves).
  vector fluidTotal;
  const std::vector<double> loads = structureLoads(fluidTotal);
  if (Pstream::master()) {
    try {
      const std::vector<double> d0 = structure_->interfaceDisplacement();
      scheme_->initialize(time_.value(),
                          Eigen::Map<const Eigen::VectorXd>(d0.data(), Eigen::Index(d0.size())),
                          Eigen::Map<const Eigen::VectorXd>(loads.data(), Eigen::Index(loads.size())));
      if (!restartArrays.empty() || isFile(stateFile(time_.timePath())))
        restoreSchemeState(restartArrays, stateFile(time_.timePath()));
    } catch (const std::exception& e) {
      FatalIOErrorInFunction(dict) << "fsiCoupling: " << e.what() << exit(FatalIOError);
    }
  }
  if (implicit_ || verifyCheckpoint_) checkpoint_->save();
  if (implicit_) {
    Info << "fsiCoupling: the fluid checkpoint holds " << checkpoint_->fieldNames() << endl;
    // The last window must be repeatable: Time::run() ends the loop at endTime before a restored step could
    // run again, so the solver gets one spare step and the object stops the run when the last window is
    // accepted.
    const_cast<Time&>(time_).setEndTime(endTime_ + dt);
  }
  sendDisplacement();
  // The transfer's parts count the windows only, like tTransfer_.
  tSetup_ = seconds(wallStart_, Clock::now());
  tGather_ = tLoadProjection_ = tDisplacementProjection_ = tScatter_ = 0;
  started_ = true;
  fsiStopRequest::install();
}

scalar fsiCoupling::namedTime(scalar t) const {
  return std::stod(std::string(time_.timeName(t)));
}

fsi::coupling::TimingSegment fsiCoupling::timingSegment(double wall) const {
  fsi::coupling::TimingSegment seg;
  const auto& s = scheme_->statistics();
  seg.startTime = namedTime(segmentStart_);
  seg.endTime = namedTime(scheme_->time());
  seg.wallSeconds = wall;
  seg.transferSeconds = tTransfer_;
  seg.structureSeconds = tStructure_;
  seg.checkpointSeconds = tCheckpoint_;
  seg.windows = s.windows;
  seg.fluidSolves = fluidSolves_;
  seg.iterations = s.iterations;
  seg.maxIterations = s.maxIterations;
  seg.notConverged = s.notConverged;
  seg.structuralSteps = structure_->structuralSteps() - stepsAtStart_;
  seg.ranks = Pstream::nProcs();
  return seg;
}

std::vector<double> fsiCoupling::structureLoads(vector& fluidTotal) const {
  fluidTotal = Zero;
  std::vector<double> loads;
  if (Pstream::master()) loads.assign(3 * std::size_t(structure_->numInterfaceNodes()), 0.0);
  std::vector<double> fs(loads.size());
  forAll(interfaces_, i) {
    const tmp<vectorField> f = faceForces(i, viscous_);
    fluidTotal += sum(f());
    const auto g0 = Clock::now();
    const std::vector<double> nodal = interfaces_[i]->gatherNodalForces(f());
    const auto g1 = Clock::now();
    tGather_ += seconds(g0, g1);
    if (Pstream::master()) {
      // Conservative transfer: F_structure = Hᵀ F_fluid has the same total force and virtual work (with a
      // smoothed displacement, Hᵀ Sᵀ F_fluid: the same).
      if (!smoothing_.empty()) {
        smoothed_.resize(nodal.size());
        smoothing_[i]->applyTranspose(nodal.data(), smoothed_.data(), 3);
        maps_[i]->applyTranspose(smoothed_.data(), fs.data(), 3);
      } else {
        maps_[i]->applyTranspose(nodal.data(), fs.data(), 3);
      }
      for (std::size_t k = 0; k < loads.size(); ++k) loads[k] += fs[k];
      tLoadProjection_ += seconds(g1, Clock::now());
    }
  }
  reduce(fluidTotal, sumOp<vector>());
  // Moments about the origin of the same loads, each on its own side: the fluid's face forces at the
  // moved face centres, the transferred nodal forces at the structure's interface nodes where the fluid
  // saw them (reference + the window's displacement). Hᵀ keeps the force exactly; it keeps the moment only
  // as far as H reproduces the positions (exact for coplanar meshes; a curved non-matching interface differs
  // by the gap between the two surfaces, docs/COUPLING.md "Output of a coupled run"), which conserveMoment
  // makes up for with a couple.
  vector fm = Zero;
  forAll(interfaces_, i) {
    const vectorField& Cf = mesh_.C().boundaryField()[patchIDs_[i]];
    fm += sum(Cf ^ faceForces(i, viscous_)());
  }
  reduce(fm, sumOp<vector>());
  fluidMoment_ = fm;
  structureMoment_ = Zero;
  if (Pstream::master() && structure_) {
    const std::vector<double> x = interfacePositions();
    if (momentConservation_ && x.size() == loads.size())
      lastMomentCorrection_ = momentConservation_->apply(x.data(), loads.data(), {fm[0], fm[1], fm[2]});
    for (std::size_t n = 0; 3 * n < std::min(x.size(), loads.size()); ++n)
      structureMoment_ += vector(x[3 * n], x[3 * n + 1], x[3 * n + 2]) ^
                          vector(loads[3 * n], loads[3 * n + 1], loads[3 * n + 2]);
  }
  return loads;
}

std::vector<double> fsiCoupling::interfacePositions() const {
  const auto& x0 = structure_->interfaceMesh().points;
  std::vector<double> x(3 * x0.size());
  const bool started = scheme_ && scheme_->displacement().size() == Eigen::Index(x.size());
  const std::vector<double> own = started ? std::vector<double>() : structure_->interfaceDisplacement();
  for (std::size_t n = 0; n < x0.size(); ++n)
    for (std::size_t k = 0; k < 3; ++k) {
      const double d = started ? scheme_->displacement()[Eigen::Index(3 * n + k)]
                               : (own.size() == x.size() ? own[3 * n + k] : 0.0);
      x[3 * n + k] = x0[n][k] + d;
    }
  return x;
}

void fsiCoupling::patchDisplacement(std::size_t i, const double* ds, std::vector<double>& df) {
  df.assign(3 * std::size_t(interfaces_[i]->nGlobalPoints()), 0.0);
  if (interfaceReference_.empty()) {
    maps_[i]->apply(ds, df.data(), 3);
  } else {
    relative_.resize(interfaceReference_.size());
    for (std::size_t k = 0; k < relative_.size(); ++k) relative_[k] = ds[k] - interfaceReference_[k];
    maps_[i]->apply(relative_.data(), df.data(), 3);
  }
  if (!smoothing_.empty()) smoothing_[i]->apply(df.data(), df.data(), 3);
}

void fsiCoupling::sendDisplacement() {
  auto& pd = mesh_.lookupObjectRef<pointVectorField>("pointDisplacement");
  std::vector<double> df;
  if (Pstream::master()) {
    const Eigen::VectorXd& ds = scheme_->displacement();
    lastSent_.assign(ds.data(), ds.data() + ds.size());
  }
  for (std::size_t i = 0; i < interfaces_.size(); ++i) {
    const auto h0 = Clock::now();
    if (Pstream::master()) patchDisplacement(i, lastSent_.data(), df);
    const auto s0 = Clock::now();
    tDisplacementProjection_ += seconds(h0, s0);
    const vectorField local = interfaces_[i]->scatterPointValues(df);
    tScatter_ += seconds(s0, Clock::now());
    refCast<fsiInterfaceDisplacementPointPatchVectorField>(pd.boundaryFieldRef()[patchIDs_[i]])
        .setDisplacement(local);
  }
}

void fsiCoupling::requestRemesh() {
  // The window is written like a run's last one: fields and structure state together, so the new mesh's
  // run restarts from them.
  const_cast<Time&>(time_).writeAndEnd();
  writeStructure();
  if (Pstream::master()) {
    const fsiFloatingPointTrapsOff noTraps;
    const fileName dir = time_.globalPath() / "structure" / "remesh";
    mkDir(dir);
    std::vector<double> df;
    try {
      // The skin as the fluid has it now: the displacement sent for this window (the staggered scheme's
      // prediction, not the structure's state after it: the new mesh must continue the flow's wall without
      // a jump). The new mesh is snapped to it, and the state file carries the displacement as the new
      // mesh's reference (remesh_reference).
      const std::string surface =
          options_->given("remeshSurface") ? options_->text("remeshSurface") : std::string();
      if (!surface.empty()) {
        // The undeformed skin moved with the canopy (the structure's design shape -> the skin's vertices):
        // every new mesh snaps to the same fine surface, not to the last mesh's faceted one.
        fileName file = fileName(surface).expand();
        if (!file.isAbsolute()) file = time_.globalPath() / file;
        const fsi::coupling::InterfaceMesh skin = fsi::coupling::readStlSurface(std::string(file));
        const fsi::coupling::L2Projection map(structure_->interfaceMesh(), skin, projectionOptions_);
        if (!map.report().allMapped())
          throw std::runtime_error("remeshSurface " + std::string(file) + ": " +
                                   std::to_string(map.report().unmappedTargetNodes) +
                                   " vertices are farther than mapTolerance from the structure's interface");
        df.assign(3 * skin.points.size(), 0.0);
        map.apply(lastSent_.data(), df.data(), 3);
        fsi::coupling::writeInterfaceStl(skin, df, std::string(dir / (interfaces_[0]->name() + ".stl")));
      } else {
        for (std::size_t i = 0; i < interfaces_.size(); ++i) {
          patchDisplacement(i, lastSent_.data(), df);
          fsi::coupling::writeInterfaceStl(interfaces_[i]->referenceMesh(), df,
                                           std::string(dir / (interfaces_[i]->name() + ".stl")));
        }
      }
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
}

void fsiCoupling::restoreSchemeState(const std::map<std::string, std::vector<double>>& arrays,
                                     const fileName& file) {
  // Values are finite (StructureParticipant::readState checks every array); here: presence and sizes. Thrown
  // as InputError: the set-up's handler stops the run with it (a FatalIOError, which OpenFOAM does not turn
  // into a warning while it loads function objects).
  const std::string where = "structure state " + std::string(file) + ": the dataset /arrays/";
  const std::size_t n = 3 * std::size_t(structure_->numInterfaceNodes());
  auto array = [&](const std::string& name, std::size_t size) -> const std::vector<double>& {
    const auto it = arrays.find(name);
    if (it == arrays.end())
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
  scheme_->restoreHistory(history);
  // The load the structure got last: with loadRelaxation < 1 the next one is relaxed towards it.
  const std::vector<double>& applied = array("applied_loads", n);
  scheme_->restoreLoadsAtWindowStart(
      Eigen::Map<const Eigen::VectorXd>(applied.data(), Eigen::Index(applied.size())));
  // The acceleration's carried state (IQN-ILS' reused columns, Aitken's factor): the restarted run iterates
  // like the uninterrupted one. A state written by a staggered run (or one whose acceleration carries
  // nothing) has none: the acceleration starts afresh, as at t = 0.
  fsi::coupling::Acceleration::State acc;
  const std::string prefix = "acceleration_";
  for (const auto& [key, values] : arrays)
    if (key.compare(0, prefix.size(), prefix) == 0) acc[key.substr(prefix.size())] = values;
  if (!implicit_) return;
  if (acc.empty()) {
    if (!scheme_->accelerationState().empty())
      Info << "[fsi] the state " << file << " carries no acceleration history (written by a staggered run or "
           << "another acceleration): the acceleration starts afresh" << endl;
    return;
  }
  try {
    scheme_->restoreAccelerationState(acc);
  } catch (const std::exception& e) {
    throw fsi::InputError(where + "acceleration_*: " + e.what() +
                          " (written by another acceleration? `acceleration` must be the one the state was "
                          "written with)");
  }
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

fileName fsiCoupling::stateFile(const fileName& timePath) const {
  return timePath / "uniform" / "fsiStructure.h5";
}

void fsiCoupling::writeStructure() {
  if (!Pstream::master()) return;
  structure_->writeResults(namedTime(time_.value()));
  timing_->write(timingSegment(seconds(wallStart_, Clock::now())));  // a killed run keeps its timing so far
  // The restart state goes with the fluid's fields: a time directory holding only it (the end of a run
  // that is not a write time) would be taken by `startFrom latestTime` and fail for want of fields.
  if (!time_.writeTime()) return;
  const fileName dir = time_.timePath() / "uniform";
  mkDir(dir);
  std::map<std::string, std::vector<double>> arrays;
  const auto& h = scheme_->history();
  for (std::size_t k = 0; k < h.size(); ++k)
    arrays["interface_history_" + std::to_string(k)] =
        std::vector<double>(h[k].data(), h[k].data() + h[k].size());
  arrays["interface_history_count"] = {double(h.size())};
  for (const auto& [key, values] : scheme_->accelerationState()) arrays["acceleration_" + key] = values;
  const Eigen::VectorXd& applied = scheme_->loadsAtWindowStart();
  arrays["applied_loads"] = std::vector<double>(applied.data(), applied.data() + applied.size());
  if (!interfaceReference_.empty()) arrays["interface_reference"] = interfaceReference_;
  if (remeshRequested_) arrays["remesh_reference"] = lastSent_;
  structure_->writeState(std::string(stateFile(time_.timePath())), arrays);
}

void fsiCoupling::keepLastStableState(bool restore) {
  if (restore) structure_->restoreCheckpoint();
  structure_->writeResults(namedTime(scheme_->time()));
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
      keepLastStableState(implicit_ && scheme_->iteration() > 0);
    } catch (const std::exception& e) {
      WarningInFunction << "fsiCoupling: writing the structure's last stable state: " << e.what() << endl;
    }
  }
  // Every rank stops with the same message (the window and the structure's time live on the master).
  label window = Pstream::master() ? label(scheme_->window()) : 0;
  scalar stateTime = Pstream::master() ? namedTime(scheme_->time()) : 0.0;
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
  if (remeshAt_ <= 0 || remeshRequested_) return;
  const scalar half = 0.5 * time_.deltaTValue();  // the step's time, not its rounding
  if (segmentStart_ >= remeshAt_ - half || time_.value() < remeshAt_ - half) return;
  remeshRequested_ = true;
  std::ostringstream why;
  why << "remeshAt " << remeshAt_ << " s reached";
  remeshReason_ = why.str();
}

void fsiCoupling::logWindow(const vector& fluidTotal, const std::vector<double>& loads, bool finished) {
  if (!Pstream::master()) return;
  // The fluid's load as transferred to the structure nodes (the transfer's conservation check; with
  // loadRelaxation < 1 the structure gets the relaxed mix of it and the previous window's load).
  vector structureTotal = Zero;
  for (std::size_t k = 0; k < loads.size(); ++k) structureTotal[k % 3] += loads[k];
  const auto& w = scheme_->lastWindow();
  Info << "fsiCoupling: t = " << time_.value() << " s, window " << w.window << ": " << w.iterations
       << " iteration(s)" << (w.converged || !implicit_ ? "" : " NOT CONVERGED") << ", interface force fluid "
       << fluidTotal << " N, structure " << structureTotal << " N";
  if (momentConservation_) {
    const auto& c = lastMomentCorrection_;
    const double defect =
        std::sqrt(c.defect[0] * c.defect[0] + c.defect[1] * c.defect[1] + c.defect[2] * c.defect[2]);
    Info << ", moment made up " << defect / max(mag(fluidMoment_), VSMALL)
         << " of the fluid's (largest nodal " << c.largestNodalForce << " N)";
  }
  Info << endl;
  // The row's time is the fluid's time name: the rows line up with the time directories exactly.
  const std::map<std::string, double> probes = structure_->recordHistory(namedTime(time_.value()));
  char buf[64];
  std::string row = std::string(time_.timeName()) + ',' + std::to_string(w.iterations) + ',' +
                    std::to_string(int(w.converged));
  auto add = [&](double v) {
    std::snprintf(buf, sizeof buf, ",%.12g", v);
    row += buf;
  };
  add(w.relativeResidual);
  for (direction k = 0; k < 3; ++k) add(fluidTotal[k]);
  for (direction k = 0; k < 3; ++k) add(structureTotal[k]);
  for (direction k = 0; k < 3; ++k) add(fluidMoment_[k]);
  for (direction k = 0; k < 3; ++k) add(structureMoment_[k]);
  for (const auto& [name, value] : probes) add(value);
  if (equilibrium_) {
    const fsi::coupling::EquilibriumReport r = structure_->equilibriumReport();
    row += ',' + std::to_string(r.steps) + ',' + std::to_string(r.resets);
    add(structure_->staticResidualRatio());
  }
  csv_->row(row);
  printProgress(fluidTotal, finished);
}

void fsiCoupling::printProgress(const vector& fluidTotal, bool finished) const {
  if (progressEvery_ <= 0) return;
  const scalar dt = time_.deltaTValue();
  const long n = std::lround(time_.value() / dt), total = std::lround(endTime_ / dt);
  const double wall = seconds(wallStart_, Clock::now());
  const long done = std::lround((time_.value() - segmentStart_) / dt);
  // Every progressEvery windows and the last; also the segment's first window (an ETA at once) and any window
  // kProgressSeconds of wall time after the last line (slow windows still show that the run is alive)
  if (n % progressEvery_ != 0 && !finished && done != 1 && wall - lastProgressWall_ < kProgressSeconds)
    return;
  lastProgressWall_ = wall;
  const auto& w = scheme_->lastWindow();
  const auto& s = scheme_->statistics();
  const double eta = done > 0 ? wall * double(total - n) / double(done) : 0.0;
  char residual[32] = "-";
  if (implicit_) std::snprintf(residual, sizeof residual, "%.2e", w.relativeResidual);
  char line[256];
  // Short enough for one terminal line (< 160 characters even at a million windows and 100 hours).
  std::snprintf(
      line, sizeof line,
      "[fsi] t %s/%g s (%.1f%%)  window %ld/%ld  iter %d (mean %.1f)  res %s  F (%.3g %.3g %.3g) N  "
      "wall %s  ETA %s",
      time_.timeName().c_str(), endTime_, 100.0 * time_.value() / endTime_, n, total, w.iterations,
      s.meanIterations(), residual, fluidTotal.x(), fluidTotal.y(), fluidTotal.z(), hms(wall).c_str(),
      hms(eta).c_str());
  Info << line << endl;
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
  }

  // The mesh guard checked this window's mesh when it moved (movePoints), before the fluid solved on it.
  checkRemeshAt();
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
                           << " and the last frame of structure/results.h5. "
                           << fsi::coupling::unstableStructureAdvice(
                                  implicit_ ? fsi::coupling::SchemeKind::Implicit
                                            : fsi::coupling::SchemeKind::Staggered)
                           << exit(FatalError);
    } catch (const std::exception& e) {
      FatalErrorInFunction << "fsiCoupling: t = " << time_.value() << " s: " << e.what() << exit(FatalError);
    }
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
    try {
      logWindow(fluidTotal, loads, finished);
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
    if ((implicit_ || verifyCheckpoint_) && !finished) checkpoint_->save();
  }
  const auto t3 = Clock::now();
  sendDisplacement();
  const auto t4 = Clock::now();
  tTransfer_ += seconds(t0, t1) + seconds(t3, t4);
  tStructure_ += seconds(t1, t2);
  tCheckpoint_ += seconds(t2, t3);
  if (finished && implicit_) {
    // The spare step added at start-up is not run: stop here (this window is written above).
    const_cast<Time&>(time_).setEndTime(time_.value());
    end();
  }
  if (remeshRequested_ || stopped_) end();  // writeAndEnd() has ended the time loop
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
    Info << "[fsi] " << s.windows << " windows, " << fluidSolves_ << " fluid solves (" << s.meanIterations()
         << " per window, at most " << s.maxIterations << ", " << s.notConverged << " not converged); "
         << structure_->structuralSteps() - stepsAtStart_ << " structural steps" << nl << "[fsi] wall time "
         << wall << " s: transfer " << tTransfer_ << " s, structure " << tStructure_ << " s, checkpoints "
         << tCheckpoint_ << " s = " << 100.0 * ours / max(wall, 1e-300) << " % of the run" << endl;
    // Two lines: [fsi] lines stay under 160 characters (tests/adapter `progress`).
    Info << "[fsi] set-up " << tSetup_ << " s (structure, projection, first displacement)" << nl
         << "[fsi] transfer parts (master rank): gather " << tGather_ << " s, load projection "
         << tLoadProjection_ << " s, displacement projection " << tDisplacementProjection_ << " s, scatter "
         << tScatter_ << " s" << endl;
    if (meshGuard_)
      Info << "[fsi] mesh guard: smallest cell volume ratio " << meshGuard_->worstRatio()
           << " (at t = " << meshGuard_->worstRatioTime() << " s; stop below " << meshGuard_->minVolumeRatio()
           << "), largest non-orthogonality " << meshGuard_->maxNonOrthSeen() << " deg, checks "
           << meshGuard_->seconds() << " s" << endl;
    const fsi::coupling::TimingSegment seg = timingSegment(wall);
    if (!timing_->earlier().empty()) {
      const fsi::coupling::TimingSegment all = timing_->total(seg);
      Info << "[fsi] all " << timing_->earlier().size() + 1 << " run segments: " << all.windows
           << " windows, " << all.fluidSolves << " fluid solves, wall time " << all.wallSeconds << " s"
           << endl;
    }
    try {
      timing_->write(seg);
    } catch (const std::exception& e) {
      WarningInFunction << "fsiCoupling: " << e.what() << endl;
    }
  }
  return true;
}

}  // namespace functionObjects
}  // namespace Foam
