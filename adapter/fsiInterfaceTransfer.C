#include <chrono>
#include <sstream>
#include <stdexcept>
#include <string>

#include "coupling/interface/InterfaceIO.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/MappingDefaults.hpp"
#include "coupling/mapping/SurfaceSmoothing.hpp"
#include "coupling/scheme/CouplingScheme.hpp"
#include "fsiInterfaceDisplacementPointPatchVectorField.H"
#include "fsiInterfaceTransfer.H"
#include "fvcGrad.H"
#include "turbulenceModel.H"
#include "volFields.H"

namespace Foam {

namespace {
using Clock = std::chrono::steady_clock;
double seconds(Clock::time_point a, Clock::time_point b) {
  return std::chrono::duration<double>(b - a).count();
}

// `head` + `text` as [fsi] log lines under 160 characters (the progress lines' promise, tests/adapter
// progress): the text broken after its ", " separators, continuation lines indented.
void infoWrapped(const std::string& head, const std::string& text) {
  constexpr std::size_t width = 150;
  std::string line = "[fsi] " + head;
  std::size_t from = 0;
  while (from < text.size()) {
    std::size_t cut = text.size();
    if (line.size() + (text.size() - from) > width) {
      const std::size_t room = width > line.size() ? width - line.size() : 0;
      const std::size_t at = text.rfind(", ", from + room);
      cut = at != std::string::npos && at > from ? at + 1 : text.size();
    }
    Info << (line + text.substr(from, cut - from)).c_str() << endl;
    from = cut;
    while (from < text.size() && text[from] == ' ') ++from;
    line = "[fsi]   ";
  }
}
}  // namespace

tmp<vectorField> fsiFaceForces(const fvMesh& mesh, label id, scalar rho0, scalar pRef, bool withViscous) {
  const volScalarField& p = mesh.lookupObject<volScalarField>("p");
  // Incompressible solvers carry kinematic pressure [m²/s²]: scale by rho like the `forces` function object.
  const bool kinematic = p.dimensions() == dimPressure / dimDensity;
  const scalar rho = kinematic ? rho0 : 1.0;
  const vectorField& Sf = mesh.Sf().boundaryField()[id];
  tmp<vectorField> tf(new vectorField(rho * (p.boundaryField()[id] - pRef / rho) * Sf));
  if (withViscous) {
    // Viscous traction as `forces` computes it: Sf & devRhoReff with devReff = -nuEff dev(twoSymm(grad U)).
    const auto& turbulence = mesh.lookupObject<turbulenceModel>(turbulenceModel::propertiesName);
    const volVectorField& U = mesh.lookupObject<volVectorField>("U");
    const tmp<volTensorField> gradU = fvc::grad(U);
    const tmp<volScalarField> nuEff = turbulence.nuEff();
    const symmTensorField devReff(-nuEff().boundaryField()[id] * dev(twoSymm(gradU().boundaryField()[id])));
    tf.ref() += rho * (Sf & devReff);
  }
  return tf;
}

fsiInterfaceTransfer::fsiInterfaceTransfer(const fvMesh& mesh, const fsiCouplingConfig& config,
                                           const pointVectorField& pointDisplacement)
    : mesh_(mesh), config_(config) {
  for (const label id : config.patchIDs)
    patches_.emplace_back(new fsiInterfacePatch(mesh, id, pointDisplacement));
}

fsiInterfaceTransfer::~fsiInterfaceTransfer() = default;

bool fsiInterfaceTransfer::undeformedStart(const pointVectorField& pd) const {
  scalar startDisplacement = 0;
  for (const label id : config_.patchIDs)
    startDisplacement = max(startDisplacement, max(mag(pd.boundaryField()[id].patchInternalField())));
  reduce(startDisplacement, maxOp<scalar>());
  return startDisplacement == 0;
}

void fsiInterfaceTransfer::setUp(const fsi::coupling::StructureParticipant& structure,
                                 std::vector<double> interfaceReference, const dictionary& dict) {
  interfaceReference_ = std::move(interfaceReference);
  // Projection structure -> each fluid patch, on the reference geometry: the structure's design shape, or
  // the shape at which the fluid mesh was made (interfaceReference).
  fsi::coupling::ProjectionOptions opt = config_.projection;
  fsi::coupling::InterfaceMesh structureReference = structure.interfaceMesh();
  for (std::size_t n = 0; n < structureReference.points.size() && !interfaceReference_.empty(); ++n)
    for (std::size_t k = 0; k < 3; ++k) structureReference.points[n][k] += interfaceReference_[3 * n + k];
  projectionOptions_ = opt;
  for (const auto& ip : patches_) {
    // The tolerance from the two surfaces' chord gaps (mappingTolerance, as `fsi map-check`) unless given.
    opt.tolerance = config_.mapTolerance
                        ? *config_.mapTolerance
                        : fsi::coupling::mappingTolerance(structureReference, ip->referenceMesh());
    maps_.emplace_back(new fsi::coupling::L2Projection(structureReference, ip->referenceMesh(), opt));
    const auto& r = maps_.back()->report();
    // The settings, and whether they are the defaults `fsi map-check` checks with (coupledRunProjection()).
    const std::vector<std::string> differ = fsi::coupling::differencesFromRunDefaults(opt);
    std::string changed;
    for (const std::string& d : differ) changed += (changed.empty() ? "" : ", ") + d;
    const std::string patch = "patch " + std::string(ip->name()) + ": ";
    infoWrapped(patch, fsi::coupling::describe(opt) + " (" +
                           (config_.mapTolerance ? "mapTolerance given" : "tolerance from the chord gaps") +
                           "; " +
                           (differ.empty() ? std::string("the defaults fsi map-check uses")
                                           : "not the defaults fsi map-check uses: " + changed) +
                           ")");
    std::ostringstream setup;
    setup << r.targetNodes << " fluid points <- " << r.sourceNodes << " structure nodes, "
          << fsi::coupling::toString(maps_.back()->mass()) << " L2 projection (level " << r.quadratureLevel
          << (r.defectCorrection ? "+defect" : "") << "), " << (r.pointwise ? "displacement pointwise, " : "")
          << "largest gap " << r.maxGap << " m";
    if (r.residedPoints > 0)
      setup << ", " << r.residedPoints << " quadrature points moved to their own side of the skin";
    setup << ", set up in " << r.setupSeconds << " s";
    infoWrapped(patch, setup.str());
    if (config_.smoothingLength > 0) {
      smoothing_.emplace_back(
          new fsi::coupling::SurfaceSmoothing(ip->referenceMesh(), config_.smoothingLength));
      Info << "[fsi] patch " << ip->name() << ": displacement smoothed over " << config_.smoothingLength
           << " m (loads through the transpose)" << endl;
    }
    if (!r.allMapped()) {
      FatalIOErrorInFunction(dict) << "fsiCoupling: " << r.unmappedTargetNodes << " points of patch "
                                   << ip->name() << " are farther than mapTolerance " << opt.tolerance
                                   << " m from the structure's interface (" << config_.scene << ")";
      for (const auto& u : r.firstUnmappedPoints)
        FatalIOError << nl << "    (" << u.x[0] << ' ' << u.x[1] << ' ' << u.x[2] << ") at distance "
                     << u.distance;
      FatalIOError << nl << "Check that the patch and the structure's interface are the same surface, or "
                   << "raise mapTolerance." << exit(FatalIOError);
    }
  }
  if (config_.conserveMoment) {
    momentConservation_ = std::make_unique<fsi::coupling::MomentConservation>(
        fsi::coupling::MomentConservation::onSurface(structure.interfaceMesh()));
    Info << "[fsi] moment conserved: the loads get the couple that restores the fluid's moment (its size: "
            "the log's window lines)"
         << endl;
  }
}

std::vector<double> fsiInterfaceTransfer::structureLoads(vector& fluidTotal,
                                                         const fsi::coupling::StructureParticipant* structure,
                                                         const fsi::coupling::CouplingScheme* scheme) {
  fluidTotal = Zero;
  std::vector<double> loads;
  if (Pstream::master()) loads.assign(3 * std::size_t(structure->numInterfaceNodes()), 0.0);
  std::vector<double> fs(loads.size());
  for (std::size_t i = 0; i < patches_.size(); ++i) {
    const tmp<vectorField> f =
        fsiFaceForces(mesh_, config_.patchIDs[label(i)], config_.rho, config_.pRef, config_.viscous);
    fluidTotal += sum(f());
    const auto g0 = Clock::now();
    const std::vector<double> nodal = patches_[i]->gatherNodalForces(f());
    const auto g1 = Clock::now();
    timers_.gather += seconds(g0, g1);
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
      timers_.loadProjection += seconds(g1, Clock::now());
    }
  }
  reduce(fluidTotal, sumOp<vector>());
  moments(loads, structure, scheme);
  return loads;
}

