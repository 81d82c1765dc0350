#include "IPstream.H"
#include "OPstream.H"
#include "fsiInterfacePatch.H"
#include "globalIndex.H"
#include "globalMeshData.H"
#include "points0MotionSolver.H"

namespace Foam {

fsiInterfacePatch::fsiInterfacePatch(const fvMesh& mesh, label patchID,
                                     const pointVectorField& pointDisplacement)
    : mesh_(mesh), patchID_(patchID) {
  const polyPatch& pp = mesh.boundaryMesh()[patchID];
  labelList uniqueMeshPoints;
  const autoPtr<globalIndex> numbering =
      mesh.globalData().mergePoints(pp.meshPoints(), pp.meshPointMap(), pointToGlobal_, uniqueMeshPoints);
  nGlobal_ = numbering->size();

  // Reference coordinates of the points this rank owns, and its faces in global numbering. The reference is
  // the motion solver's own points0 (x = points0 + displacement) when there is one: x - u of a restart's
  // moved mesh differs from it by round-off, which changed a restarted implicit run's iteration counts
  // (docs/ROBUSTNESS.md); on a fresh start both are the same points.
  const pointField& x = mesh.points();
  const vectorField& u = pointDisplacement.primitiveField();
  const HashTable<const points0MotionSolver*> solvers = mesh.lookupClass<points0MotionSolver>();
  const pointField* points0 = solvers.size() == 1 ? &(*solvers.cbegin())->points0() : nullptr;
  if (points0 && points0->size() != x.size()) points0 = nullptr;
  List<pointField> ownedPoints(Pstream::nProcs());
  ownedPoints[Pstream::myProcNo()].setSize(uniqueMeshPoints.size());
  forAll(uniqueMeshPoints, i) ownedPoints[Pstream::myProcNo()][i] =
      points0 ? (*points0)[uniqueMeshPoints[i]] : x[uniqueMeshPoints[i]] - u[uniqueMeshPoints[i]];
  List<faceList> faces(Pstream::nProcs());
  faceList& mine = faces[Pstream::myProcNo()];
  mine = pp.localFaces();
  for (face& f : mine)
    for (label& v : f) v = pointToGlobal_[v];
  Pstream::gatherList(ownedPoints);
  Pstream::gatherList(faces);

  rankPoints_.setSize(Pstream::nProcs());
  rankPoints_[Pstream::myProcNo()] = pointToGlobal_;
  Pstream::gatherList(rankPoints_);
  if (!Pstream::master()) rankPoints_.clear();

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
  List<vectorField> values(Pstream::nProcs());
  values[Pstream::myProcNo()] = local;
  Pstream::gatherList(values);
  const List<labelList>& ids = rankPoints_;
  std::vector<double> global;
  if (!Pstream::master()) return global;
  global.assign(3 * std::size_t(nGlobal_), 0.0);
  for (label proc = 0; proc < Pstream::nProcs(); ++proc)
    forAll(ids[proc], i) for (direction k = 0; k < 3; ++k) global[3 * std::size_t(ids[proc][i]) + k] +=
        values[proc][i][k];
  return global;
}

vectorField fsiInterfacePatch::scatterPointValues(const std::vector<double>& global) const {
  // Each rank gets its own points only: O(interface) data in all, not O(interface x ranks) as a broadcast.
  auto valuesOf = [&global](const labelList& ids) {
    vectorField v(ids.size());
    forAll(ids, i) v[i] = vector(global[3 * ids[i]], global[3 * ids[i] + 1], global[3 * ids[i] + 2]);
    return v;
  };
  if (!Pstream::parRun()) return valuesOf(pointToGlobal_);
  if (Pstream::master()) {
    for (label proc = 1; proc < Pstream::nProcs(); ++proc) {
      OPstream toProc(Pstream::commsTypes::scheduled, proc);
      toProc << valuesOf(rankPoints_[proc]);
    }
    return valuesOf(pointToGlobal_);
  }
  IPstream fromMaster(Pstream::commsTypes::scheduled, Pstream::masterNo());
  vectorField mine(fromMaster);
  return mine;
}

}  // namespace Foam
