// The membrane's scene keys: `material: NAME` (a membrane material) for the mesh's triangles.
#include "structure/scene/ReadMaterials.hpp"
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

}  // namespace

KindReader membraneReader() {
  return {"membrane", {"material"}, nullptr, read, check};
}

}  // namespace fsi::structure
