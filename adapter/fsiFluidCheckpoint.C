#include "fsiFluidCheckpoint.H"
#include "pointFields.H"
#include "surfaceFields.H"
#include "volFields.H"

namespace Foam {

struct fsiFluidCheckpoint::Store {
  virtual ~Store() = default;
  /// Copies the live field's values into the stored levels; false if the level count changed (rebuild).
  virtual bool update() = 0;
  virtual void restore() = 0;
};

namespace {

// One GeometricField: copies of the field and of each old-time level (values, boundary values, time index).
template <class FieldType>
class FieldStore final : public fsiFluidCheckpoint::Store {
 public:
  explicit FieldStore(FieldType& f) : field_(f) {
    const FieldType* level = &f;
    while (true) {
      levels_.emplace_back(new FieldType(IOobject(level->name() + "_fsiCheckpoint", level->time().timeName(),
                                                  level->db(), IOobject::NO_READ, IOobject::NO_WRITE, false),
                                         *level));
      indices_.push_back(level->timeIndex());
      if (level->nOldTimes() == 0) break;
      level = &level->oldTime();
    }
  }
  bool update() override {
    // Values only: no field is constructed, so saving every window costs a copy of the data and no more.
    const FieldType* level = &field_;
    for (std::size_t i = 0; i < levels_.size(); ++i) {
      if (i > 0) {
        if (level->nOldTimes() == 0) return false;
        level = &level->oldTime();
      }
      levels_[i]->primitiveFieldRef(false) = level->primitiveField();
      auto& bf = levels_[i]->boundaryFieldRef(false);
      forAll(bf, p) bf[p] == level->boundaryField()[p];
      indices_[i] = level->timeIndex();
    }
    return level->nOldTimes() == 0;
  }

  void restore() override {
    // Collect the live levels first: oldTime() shifts the levels of a field whose time index is not the
    // current one, so it must not be called once saved indices are back in place. Then assign without
    // touching the access time (primitiveFieldRef(false), boundaryFieldRef(false)), which would shift too.
    std::vector<FieldType*> live{&field_};
    while (live.size() < levels_.size()) live.push_back(&live.back()->oldTime());
    for (std::size_t i = 0; i < levels_.size(); ++i) {
      live[i]->primitiveFieldRef(false) = levels_[i]->primitiveField();
      auto& bf = live[i]->boundaryFieldRef(false);
      forAll(bf, p) bf[p] == levels_[i]->boundaryField()[p];  // forced: fixed values too
      live[i]->timeIndex() = indices_[i];
    }
  }

 private:
  FieldType& field_;
  std::vector<std::unique_ptr<FieldType>> levels_;
  std::vector<label> indices_;
};

}  // namespace

fsiFluidCheckpoint::fsiFluidCheckpoint(const fvMesh& mesh, bool restorePoints)
    : mesh_(mesh), restorePoints_(restorePoints) {}
fsiFluidCheckpoint::~fsiFluidCheckpoint() = default;

template <class FieldType>
wordList fsiFluidCheckpoint::stateFields() const {
  // The mesh's own geometry (sliced onto its arrays) is recomputed by the next mesh motion: not a state.
  // Old-time levels come with their field.
  static const wordHashSet geometry{"C", "Cf", "Sf", "magSf", "meshPhi"};
  wordList names;
  for (const word& name : mesh_.sortedNames<FieldType>())
    if (!geometry.found(name) && !name.endsWith("_0") && !name.endsWith("_fsiCheckpoint")) names.append(name);
  return names;
}

template <class FieldType>
void fsiFluidCheckpoint::collect() {
  for (const word& name : stateFields<FieldType>()) {
    FieldType& f = const_cast<FieldType&>(mesh_.lookupObject<FieldType>(name));
    stores_.emplace_back(new FieldStore<FieldType>(f));
    names_.append(name);
  }
}

wordList fsiFluidCheckpoint::allStateFields() const {
  wordList names;
  names.append(stateFields<volScalarField>());
  names.append(stateFields<volVectorField>());
  names.append(stateFields<surfaceScalarField>());
  names.append(stateFields<surfaceVectorField>());
  names.append(stateFields<pointScalarField>());
  names.append(stateFields<pointVectorField>());
  return names;
}

void fsiFluidCheckpoint::save() {
  bool reused = saved_ && allStateFields() == names_;
  for (auto& s : stores_) reused = reused && s->update();
  if (!reused) rebuild();
  points_ = mesh_.points();
  time_ = mesh_.time().value();
  timeIndex_ = mesh_.time().timeIndex();
  saved_ = true;
}

void fsiFluidCheckpoint::rebuild() {
  stores_.clear();
  names_.clear();
  collect<volScalarField>();
  collect<volVectorField>();
  collect<surfaceScalarField>();
  collect<surfaceVectorField>();
  collect<pointScalarField>();
  collect<pointVectorField>();
}

void fsiFluidCheckpoint::restore() {
  if (!saved_) FatalErrorInFunction << "fsiCoupling: no fluid checkpoint to restore" << exit(FatalError);
  // Mesh points back first (still at the failed pass's time index, so OpenFOAM keeps the start-of-window
  // old points and volumes): the motion solver then assembles its Laplacian on the same geometry as in the
  // first pass. The fields come after, overwriting anything the motion touched.
  if (restorePoints_) const_cast<fvMesh&>(mesh_).movePoints(points_);
  for (auto& s : stores_) s->restore();
  const_cast<Time&>(mesh_.time()).setTime(time_, timeIndex_);
}

}  // namespace Foam
