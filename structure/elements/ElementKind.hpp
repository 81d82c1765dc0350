#pragma once
// ElementKind: everything the solver needs to know about one kind of element (membrane triangle, cable, bar,
// point mass, ...), behind one small interface. A kind builds and works on its own structure-of-arrays block
// in the Model (the typed model.membranes and model.cables, or a block in model.kindBlocks, e.g. the point
// masses and the bars) and keeps its per-element loops inside its own files, templated on compile-time
// options: the solver makes one virtual call per element kind (per step for the forces), never one per
// element.
//
// What a kind provides:
//   build        build(): its block of the model from the meshes' cells that are its own (triangles are the
//                membranes', lines the cables' unless a kind's scene reader claimed them into
//                MeshInput::kindInputs), its constants (wave speeds, stable-step data) and the checks of its
//                materials and elements (InputError naming the mesh and the element);
//   forces       makeForces(): the Effect that adds the internal forces and bounds the stable step (none for
//                a kind without internal forces);
//   mass         addLumpedMass() (physical) and scaleMass() (selective mass scaling);
//   relaxation   addStiffnessBounds() (Gerschgorin row sums of the tangent stiffness) and, optionally,
//                addStressBoundMass() (the stress-based fictitious mass);
//   output       outputCells() (its cells in the results file), outputFields() and addFields() (the
//                element-centred fields written on them);
//   report       label() and report() (its line in the run log and its entry in summary.json);
//   diagnosis    mostStrained() and describe() (names an element in messages).
// How a scene spells a kind (its mesh keys, its materials) is not here: that is the kind's scene reader in
// structure/scene/kinds/, registered beside it (docs/ARCHITECTURE.md "Adding an element kind").
// Kinds are registered by name in elementKinds() (ElementRegistry.cpp): the order there is the order of
// every loop over kinds (mass sums, field lists), so results do not depend on anything else.

#include <memory>
#include <optional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/model/FieldView.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

/// Element damping, the same for every kind: stiffness-proportional Rayleigh β [s] and the linear bulk
/// viscosity b1 (viscous stress b1 ρ c L_e times the strain rate, ρ and c the element's — scaled — density
/// and wave speed, so that the element's highest mode has the damping ratio b1 with or without mass scaling).
struct ElementDamping {
  double beta = 0;
  double bulkB1 = 0;
  bool enabled() const { return beta > 0 || bulkB1 > 0; }
};

/// Result of selective mass scaling over one kind.
struct ScaledMass {
  int elements = 0;    ///< elements whose density was raised
  double added = 0.0;  ///< added mass [kg]
};

/// The element with the largest strain measure of a kind, for instability messages.
struct StrainedElement {
  int element = -1;
  double strain = 0;  ///< non-finite when the element's state is
};

/// Buffers an element kind fills for one output frame; kept between frames (no allocation once sized).
struct ElementFieldBuffers {
  std::vector<std::vector<double>> arrays;
};

/// The element of a kind at a node with the smallest reference stable step (the stiffest for its mass).
struct LimitingElement {
  int element = -1;
  double stableDt = 0;  ///< reference L_e/c_e [s]
  double size = 0;      ///< its length (cables) [m]
};

class ElementKind {
 public:
  virtual ~ElementKind() = default;
  /// Registry name ("membrane", "cable"); also the name of its force effect in logs.
  virtual std::string name() const = 0;
  /// Its elements in the run log's model line, plural ("membrane triangles", "cables").
  virtual std::string label() const = 0;
  virtual int count(const Model& model) const = 0;
  /// "triangle 12 of mesh 'canopy'".
  virtual std::string describe(const Model& model, int element) const = 0;

  /// Builds the kind's own block from the meshes (called by buildModel for every kind, in registry order,
  /// once the nodes are numbered: model.meshes[m].node maps a mesh-local node): its elements, sorted as it
  /// likes, their reference geometry and constants; validates its materials and references (InputError
  /// naming the mesh, or the element through the model's describe functions). The lumped masses are summed
  /// after every kind is built.
  virtual void build(const std::vector<MeshInput>& inputs, const MaterialTable& materials,
                     Model& model) const = 0;

  /// The force effect over the kind's elements (references the model: create it once the model is in place);
  /// nullptr for a kind without internal forces (a point mass).
  virtual std::unique_ptr<Effect> makeForces(const Model& model, const ElementDamping& damping) const = 0;

  /// Adds the lumped physical mass of every element to `mass` (one per node).
  virtual void addLumpedMass(const Model& model, std::vector<double>& mass) const = 0;
  /// Smallest reference stable step L_e/c_e (no safety factor); +inf without elements.
  virtual double referenceStableDt(const Model& model) const = 0;
  /// Raises the density of every element whose reference step is below `need` just enough to reach it:
  /// adds the mass to model.nodes.mass and updates the kind's wave speeds (not invMassDof).
  virtual ScaledMass scaleMass(Model& model, double need) const = 0;

  /// Adds, per dof, the row sums Σ_j |K_ij| and the diagonal K_ii of the element tangent stiffness
  /// (material + geometric) at configuration x.
  virtual void addStiffnessBounds(const Model& model, const double* x, std::vector<double>& dofRow,
                                  std::vector<double>& dofDiag) const = 0;
  /// The stress-based fictitious mass ("proposal 1"), if the kind defines one: adds (λ/2)·bound to m and
  /// marks the nodes it covered; nodes no kind covers fall back to the Gerschgorin bound. Default: none.
  virtual void addStressBoundMass(const Model& /*model*/, const double* /*x*/, double /*lambda*/,
                                  std::vector<double>& /*m*/, std::vector<char>& /*covered*/) const {}

  /// The kind's cells in the results file (connectivity in model nodes); nullopt for a kind that writes
  /// none. A set is written to /mesh/<dataset> even when empty, its XDMF grid only when it has cells.
  virtual std::optional<CellSet> outputCells(const Model& /*model*/) const { return std::nullopt; }
  /// Names of the element fields this kind can write (the scene's output.fields entries).
  virtual std::vector<std::string> outputFields() const { return {}; }
  /// Appends views of the requested fields at configuration x; the data live in `buffers` until the next
  /// call.
  virtual void addFields(const Model& /*model*/, const double* /*x*/, const std::set<std::string>& /*wanted*/,
                         ElementFieldBuffers& /*buffers*/, std::vector<FieldView>& /*views*/) const {}
  /// Among the kind's elements at `node`, the one with the smallest reference stable step (for diagnoses:
  /// a short element makes its nodes stiff, heavy in dynamic relaxation, and limits the explicit step);
  /// nullopt if the kind has none there or does not report it.
  virtual std::optional<LimitingElement> limitingElementAt(const Model& /*model*/, int /*node*/) const {
    return std::nullopt;
  }
  /// Its characteristic quantities at configuration x for summary.json (e.g. the largest cable force),
  /// name and value; the count is reported by the caller. Default: none.
  virtual std::vector<std::pair<std::string, double>> report(const Model& /*model*/,
                                                             const double* /*x*/) const {
    return {};
  }
  /// The most strained element (or the first non-finite one); nullopt if the kind reports none.
  virtual std::optional<StrainedElement> mostStrained(const Model& /*model*/, const double* /*x*/) const {
    return std::nullopt;
  }
};

/// Every registered element kind, in registration order.
const std::vector<const ElementKind*>& elementKinds();
/// The kind registered under `name`, or nullptr.
const ElementKind* findElementKind(const std::string& name);

}  // namespace fsi::structure
