#include <algorithm>
#include <numeric>
#include <vector>

#include "addToRunTimeSelectionTable.H"
#include "fsiPorousWallVelocityFvPatchVectorField.H"
#include "fvcMeshPhi.H"
#include "surfaceFields.H"
#include "turbulenceModel.H"
#include "volFields.H"

namespace Foam {

fsiPorousWallVelocityFvPatchVectorField::fsiPorousWallVelocityFvPatchVectorField(
    const fvPatch& p, const DimensionedField<vector, volMesh>& iF)
    : fixedValueFvPatchVectorField(p, iF), seepage_(p.size(), Zero), seepage0_(p.size(), Zero) {}

fsiPorousWallVelocityFvPatchVectorField::fsiPorousWallVelocityFvPatchVectorField(
    const fvPatch& p, const DimensionedField<vector, volMesh>& iF, const dictionary& dict)
    : fixedValueFvPatchVectorField(p, iF, dict, false),
      partner_(dict.get<word>("partner")),
      a_(dict.get<scalar>("a")),
      b_(dict.get<scalar>("b")),
      relaxation_(dict.lookupOrDefault<scalar>("relaxation", 1)),
      pName_(dict.lookupOrDefault<word>("p", "p")),
      seepage_(p.size(), Zero),
      seepage0_(p.size(), Zero),
      source_(dict.name() + " line " + Foam::name(dict.startLineNumber())) {
  if (!(a_ >= 0 && b_ >= 0 && a_ + b_ > 0))
    FatalIOErrorInFunction(dict) << "fsiPorousWall on patch " << p.name() << ": a = " << a_ << ", b = " << b_
                                 << " (a [1/m] and b [-] non-negative, not both zero)" << exit(FatalIOError);
  if (!(relaxation_ > 0 && relaxation_ <= 1))
    FatalIOErrorInFunction(dict) << "fsiPorousWall on patch " << p.name() << ": relaxation " << relaxation_
                                 << " is not in (0, 1]" << exit(FatalIOError);
  if (dict.found("seepage")) {
    seepage_ = scalarField("seepage", dict, p.size());
    seepage0_ = seepage_;
  }
  if (dict.found("value"))
    fvPatchVectorField::operator=(vectorField("value", dict, p.size()));
  else
    fvPatchVectorField::operator=(patchInternalField());
  partnerPatch();
  pairFaces();
}

fsiPorousWallVelocityFvPatchVectorField::fsiPorousWallVelocityFvPatchVectorField(
    const fsiPorousWallVelocityFvPatchVectorField& ptf, const fvPatch& p,
    const DimensionedField<vector, volMesh>& iF, const fvPatchFieldMapper& mapper)
    : fixedValueFvPatchVectorField(ptf, p, iF, mapper),
      partner_(ptf.partner_),
      a_(ptf.a_),
      b_(ptf.b_),
      relaxation_(ptf.relaxation_),
      pName_(ptf.pName_),
      seepage_(ptf.seepage_, mapper),
      seepage0_(ptf.seepage0_, mapper),
      timeIndex_(ptf.timeIndex_),
      source_(ptf.source_) {}

fsiPorousWallVelocityFvPatchVectorField::fsiPorousWallVelocityFvPatchVectorField(
    const fsiPorousWallVelocityFvPatchVectorField& ptf)
    : fixedValueFvPatchVectorField(ptf),
      partner_(ptf.partner_),
      a_(ptf.a_),
      b_(ptf.b_),
      relaxation_(ptf.relaxation_),
      pName_(ptf.pName_),
      seepage_(ptf.seepage_),
      seepage0_(ptf.seepage0_),
      timeIndex_(ptf.timeIndex_),
      partnerFace_(ptf.partnerFace_),
      source_(ptf.source_) {}

fsiPorousWallVelocityFvPatchVectorField::fsiPorousWallVelocityFvPatchVectorField(
    const fsiPorousWallVelocityFvPatchVectorField& ptf, const DimensionedField<vector, volMesh>& iF)
    : fixedValueFvPatchVectorField(ptf, iF),
      partner_(ptf.partner_),
      a_(ptf.a_),
      b_(ptf.b_),
      relaxation_(ptf.relaxation_),
      pName_(ptf.pName_),
      seepage_(ptf.seepage_),
      seepage0_(ptf.seepage0_),
      timeIndex_(ptf.timeIndex_),
      partnerFace_(ptf.partnerFace_),
      source_(ptf.source_) {}

scalar fsiPorousWallVelocityFvPatchVectorField::seepage(scalar dpk, scalar aNu, scalar b) {
  const scalar m = mag(dpk);
  const scalar u = 2 * m / (aNu + std::sqrt(aNu * aNu + 4 * b * m) + VSMALL);
  return dpk < 0 ? -u : u;
}

label fsiPorousWallVelocityFvPatchVectorField::partnerPatch() const {
  const label id = patch().boundaryMesh().findPatchID(partner_);
  if (id < 0 || id == patch().index())
    FatalErrorInFunction << source_.c_str() << ": fsiPorousWall on patch " << patch().name() << ": partner '"
                         << partner_ << "' is " << (id < 0 ? "not a patch of the mesh" : "the patch itself")
                         << exit(FatalError);
  return id;
}

namespace {

/// The values of a patch field on every processor, in processor order (the local field in serial): a baffle's
/// two sides may be decomposed onto different processors.
template <class Type>
tmp<Field<Type>> allValues(const Field<Type>& local) {
  if (!Pstream::parRun()) return tmp<Field<Type>>::New(local);
  List<Field<Type>> all(Pstream::nProcs());
  all[Pstream::myProcNo()] = local;
  Pstream::gatherList(all);
  Pstream::scatterList(all);
  label n = 0;
  forAll(all, proc) n += all[proc].size();
  auto out = tmp<Field<Type>>::New(n);
  n = 0;
  forAll(all, proc) forAll(all[proc], i) out.ref()[n++] = all[proc][i];
  return out;
}

}  // namespace

void fsiPorousWallVelocityFvPatchVectorField::pairFaces() {
  const fvPatch& other = patch().boundaryMesh()[partnerPatch()];
  const vectorField& c = patch().Cf();
  const vectorField co(allValues(other.Cf()));  // the partner's faces on all processors
  const scalarField& area = patch().magSf();
  const label total = returnReduce(c.size(), sumOp<label>());
  if (co.size() != total)
    FatalErrorInFunction << source_.c_str() << ": fsiPorousWall on patch " << patch().name() << ": " << total
                         << " faces but partner " << partner_ << " has " << co.size()
                         << " (not the two sides of one baffle)" << exit(FatalError);
  const label n = c.size(), m = co.size();
  auto close = [&](label i, label j) { return magSqr(c[i] - co[j]) <= 1e-6 * area[i]; };
  partnerFace_.setSize(n);
  bool sameOrder = n == m;
  for (label i = 0; i < n && sameOrder; ++i) sameOrder = close(i, i);
  if (sameOrder) {
    std::iota(partnerFace_.begin(), partnerFace_.end(), 0);
    return;
  }
  // Nearest centre: the partner's faces sorted along the widest axis, a window of the tolerance searched.
  const boundBox box(co, false);
  const direction axis = findMax(box.span());
  labelList order(identity(m));
  std::sort(order.begin(), order.end(), [&](label i, label j) { return co[i][axis] < co[j][axis]; });
  scalarList keys(m);
  forAll(order, k) keys[k] = co[order[k]][axis];
  std::vector<bool> taken(keys.size(), false);
  for (label i = 0; i < n; ++i) {
    const scalar tol = 1e-3 * std::sqrt(area[i]);
    label best = -1;
    const auto lo = std::lower_bound(keys.begin(), keys.end(), c[i][axis] - tol) - keys.begin();
    for (label k = lo; k < m && keys[k] <= c[i][axis] + tol; ++k)
      if (close(i, order[k]) && (best < 0 || magSqr(c[i] - co[order[k]]) < magSqr(c[i] - co[best])))
        best = order[k];
    if (best < 0 || taken[best])
      FatalErrorInFunction << source_.c_str() << ": fsiPorousWall on patch " << patch().name() << ": face "
                           << i << " at " << c[i] << (best < 0 ? " has no face of " : " shares its face of ")
                           << partner_ << " within 1e-3 of its size (the two patches are not one baffle)"
                           << exit(FatalError);
    taken[best] = true;
    partnerFace_[i] = best;
  }
  Info << "fsiPorousWall " << patch().name() << ": faces paired with " << partner_ << " by nearest centre"
       << endl;
}

tmp<vectorField> fsiPorousWallVelocityFvPatchVectorField::wallVelocity() const {
  const fvMesh& mesh = internalField().mesh();
  if (!mesh.moving()) return tmp<vectorField>::New(size(), Zero);
  const polyPatch& pp = patch().patch();
  const pointField& oldPoints = mesh.oldPoints();
  vectorField oldFc(pp.size());
  forAll(oldFc, i) oldFc[i] = pp[i].centre(oldPoints);
  const vectorField up((pp.faceCentres() - oldFc) / mesh.time().deltaTValue());
  const volVectorField& U = static_cast<const volVectorField&>(internalField());
  const scalarField phip(patch().patchField<surfaceScalarField, scalar>(fvc::meshPhi(U)));
  const vectorField n(patch().nf());
  return up + n * (phip / (patch().magSf() + VSMALL) - (n & up));
}

void fsiPorousWallVelocityFvPatchVectorField::updateCoeffs() {
  if (updated()) return;
  if (partnerFace_.size() != size()) pairFaces();
  const volScalarField& p = db().lookupObject<volScalarField>(pName_);
  if (p.dimensions() != dimPressure / dimDensity)
    FatalErrorInFunction << source_.c_str() << ": fsiPorousWall on patch " << patch().name() << ": pressure "
                         << pName_ << " has dimensions " << p.dimensions()
                         << "; only the kinematic pressure of an incompressible solver" << exit(FatalError);
  const scalarField& pThis = p.boundaryField()[patch().index()];
  const scalarField pOther(allValues(p.boundaryField()[partnerPatch()]));
  const auto& turbulence = db().lookupObject<turbulenceModel>(
      IOobject::groupName(turbulenceModel::propertiesName, internalField().group()));
  const scalarField nu(turbulence.nu(patch().index()));
  // relaxation: from the last time step's seepage (however often the solver evaluates the condition per step)
  const label timeIndex = db().time().timeIndex();
  if (timeIndex != timeIndex_) {
    seepage0_ = seepage_;
    timeIndex_ = timeIndex;
  }
  forAll(seepage_, i) {
    const scalar law = seepage(pThis[i] - pOther[partnerFace_[i]], a_ * nu[i], b_);
    seepage_[i] = seepage0_[i] + relaxation_ * (law - seepage0_[i]);
  }
  vectorField::operator=(wallVelocity() + patch().nf() * seepage_);
  fixedValueFvPatchVectorField::updateCoeffs();
}

void fsiPorousWallVelocityFvPatchVectorField::autoMap(const fvPatchFieldMapper& m) {
  fixedValueFvPatchVectorField::autoMap(m);
  seepage_.autoMap(m);
  seepage0_.autoMap(m);
  partnerFace_.clear();
}

void fsiPorousWallVelocityFvPatchVectorField::rmap(const fvPatchVectorField& ptf, const labelList& addr) {
  fixedValueFvPatchVectorField::rmap(ptf, addr);
  const auto& other = refCast<const fsiPorousWallVelocityFvPatchVectorField>(ptf);
  seepage_.rmap(other.seepage_, addr);
  seepage0_.rmap(other.seepage0_, addr);
  partnerFace_.clear();
}

void fsiPorousWallVelocityFvPatchVectorField::write(Ostream& os) const {
  fvPatchVectorField::write(os);
  os.writeEntry("partner", partner_);
  os.writeEntry("a", a_);
  os.writeEntry("b", b_);
  os.writeEntry("relaxation", relaxation_);
  os.writeEntryIfDifferent<word>("p", "p", pName_);
  seepage_.writeEntry("seepage", os);
  writeEntry("value", os);
}

makePatchTypeField(fvPatchVectorField, fsiPorousWallVelocityFvPatchVectorField);

}  // namespace Foam
