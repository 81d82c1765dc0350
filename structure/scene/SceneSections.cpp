// The schema sections of the scene's top level and mesh entries, and the list of every section
// (sceneSchema(), in the order of docs/SCENES.md's key reference).

#include "structure/elements/ElementKind.hpp"
#include "structure/model/MaterialKeys.hpp"
#include "structure/scene/BuildConstraints.hpp"
#include "structure/scene/ExtrudeTies.hpp"
#include "structure/scene/GeneratorKinds.hpp"
#include "structure/scene/MaterialTypes.hpp"
#include "structure/scene/ReadControls.hpp"
#include "structure/scene/ReadCoupling.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/SelectorSchema.hpp"
#include "structure/scene/effects/EffectKinds.hpp"
#include "structure/scene/kinds/KindReaders.hpp"
#include "structure/scene/probes/ReadProbes.hpp"

namespace fsi::structure {

const SchemaSection& topLevelSchema() {
  using T = KeyType;
  static const SchemaSection s{
      "(top level)",
      "the sections of a scene file",
      {{"title",
        T::String,
        "",
        "",
        "empty",
        {},
        {},
        {},
        "free text, printed in the log and stored in summary.json"},
       {"materials",
        T::Map,
        "",
        "",
        "required",
        {},
        {},
        {},
        "membrane, cable and point-mass materials, by name"},
       {"meshes",
        T::Map,
        "",
        "",
        "required",
        {},
        {},
        {},
        "Gmsh files or generated meshes, by name (at least one)"},
       {"sets", T::Map, "", "", "", {}, {}, {}, "named selections"},
       {"constraints",
        T::Any,
        "",
        "",
        "",
        {},
        {},
        {},
        "a list of fix / symmetry / prescribe / extrude entries"},
       {"effects", T::Map, "", "", "", {}, {}, {}, "loads and damping, by effect type"},
       {"coupling", T::Map, "", "", "", {}, {}, {}, "the interface a flow solver loads"},
       {"solver", T::Map, "", "", "explicit dynamics", {}, {}, {}, "explicit dynamics or dynamic relaxation"},
       {"time",
        T::Map,
        "",
        "",
        "",
        {},
        {},
        {},
        "end time or until-static, step control (explicit dynamics; none with dynamic relaxation)"},
       {"output",
        T::Map,
        "",
        "",
        "first and last frame, all fields",
        {},
        {},
        {},
        "frame interval and fields"},
       {"probes", T::Map, "", "", "", {}, {}, {}, "scalar results, by name"}}};
  return s;
}

const SchemaSection& meshEntrySchema() {
  // Where the mesh comes from, then every element kind's own keys (its cells and material references), in
  // the order of the kinds' scene readers (scene/kinds): each reader declares them in its section and reads
  // and checks them (KindReader::claim/read/check).
  static const SchemaSection s = [] {
    SchemaSection m{"meshes.NAME",
                    "one mesh: from a Gmsh file or a generator, with its element kinds' materials",
                    {{"file",
                      KeyType::String,
                      "",
                      "",
                      "",
                      {},
                      {},
                      {},
                      "Gmsh .msh file, relative to the scene's folder (exactly one of file and generator)"},
                     {"generator",
                      KeyType::Map,
                      "",
                      "",
                      "",
                      {},
                      {},
                      {},
                      "a built-in parametric mesh: `type:` and its keys"}}};
    for (const KindReader& r : kindReaders())
      for (const SceneKey& key : r.schema->keys) m.keys.push_back(key);
    return m;
  }();
  return s;
}

std::vector<const SchemaSection*> sceneSchema() {
  std::vector<const SchemaSection*> all{&topLevelSchema()};
  for (const MaterialType& t : materialTypes()) all.push_back(t.schema);
  all.push_back(&meshEntrySchema());
  for (const GeneratorKind& g : generatorKinds())
    if (g.schema) all.push_back(g.schema);
  all.push_back(&setsSchema());
  all.push_back(&planeSelectorSchema());
  all.push_back(&boxSelectorSchema());
  all.push_back(&nearestSelectorSchema());
  all.push_back(&idsSelectorSchema());
  all.push_back(&fixSchema());
  all.push_back(&symmetrySchema());
  all.push_back(&prescribeSchema());
  all.push_back(&extrudeSchema());
  for (const EffectKind& e : effectKinds())
    if (e.schema) all.push_back(e.schema);
  all.push_back(&couplingSchema());
  all.push_back(&solverSchema());
  all.push_back(&relaxationSchema());
  all.push_back(&timeSchema());
  all.push_back(&untilStaticSchema());
  all.push_back(&outputSchema());
  for (const ProbeReader& r : probeReaders()) all.push_back(r.schema);
  for (const SchemaSection* f : timeFunctionSchemas()) all.push_back(f);
  return all;
}

}  // namespace fsi::structure