void fsiInterfaceTransfer::moments(std::vector<double>& loads,
                                   const fsi::coupling::StructureParticipant* structure,
                                   const fsi::coupling::CouplingScheme* scheme) {
  // Moments about the origin of the same loads, each on its own side: the fluid's face forces at the
  // moved face centres, the transferred nodal forces at the structure's interface nodes where the fluid
  // saw them (reference + the window's displacement). Hᵀ keeps the force exactly; it keeps the moment only
  // as far as H reproduces the positions (exact for coplanar meshes; a curved non-matching interface differs
  // by the gap between the two surfaces, docs/COUPLING.md "Output of a coupled run"), which conserveMoment
  // makes up for with a couple.
  vector fm = Zero;
  forAll(config_.patchIDs, i) {
    const vectorField& Cf = mesh_.C().boundaryField()[config_.patchIDs[i]];
    fm += sum(Cf ^ fsiFaceForces(mesh_, config_.patchIDs[i], config_.rho, config_.pRef, config_.viscous)());
  }
  reduce(fm, sumOp<vector>());
  fluidMoment_ = fm;
  structureMoment_ = Zero;
  if (Pstream::master() && structure) {
    const std::vector<double> x = interfacePositions(*structure, scheme);
    if (momentConservation_ && x.size() == loads.size())
      lastMomentCorrection_ = momentConservation_->apply(x.data(), loads.data(), {fm[0], fm[1], fm[2]});
    for (std::size_t n = 0; 3 * n < std::min(x.size(), loads.size()); ++n)
      structureMoment_ += vector(x[3 * n], x[3 * n + 1], x[3 * n + 2]) ^
                          vector(loads[3 * n], loads[3 * n + 1], loads[3 * n + 2]);
  }
}

