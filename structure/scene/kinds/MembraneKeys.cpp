// The membrane's scene keys: `material: NAME` (a membrane material) for the mesh's triangles.
#include "structure/scene/ReadMaterials.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/YamlAccess.hpp"
#include "structure/scene/kinds/KindReaders.hpp"

namespace fsi::structure {

namespace {

void read(const YamlMap& entry, const MaterialTable& materials, MeshInput& in) {
  if (entry.has("material"))
    in.membraneMaterial = materialRef(entry, "material", materialsOfKind(materials, "membrane"), "membrane");
}

void check(const YamlMap& entry, const MeshInput& in) {
  if (!in.mesh.triangles.empty() && in.membraneMaterial < 0)
    entry.fail("this mesh has triangles: give it a membrane 'material'");
}

const SchemaSection& schema() {
  static const SchemaSection s{"meshes.NAME (membrane)",
                               "the membrane's keys of a mesh entry",
                               {{"material",
                                 KeyType::String,
                                 "",
                                 "",
                                 "required with triangles",
                                 {},
                                 {},
                                 {},
                                 "a `type: membrane` material for the mesh's triangles"}}};
  return s;
}

}  // namespace

KindReader membraneReader() {
  return {"membrane", &schema(), nullptr, read, check};
}

}  // namespace fsi::structure
