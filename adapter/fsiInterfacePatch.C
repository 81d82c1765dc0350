#include "fsiInterfacePatch.H"
#include "globalIndex.H"
#include "globalMeshData.H"

namespace Foam {

fsiInterfacePatch::fsiInterfacePatch(const fvMesh& mesh, label patchID,
                                     const pointVectorField& pointDisplacement)
    : mesh_(mesh), patchID_(patchID) {
  const polyPatch& pp = mesh.boundaryMesh()[patchID];
  labelList uniqueMeshPoints;
  const autoPtr<globalIndex> numbering =
      mesh.globalData().mergePoints(pp.meshPoints(), pp.meshPointMap(), pointToGlobal_, uniqueMeshPoints);
  nGlobal_ = numbering->size();

  // Reference coordinates of the points this rank owns, and its faces in global numbering.
  const pointField& x = mesh.points();
  const vectorField& u = pointDisplacement.primitiveField();
  List<pointField> ownedPoints(Pstream::nProcs());
  ownedPoints[Pstream::myProcNo()].setSize(uniqueMeshPoints.size());
  forAll(uniqueMeshPoints, i) ownedPoints[Pstream::myProcNo()][i] =
      x[uniqueMeshPoints[i]] - u[uniqueMeshPoints[i]];
  List<faceList> faces(Pstream::nProcs());
  faceList& mine = faces[Pstream::myProcNo()];
  mine = pp.localFaces();
  for (face& f : mine)
    for (label& v : f) v = pointToGlobal_[v];
  Pstream::gatherList(ownedPoints);
  Pstream::gatherList(faces);

  reference_.name = pp.name();
  if (!Pstream::master()) return;
  reference_.points.resize(nGlobal_);
  for (label proc = 0; proc < Pstream::nProcs(); ++proc) forAll(ownedPoints[proc], i) {
      const point& p = ownedPoints[proc][i];
      reference_.points[numbering->toGlobal(proc, i)] = {p.x(), p.y(), p.z()};
    }
  for (const faceList& fl : faces)
    for (const face& f : fl) reference_.addFace(std::vector<int>(f.begin(), f.end()));
}

const word& fsiInterfacePatch::name() const {
  return mesh_.boundaryMesh()[patchID_].name();
}

std::vector<double> fsiInterfacePatch::gatherNodalForces(const vectorField& faceForces) const {
  const polyPatch& pp = mesh_.boundaryMesh()[patchID_];
  const faceList& lf = pp.localFaces();
  vectorField local(pp.nPoints(), Zero);
  forAll(lf, f) {
    const vector share = faceForces[f] / scalar(lf[f].size());
    for (const label v : lf[f]) local[v] += share;
  }
  List<labelList> ids(Pstream::nProcs());
  List<vectorField> values(Pstream::nProcs());
  ids[Pstream::myProcNo()] = pointToGlobal_;
  values[Pstream::myProcNo()] = local;
  Pstream::gatherList(ids);
  Pstream::gatherList(values);
  std::vector<double> global;
  if (!Pstream::master()) return global;
  global.assign(3 * std::size_t(nGlobal_), 0.0);
  for (label proc = 0; proc < Pstream::nProcs(); ++proc)
    forAll(ids[proc], i) for (direction k = 0; k < 3; ++k) global[3 * std::size_t(ids[proc][i]) + k] +=
        values[proc][i][k];
  return global;
}

vectorField fsiInterfacePatch::scatterPointValues(const std::vector<double>& global) const {
  vectorField all(nGlobal_, Zero);
  if (Pstream::master()) forAll(all, i) all[i] = vector(global[3 * i], global[3 * i + 1], global[3 * i + 2]);
  Pstream::scatter(all);
  return vectorField(all, pointToGlobal_);
}

}  // namespace Foam
