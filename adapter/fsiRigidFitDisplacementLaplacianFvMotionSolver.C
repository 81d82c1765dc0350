#include <Eigen/Dense>

#include "addToRunTimeSelectionTable.H"
#include "emptyPolyPatch.H"
#include "fsiRigidFitDisplacementLaplacianFvMotionSolver.H"
#include "pointMesh.H"
#include "pointPatchDist.H"
#include "unitConversion.H"
#include "valuePointPatchField.H"

namespace Foam {

defineTypeNameAndDebug(fsiRigidFitDisplacementLaplacianFvMotionSolver, 0);
addToRunTimeSelectionTable(motionSolver, fsiRigidFitDisplacementLaplacianFvMotionSolver, dictionary);

fsiRigidFitDisplacementLaplacianFvMotionSolver::fsiRigidFitDisplacementLaplacianFvMotionSolver(
    const polyMesh& mesh, const IOdictionary& dict)
    : displacementLaplacianFvMotionSolver(mesh, checkedDictionary(dict)) {
  readCoeffs();
  computeWeights();
}

const IOdictionary& fsiRigidFitDisplacementLaplacianFvMotionSolver::checkedDictionary(
    const IOdictionary& dict) {
  // The base solver reads displacementLaplacianCoeffs; a dictionary named after this solver would be ignored.
  if (dict.found(typeName + "Coeffs") || !dict.isDict("displacementLaplacianCoeffs"))
    FatalIOErrorInFunction(dict) << typeName << " extends displacementLaplacian and reads its coefficients "
                                 << "(diffusivity, and patches, innerDistance, outerDistance) from "
                                 << "displacementLaplacianCoeffs { ... }, not from " << typeName << "Coeffs"
                                 << exit(FatalIOError);
  return dict;
}

void fsiRigidFitDisplacementLaplacianFvMotionSolver::readCoeffs() {
  const dictionary& d = coeffDict();
  const wordRes names(d.get<wordRes>("patches"));
  patchIDs_ = fvMesh_.boundaryMesh().patchSet(names).sortedToc();
  if (patchIDs_.empty())
    FatalIOErrorInFunction(d) << type() << ": `patches` " << names << " matches no patch of the mesh "
                              << "(patches: " << fvMesh_.boundaryMesh().names() << ")" << exit(FatalIOError);
  innerDistance_ = d.get<scalar>("innerDistance");
  outerDistance_ = d.get<scalar>("outerDistance");
  if (!(innerDistance_ >= 0) || !(outerDistance_ > innerDistance_))
    FatalIOErrorInFunction(d) << type() << ": need 0 <= innerDistance < outerDistance, got innerDistance "
                              << innerDistance_ << ", outerDistance " << outerDistance_ << exit(FatalIOError);
  const auto& bf = pointDisplacement().boundaryField();
  for (const label id : patchIDs_)
    if (!isA<valuePointPatchField<vector>>(bf[id]))
      FatalIOErrorInFunction(d)
          << type() << ": pointDisplacement on patch " << bf[id].patch().name() << " is of type "
          << bf[id].type() << ", which sets no displacement; the fitted patches need a fixed displacement "
          << "(e.g. fsiInterfaceDisplacement)" << exit(FatalIOError);
  residual_.setSize(patchIDs_.size());
}

void fsiRigidFitDisplacementLaplacianFvMotionSolver::computeWeights() {
  // The distance of each reference point to the fitted patches, by a point-edge wave through the mesh (all
  // ranks): exact on the patches, the edge-path distance elsewhere, which is all a blending ramp needs.
  const pointPatchDist dist(pointMesh::New(fvMesh_), labelHashSet(patchIDs_), points0());
  weight_.setSize(dist.size());
  const scalar ramp = outerDistance_ - innerDistance_;
  forAll(weight_, i) {
    const scalar s = (dist[i] - innerDistance_) / ramp;
    weight_[i] = s <= 0 ? 1 : s >= 1 ? 0 : 0.5 * (1 + std::cos(constant::mathematical::pi * s));
  }
  label rigid = 0, ramped = 0;
  forAll(weight_, i) {
    if (weight_[i] == 1)
      ++rigid;
    else if (weight_[i] > 0)
      ++ramped;
  }
  // The rigid part must fade out before any other boundary, whose own condition it would overrule.
  const polyBoundaryMesh& bm = fvMesh_.boundaryMesh();
  forAll(bm, id) {
    const polyPatch& pp = bm[id];
    if (pp.coupled() || isA<emptyPolyPatch>(pp) || patchIDs_.found(id)) continue;
    scalar nearest = GREAT;
    for (const label p : pp.meshPoints()) nearest = min(nearest, dist[p]);
    reduce(nearest, minOp<scalar>());
    if (nearest < outerDistance_)
      FatalIOErrorInFunction(coeffDict())
          << type() << ": outerDistance " << outerDistance_ << " m reaches patch " << pp.name() << " ("
          << nearest << " m from the fitted patches), whose points the rigid part would move; "
          << "make outerDistance smaller than " << nearest << exit(FatalIOError);
  }
  Info << type() << ": " << returnReduce(rigid, sumOp<label>()) << " points move rigidly (within "
       << innerDistance_ << " m of " << patchIDs_.size() << " patch(es)), "
       << returnReduce(ramped, sumOp<label>()) << " on the ramp to " << outerDistance_ << " m" << endl;
}

void fsiRigidFitDisplacementLaplacianFvMotionSolver::fitRigidMotion() {
  // Area-weighted face samples (reference and displaced face centres): each face lives on one rank, so the
  // fit is the same for any decomposition.
  const pointField& x0 = points0();
  const auto& bf = pointDisplacement().boundaryField();
  DynamicList<scalar> area;
  DynamicList<point> ref, cur;
  for (const label id : patchIDs_) {
    const polyPatch& pp = fvMesh_.boundaryMesh()[id];
    const labelList& mp = pp.meshPoints();
    const vectorField& d = refCast<const valuePointPatchField<vector>>(bf[id]);  // just set by its condition
    const faceList& lf = pp.localFaces();
    forAll(lf, f) {
      point p0 = Zero, p = Zero;
      for (const label v : lf[f]) {
        p0 += x0[mp[v]];
        p += x0[mp[v]] + d[v];
      }
      area.append(mag(pp[f].areaNormal(x0)));
      ref.append(p0 / lf[f].size());
      cur.append(p / lf[f].size());
    }
  }
  scalar total = 0;
  vector s0 = Zero, s = Zero;
  forAll(area, i) {
    total += area[i];
    s0 += area[i] * ref[i];
    s += area[i] * cur[i];
  }
  reduce(total, sumOp<scalar>());
  reduce(s0, sumOp<vector>());
  reduce(s, sumOp<vector>());
  if (total <= 0) FatalErrorInFunction << type() << ": the fitted patches have no area" << exit(FatalError);
  c0_ = s0 / total;
  c_ = s / total;

  tensor H = Zero;  // sum of a (x0 - c0)(x - c)^T
  forAll(area, i) H += area[i] * ((ref[i] - c0_) * (cur[i] - c_));
  reduce(H, sumOp<tensor>());

  // Kabsch: with H = U S V^T, the proper rotation closest to mapping (x0 - c0) onto (x - c) is
  // R = V diag(1, 1, sign det(V U^T)) U^T.
  Eigen::Matrix3d h;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) h(i, j) = H(i, j);
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(h, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d corr = Eigen::Matrix3d::Identity();
  corr(2, 2) = (svd.matrixV() * svd.matrixU().transpose()).determinant() < 0 ? -1 : 1;
  const Eigen::Matrix3d r = svd.matrixV() * corr * svd.matrixU().transpose();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) R_(i, j) = r(i, j);
  if (!std::isfinite(tr(R_)))
    FatalErrorInFunction << type() << ": the rigid-body fit of the interface displacement is not finite"
                         << exit(FatalError);
}

