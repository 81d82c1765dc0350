#include "Time.H"
#include "addToRunTimeSelectionTable.H"
#include "fsiInterfaceDisplacementPointPatchVectorField.H"
#include "pointPatchFields.H"

namespace Foam {

fsiInterfaceDisplacementPointPatchVectorField::fsiInterfaceDisplacementPointPatchVectorField(
    const pointPatch& p, const DimensionedField<vector, pointMesh>& iF)
    : fixedValuePointPatchField<vector>(p, iF), startIndex_(iF.time().timeIndex()) {}

fsiInterfaceDisplacementPointPatchVectorField::fsiInterfaceDisplacementPointPatchVectorField(
    const pointPatch& p, const DimensionedField<vector, pointMesh>& iF, const dictionary& dict)
    : fixedValuePointPatchField<vector>(p, iF, dict), startIndex_(iF.time().timeIndex()) {}

fsiInterfaceDisplacementPointPatchVectorField::fsiInterfaceDisplacementPointPatchVectorField(
    const fsiInterfaceDisplacementPointPatchVectorField& ptf, const pointPatch& p,
    const DimensionedField<vector, pointMesh>& iF, const pointPatchFieldMapper& mapper)
    : fixedValuePointPatchField<vector>(ptf, p, iF, mapper), startIndex_(ptf.startIndex_) {}

fsiInterfaceDisplacementPointPatchVectorField::fsiInterfaceDisplacementPointPatchVectorField(
    const fsiInterfaceDisplacementPointPatchVectorField& ptf, const DimensionedField<vector, pointMesh>& iF)
    : fixedValuePointPatchField<vector>(ptf, iF),
      next_(ptf.next_),
      hasNext_(ptf.hasNext_),
      startIndex_(ptf.startIndex_) {}

void fsiInterfaceDisplacementPointPatchVectorField::setDisplacement(const vectorField& d) {
  if (d.size() != this->size())
    FatalErrorInFunction << "fsiInterfaceDisplacement on patch " << this->patch().name() << ": " << d.size()
                         << " values for " << this->size() << " points" << exit(FatalError);
  next_ = d;
  hasNext_ = true;
}

void fsiInterfaceDisplacementPointPatchVectorField::updateCoeffs() {
  if (this->updated()) return;
  if (hasNext_) {
    if (debug)
      Info << "fsiInterfaceDisplacement " << this->patch().name() << ": max |d| " << gMax(mag(next_))
           << " sum " << gSum(next_) << endl;
    this->operator==(next_);
  } else if (this->db().time().timeIndex() > startIndex_)
    FatalErrorInFunction << "fsiInterfaceDisplacement on patch " << this->patch().name()
                         << ": the mesh moves but no fsiCoupling function object has set the interface "
                         << "displacement; the coupling did not start (check the fsiCoupling entry in "
                         << "system/controlDict `functions`)" << exit(FatalError);
  fixedValuePointPatchField<vector>::updateCoeffs();
}

makePointPatchTypeField(pointPatchVectorField, fsiInterfaceDisplacementPointPatchVectorField);

}  // namespace Foam
