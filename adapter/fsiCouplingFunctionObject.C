#include "addToRunTimeSelectionTable.H"
#include "coupling/StructureParticipant.hpp"
#include "fsiCouplingFunctionObject.H"
#include "surfaceFields.H"
#include "volFields.H"

namespace Foam {
namespace functionObjects {

defineTypeNameAndDebug(fsiCoupling, 0);
addToRunTimeSelectionTable(functionObject, fsiCoupling, dictionary);

fsiCoupling::fsiCoupling(const word& name, const Time& runTime, const dictionary& dict)
    : fvMeshFunctionObject(name, runTime, dict) {
  read(dict);
}

fsiCoupling::~fsiCoupling() = default;

bool fsiCoupling::read(const dictionary& dict) {
  fvMeshFunctionObject::read(dict);
  patches_ = wordList(dict.lookup("patches"));
  rho_ = dict.get<scalar>("rho");
  pRef_ = dict.lookupOrDefault<scalar>("pRef", 0.0);
  patchIDs_.setSize(patches_.size());
  forAll(patches_, i) {
    patchIDs_[i] = mesh_.boundaryMesh().findPatchID(patches_[i]);
    if (patchIDs_[i] < 0)
      FatalIOErrorInFunction(dict) << "fsiCoupling: no patch named " << patches_[i]
                                   << "; the mesh has the patches " << mesh_.boundaryMesh().names()
                                   << exit(FatalIOError);
  }
  if (dict.found("scene")) {
    scene_ = dict.get<fileName>("scene").expand();
    if (!scene_.isAbsolute()) scene_ = time_.path() / scene_;
    try {
      structure_ = std::make_unique<fsi::coupling::StructureParticipant>(std::string(scene_));
    } catch (const std::exception& e) {
      FatalIOErrorInFunction(dict) << "fsiCoupling: structure scene " << scene_ << ": " << e.what()
                                   << exit(FatalIOError);
    }
    Info << "fsiCoupling: structure " << scene_ << " with " << structure_->numInterfaceNodes()
         << " interface nodes" << endl;
  }
  return true;
}

vector fsiCoupling::pressureForce() const {
  if (!mesh_.foundObject<volScalarField>("p"))
    FatalErrorInFunction << "fsiCoupling: no pressure field p (solvers with p_rgh are not supported)"
                         << exit(FatalError);
  const volScalarField& p = mesh_.lookupObject<volScalarField>("p");
  // Incompressible solvers carry kinematic pressure [m²/s²]: scale by rho like the `forces` function object.
  const bool kinematic = p.dimensions() == dimPressure / dimDensity;
  vector F = Zero;
  for (const label id : patchIDs_) {
    const scalarField& pp = p.boundaryField()[id];
    const vectorField& Sf = mesh_.Sf().boundaryField()[id];
    F += sum((kinematic ? rho_ : 1.0) * (pp - (kinematic ? pRef_ / rho_ : pRef_)) * Sf);
  }
  reduce(F, sumOp<vector>());
  return F;
}

bool fsiCoupling::execute() {
  Info << "fsiCoupling: t = " << time_.value() << " s, interface pressure force " << pressureForce() << " N"
       << endl;
  return true;
}

bool fsiCoupling::write() {
  return true;
}

}  // namespace functionObjects
}  // namespace Foam