scalar fsiRigidFitDisplacementLaplacianFvMotionSolver::angle() const {
  return std::acos(max(-1.0, min(1.0, 0.5 * (tr(R_) - 1))));
}

void fsiRigidFitDisplacementLaplacianFvMotionSolver::solve() {
  // The patches' conditions set the total displacement now (the base solve's own update is then a no-op).
  pointVectorField& pd = pointDisplacement();
  pd.boundaryFieldRef().updateCoeffs();
  fitRigidMotion();
  fitted_ = true;

  // The Laplacian sees the residual on the fitted patches, both in the patch values and in the point values
  // the cellDisplacement boundary condition averages.
  const pointField& x0 = points0();
  vectorField& values = pd.primitiveFieldRef();
  forAll(patchIDs_, k) {
    const label id = patchIDs_[k];
    auto& patchField = refCast<valuePointPatchField<vector>>(pd.boundaryFieldRef()[id]);
    const labelList& mp = fvMesh_.boundaryMesh()[id].meshPoints();
    vectorField& r = residual_[k];
    r = patchField;
    forAll(mp, i) {
      r[i] -= rigidDisplacement(x0[mp[i]]);
      values[mp[i]] = r[i];
    }
    patchField == r;
  }
  const vector axis(R_.zy() - R_.yz(), R_.xz() - R_.zx(), R_.yx() - R_.xy());  // 2 sin(angle) * unit axis
  Info << type() << ": rigid part: rotation " << radToDeg(angle()) << " deg about "
       << axis / max(mag(axis), VSMALL) << ", translation " << (c_ - c0_) << endl;
  displacementLaplacianFvMotionSolver::solve();
}

tmp<pointField> fsiRigidFitDisplacementLaplacianFvMotionSolver::curPoints() const {
  auto& pd = const_cast<pointVectorField&>(pointDisplacement());
  if (fitted_)  // the base interpolation inserts the patches' values: the residual, however often it runs
    forAll(patchIDs_, k)
            refCast<valuePointPatchField<vector>>(pd.boundaryFieldRef()[patchIDs_[k]]) == residual_[k];
  // points0 + residual
  tmp<pointField> tpoints = displacementLaplacianFvMotionSolver::curPoints();
  if (!fitted_) return tpoints;
  pointField points(tpoints());
  const pointField& x0 = points0();
  vectorField& total = pd.primitiveFieldRef();
  forAll(points, i) {
    if (weight_[i] == 0) continue;
    const vector rigid = weight_[i] * rigidDisplacement(x0[i]);
    points[i] += rigid;
    total[i] += rigid;
  }
  forAll(patchIDs_, k) {
    const labelList& mp = fvMesh_.boundaryMesh()[patchIDs_[k]].meshPoints();
    auto& patchField = refCast<valuePointPatchField<vector>>(pd.boundaryFieldRef()[patchIDs_[k]]);
    vectorField t(mp.size());
    forAll(mp, i) t[i] = total[mp[i]];
    patchField == t;
  }
  twoDCorrectPoints(points);
  return tmp<pointField>::New(std::move(points));
}

}  // namespace Foam