std::vector<double> fsiInterfaceTransfer::interfacePositions(
    const fsi::coupling::StructureParticipant& structure, const fsi::coupling::CouplingScheme* scheme) const {
  const auto& x0 = structure.interfaceMesh().points;
  std::vector<double> x(3 * x0.size());
  const bool started = scheme && scheme->displacement().size() == Eigen::Index(x.size());
  const std::vector<double> own = started ? std::vector<double>() : structure.interfaceDisplacement();
  for (std::size_t n = 0; n < x0.size(); ++n)
    for (std::size_t k = 0; k < 3; ++k) {
      const double d = started ? scheme->displacement()[Eigen::Index(3 * n + k)]
                               : (own.size() == x.size() ? own[3 * n + k] : 0.0);
      x[3 * n + k] = x0[n][k] + d;
    }
  return x;
}

void fsiInterfaceTransfer::patchDisplacement(std::size_t i, const double* ds, std::vector<double>& df) {
  df.assign(3 * std::size_t(patches_[i]->nGlobalPoints()), 0.0);
  if (interfaceReference_.empty()) {
    maps_[i]->apply(ds, df.data(), 3);
  } else {
    relative_.resize(interfaceReference_.size());
    for (std::size_t k = 0; k < relative_.size(); ++k) relative_[k] = ds[k] - interfaceReference_[k];
    maps_[i]->apply(relative_.data(), df.data(), 3);
  }
  if (!smoothing_.empty()) smoothing_[i]->apply(df.data(), df.data(), 3);
}

void fsiInterfaceTransfer::sendDisplacement(const fsi::coupling::CouplingScheme* scheme) {
  auto& pd = mesh_.lookupObjectRef<pointVectorField>("pointDisplacement");
  std::vector<double> df;
  if (Pstream::master()) {
    const Eigen::VectorXd& ds = scheme->displacement();
    lastSent_.assign(ds.data(), ds.data() + ds.size());
  }
  for (std::size_t i = 0; i < patches_.size(); ++i) {
    const auto h0 = Clock::now();
    if (Pstream::master()) patchDisplacement(i, lastSent_.data(), df);
    const auto s0 = Clock::now();
    timers_.displacementProjection += seconds(h0, s0);
    const vectorField local = patches_[i]->scatterPointValues(df);
    timers_.scatter += seconds(s0, Clock::now());
    refCast<fsiInterfaceDisplacementPointPatchVectorField>(pd.boundaryFieldRef()[patches_[i]->patchID()])
        .setDisplacement(local);
  }
}

void fsiInterfaceTransfer::writeSkins(const fileName& dir, const fileName& surface,
                                      const fsi::coupling::StructureParticipant& structure) {
  // The skin as the fluid has it now: the displacement sent for this window (the staggered scheme's
  // prediction, not the structure's state after it: the new mesh must continue the flow's wall without
  // a jump). The new mesh is snapped to it, and the state file carries the displacement as the new
  // mesh's reference (remesh_reference).
  std::vector<double> df;
  if (!surface.empty()) {
    // The undeformed skin moved with the canopy (the structure's design shape -> the skin's vertices):
    // every new mesh snaps to the same fine surface, not to the last mesh's faceted one.
    const fsi::coupling::InterfaceMesh skin = fsi::coupling::readStlSurface(std::string(surface));
    fsi::coupling::ProjectionOptions opt = projectionOptions_;
    opt.tolerance = config_.mapTolerance ? *config_.mapTolerance
                                         : fsi::coupling::mappingTolerance(structure.interfaceMesh(), skin);
    const fsi::coupling::L2Projection map(structure.interfaceMesh(), skin, opt);
    if (!map.report().allMapped())
      throw std::runtime_error("remeshSurface " + std::string(surface) + ": " +
                               std::to_string(map.report().unmappedTargetNodes) +
                               " vertices are farther than mapTolerance from the structure's interface");
    df.assign(3 * skin.points.size(), 0.0);
    map.apply(lastSent_.data(), df.data(), 3);
    fsi::coupling::writeInterfaceStl(skin, df, std::string(dir / (patches_[0]->name() + ".stl")));
    return;
  }
  for (std::size_t i = 0; i < patches_.size(); ++i) {
    patchDisplacement(i, lastSent_.data(), df);
    fsi::coupling::writeInterfaceStl(patches_[i]->referenceMesh(), df,
                                     std::string(dir / (patches_[i]->name() + ".stl")));
  }
}

}  // namespace Foam
