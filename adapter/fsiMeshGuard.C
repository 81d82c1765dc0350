#include <chrono>
#include <cstdio>

#include "fsiMeshGuard.H"
#include "unitConversion.H"
#include "volFields.H"

namespace Foam {

namespace {

// Cell volumes of the mesh's cells on the points x: V = 1/3 sum over faces of (face centre . area vector),
// outward. Exact for planar faces, as OpenFOAM's own volumes; for a warped face both decompose it about its
// centre, differing at second order in the warp.
scalarField cellVolumes(const polyMesh& mesh, const pointField& x) {
  scalarField V(mesh.nCells(), 0.0);
  const faceList& faces = mesh.faces();
  const labelList& own = mesh.faceOwner();
  const labelList& nei = mesh.faceNeighbour();
  forAll(faces, f) {
    const scalar v = (faces[f].centre(x) & faces[f].areaNormal(x)) / 3.0;
    V[own[f]] += v;
    if (f < mesh.nInternalFaces()) V[nei[f]] -= v;
  }
  return V;
}

// The global minimum of `value` and the lowest rank holding it.
label ownerOfMin(scalar value, scalar& globalMin) {
  globalMin = returnReduce(value, minOp<scalar>());
  return returnReduce(value == globalMin ? Pstream::myProcNo() : Pstream::nProcs(), minOp<label>());
}

// Sends `v` from rank `from` to all (a sum of zeros elsewhere: no new communication pattern needed).
template <class T>
T fromRank(label from, const T& v) {
  return returnReduce(Pstream::myProcNo() == from ? v : pTraits<T>::zero, sumOp<T>());
}

}  // namespace

fsiMeshGuard::fsiMeshGuard(const fvMesh& mesh, const labelList& interfacePatches,
                           const pointVectorField& pointDisplacement, scalar minVolumeRatio)
    : mesh_(mesh), patches_(interfacePatches), minVolumeRatio_(minVolumeRatio) {
  V0_ = cellVolumes(mesh_, mesh_.points() - pointDisplacement.primitiveField());
}

fsiMeshGuard::Report fsiMeshGuard::check() {
  const auto start = std::chrono::steady_clock::now();
  Report r;
  // The primitive mesh's geometry only: check() runs while the fvMesh rebuilds its own after a motion
  // (fsiCoupling::movePoints), when V(), C() and Cf() still refer to the old points' arrays.
  const scalarField& V = mesh_.cellVolumes();
  // Smallest volume ratio and the cells that fail.
  scalar localMin = GREAT;
  label worst = -1;
  forAll(V, c) {
    const scalar ratio = V[c] / V0_[c];
    if (V[c] <= 0) ++r.inverted;
    if (ratio < minVolumeRatio_) ++r.belowRatio;
    if (ratio < localMin) {
      localMin = ratio;
      worst = c;
    }
  }
  r.cells = returnReduce(V.size(), sumOp<label>());
  reduce(r.inverted, sumOp<label>());
  reduce(r.belowRatio, sumOp<label>());
  // The faces' pyramids, OpenFOAM's checkFacePyramids criterion (primitiveMeshTools::facePyramidVolume: the
  // pyramid of a face to a cell centre has the volume Sf . (Cf - C) / 3; the owner's must be positive, the
  // neighbour's negative, beyond -SMALL), on the mesh's cached face centres and areas: checkFacePyramids
  // itself recomputes every face's centre and area from its points, which made the guard cost 4 % of
  // cavity-membrane-2d's run. tests/adapter mesh-guard checks the count against checkMesh's.
  // In the same pass, the non-orthogonality of the internal faces (angle between the centres' line and Sf).
  const vectorField& Cf = mesh_.faceCentres();
  const vectorField& Sf = mesh_.faceAreas();
  const vectorField& C = mesh_.cellCentres();
  const labelList& own = mesh_.faceOwner();
  const labelList& nei = mesh_.faceNeighbour();
  label firstBad = -1, nBad = 0;
  scalar minCos = 1;
  forAll(Cf, f) {
    bool bad = (Sf[f] & (Cf[f] - C[own[f]])) / 3 < -SMALL;
    if (f < mesh_.nInternalFaces()) {
      const vector d = C[nei[f]] - C[own[f]];
      bad = bad || (Sf[f] & (C[nei[f]] - Cf[f])) / 3 < -SMALL;
      minCos = min(minCos, (d & Sf[f]) / (mag(d) * mag(Sf[f]) + VSMALL));
    }
    if (bad) {
      if (firstBad < 0) firstBad = f;
      ++nBad;
    }
  }
  r.badPyramids = returnReduce(nBad, sumOp<label>());
  reduce(minCos, minOp<scalar>());
  r.maxNonOrth = radToDeg(std::acos(min(1.0, max(-1.0, minCos))));

  r.rank = ownerOfMin(localMin, r.minRatio);
  // With remeshing on, a wrong-oriented face in cells that all keep a positive volume above minVolumeRatio
  // asks for a new mesh rather than a stop: the window's flow is still finite there, and a mesh snapped
  // around a deformed canopy can fold a face at a feature while no cell has lost much volume.
  const bool remeshing = remeshBelow_ > 0;
  r.failed = r.inverted > 0 || r.belowRatio > 0 || (r.badPyramids > 0 && !remeshing);
  worstRatio_ = min(worstRatio_, r.minRatio);
  if (worstRatio_ == r.minRatio) worstRatioTime_ = mesh_.time().value();
  maxNonOrthSeen_ = max(maxNonOrthSeen_, r.maxNonOrth);
  r.remesh = !r.failed && remeshing && (r.minRatio < remeshBelow_ || r.badPyramids > 0);
  if (r.failed || r.remesh) {
    // Where: the worst cell, then the interface face nearest to it (over all ranks).
    const bool mine = Pstream::myProcNo() == r.rank && worst >= 0;
    r.cell = fromRank(r.rank, mine ? worst : label(0));
    r.centre = fromRank(r.rank, mine ? mesh_.cellCentres()[worst] : point(Zero));
    r.volume = fromRank(r.rank, mine ? V[worst] : 0.0);
    r.volume0 = fromRank(r.rank, mine ? V0_[worst] : 0.0);
  }
  if (r.failed || r.remesh) {
    scalar nearest = GREAT;
    label patchIndex = -1, face = -1;
    forAll(patches_, i) {
      const vectorField::subField Cf = mesh_.boundaryMesh()[patches_[i]].faceCentres();
      forAll(Cf, f) {
        const scalar d = mag(Cf[f] - r.centre);
        if (d < nearest) {
          nearest = d;
          patchIndex = i;
          face = f;
        }
      }
    }
    const label at = ownerOfMin(nearest, r.distance);
    r.faceRank = at;
    const bool near = Pstream::myProcNo() == at && face >= 0;
    const label i = fromRank(at, near ? patchIndex : label(0));
    r.face = fromRank(at, near ? face : label(0));
    r.faceCentre =
        fromRank(at, near ? mesh_.boundaryMesh()[patches_[patchIndex]].faceCentres()[face] : point(Zero));
    r.patch = mesh_.boundaryMesh()[patches_[i]].name();
    if (r.badPyramids > 0) {
      r.badFaceRank = returnReduce(firstBad < 0 ? Pstream::nProcs() : Pstream::myProcNo(), minOp<label>());
      const bool here = Pstream::myProcNo() == r.badFaceRank;
      const label f = here ? firstBad : label(-1);
      r.badFace = fromRank(r.badFaceRank, here ? f : label(0));
      r.badFaceOwner = fromRank(r.badFaceRank, here ? mesh_.faceOwner()[f] : label(0));
      r.badFaceCentre = fromRank(r.badFaceRank, here ? mesh_.faceCentres()[f] : point(Zero));
    }
  }
  seconds_ += std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return r;
}

std::string fsiMeshGuard::describe(const Report& r) const {
  char buf[1024];
  std::string s = "the moving mesh has degraded: ";
  std::string what;
  if (r.inverted > 0) what += std::to_string(r.inverted) + " cell(s) with non-positive volume (inverted)";
  if (r.badPyramids > 0)
    what +=
        (what.empty() ? "" : ", ") + std::to_string(r.badPyramids) + " face(s) with wrong-oriented pyramids";
  if (r.belowRatio > 0) {
    std::snprintf(buf, sizeof buf, "%d cell(s) shrunk below minVolumeRatio %g of their initial volume",
                  int(r.belowRatio), minVolumeRatio_);
    what += (what.empty() ? "" : ", ") + std::string(buf);
  }
  s += what + " (of " + std::to_string(r.cells) + " cells).\n";
  std::snprintf(buf, sizeof buf,
                "    Worst cell: %d%s at (%g %g %g): volume %g m3, initial %g m3, volume ratio %g; "
                "largest face non-orthogonality %.1f deg.\n",
                int(r.cell), Pstream::parRun() ? (" on rank " + std::to_string(r.rank)).c_str() : "",
                r.centre.x(), r.centre.y(), r.centre.z(), r.volume, r.volume0, r.minRatio, r.maxNonOrth);
  s += buf;
  if (r.badFace >= 0) {
    std::snprintf(buf, sizeof buf, "    First wrong-oriented face: %d (owner cell %d)%s at (%g %g %g).\n",
                  int(r.badFace), int(r.badFaceOwner),
                  Pstream::parRun() ? (" on rank " + std::to_string(r.badFaceRank)).c_str() : "",
                  r.badFaceCentre.x(), r.badFaceCentre.y(), r.badFaceCentre.z());
    s += buf;
  }
  std::snprintf(buf, sizeof buf,
                "    Nearest interface face: patch %s, face %d%s at (%g %g %g), %g m away.\n",
                r.patch.c_str(), int(r.face),
                Pstream::parRun() ? (" on rank " + std::to_string(r.faceRank)).c_str() : "", r.faceCentre.x(),
                r.faceCentre.y(), r.faceCentre.z(), r.distance);
  s += buf;
  s += "    The interface moved farther than the mesh motion can follow. Remedies: a smaller structural "
       "motion "
       "per window (smaller deltaT), `loadRelaxation` < 1 to damp a load-shape feedback, a stiffer motion "
       "diffusivity near the interface in constant/dynamicMeshDict (e.g. `diffusivity inverseDistance "
       "(<patch>)` or `quadratic inverseDistance`), or remeshing for motions this large. `minVolumeRatio` "
       "sets the threshold, `meshGuard no` turns the check off.";
  return s;
}

}  // namespace Foam
