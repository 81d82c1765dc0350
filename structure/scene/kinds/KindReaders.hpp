#pragma once
// The element kinds' scene readers: how a scene's mesh entry spells each element kind (its keys, its
// material references, which of the mesh's cells are its own), split from what the kind computes
// (structure/elements: the kinds read no YAML). One reader per kind, in its own file beside the others here,
// registered by one line in kindReaders() (KindReaderRegistry.cpp); readMeshes (ReadMeshes.cpp) accepts the
// keys of every reader and calls them in three passes over a mesh entry:
//   claim  a kind takes the cells the entry gives it out of the mesh into MeshInput::kindInputs (e.g. the
//          bars' line groups), before any kind reads: what no kind claimed stays with the defaults, the
//          triangles the membranes' and the lines the cables';
//   read   the kind's keys into the MeshInput (material indices, its kindInputs);
//   check  once the entry's keys are known to be valid: a mesh with cells of the kind but no material for
//          them is an error located at the entry.
// Each reader declares its keys in a schema section (path "meshes.NAME (KIND)"); meshEntrySchema() lists
// them after `file` and `generator`, so the valid keys, the docs and the readers' keys are one table.

#include <string>
#include <vector>

#include "structure/model/Materials.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

class YamlMap;
struct SchemaSection;

struct KindReader {
  std::string kind;             ///< the element kind it reads for (ElementKind::name())
  const SchemaSection* schema;  ///< its keys of a mesh entry (types, defaults, descriptions; SceneSchema)
  /// Takes the kind's cells out of the mesh (may be null: the kind claims nothing).
  void (*claim)(const YamlMap& entry, const MaterialTable& materials, MeshInput& in);
  /// Reads the kind's keys into `in` (errors located at the key; may be null).
  void (*read)(const YamlMap& entry, const MaterialTable& materials, MeshInput& in);
  /// Rejects cells of the kind without a material (located at the entry; may be null).
  void (*check)(const YamlMap& entry, const MeshInput& in);
};

/// Every registered kind reader, in registration order.
const std::vector<KindReader>& kindReaders();

}  // namespace fsi::structure
