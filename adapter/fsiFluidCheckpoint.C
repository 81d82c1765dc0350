#include "fsiFluidCheckpoint.H"

#include "pointFields.H"
#include "surfaceFields.H"
#include "volFields.H"

namespace Foam {

struct fsiFluidCheckpoint::Store {
  virtual ~Store() = default;
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
  void restore() override {
    FieldType* level = &field_;
    for (std::size_t i = 0; i < levels_.size(); ++i) {
      // Forced assignment: fixed-value boundaries take the saved values too.
      level->primitiveFieldRef() = levels_[i]->primitiveField();
      forAll(level->boundaryFieldRef(), p) level->boundaryFieldRef()[p] == levels_[i]->boundaryField()[p];
      level->timeIndex() = indices_[i];
      if (i + 1 < levels_.size()) level = &level->oldTime();
    }
  }

 private:
  FieldType& field_;
  std::vector<std::unique_ptr<FieldType>> levels_;
  std::vector<label> indices_;
};

}  // namespace

fsiFluidCheckpoint::fsiFluidCheckpoint(const fvMesh& mesh) : mesh_(mesh) {}
fsiFluidCheckpoint::~fsiFluidCheckpoint() = default;

template <class FieldType>
void fsiFluidCheckpoint::collect() {
  // The mesh's own geometry (sliced onto its arrays) is recomputed by the next mesh motion: not a state.
  static const wordHashSet geometry{"C", "Cf", "Sf", "magSf", "meshPhi"};
  for (const word& name : mesh_.sortedNames<FieldType>()) {
    // Old-time levels come with their field.
    if (geometry.found(name) || name.endsWith("_0") || name.endsWith("_fsiCheckpoint")) continue;
    FieldType& f = const_cast<FieldType&>(mesh_.lookupObject<FieldType>(name));
    stores_.emplace_back(new FieldStore<FieldType>(f));
  }
}

void fsiFluidCheckpoint::save() {
  stores_.clear();
  collect<volScalarField>();
  collect<volVectorField>();
  collect<surfaceScalarField>();
  collect<surfaceVectorField>();
  collect<pointScalarField>();
  collect<pointVectorField>();
  time_ = mesh_.time().value();
  timeIndex_ = mesh_.time().timeIndex();
  saved_ = true;
}

void fsiFluidCheckpoint::restore() {
  if (!saved_) FatalErrorInFunction << "fsiCoupling: no fluid checkpoint to restore" << exit(FatalError);
  for (auto& s : stores_) s->restore();
  const_cast<Time&>(mesh_.time()).setTime(time_, timeIndex_);
}

}  // namespace Foam
