#include "structure/scene/MeshSources.hpp"

#include "structure/io/GmshReader.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/GeneratorKinds.hpp"

namespace fsi::structure {

MeshData meshFromScene(const YamlMap& entry, const std::string& name, const std::filesystem::path& sceneDir) {
  const bool hasFile = entry.has("file"), hasGen = entry.has("generator");
  if (hasFile == hasGen) entry.fail("a mesh needs exactly one of 'file' (Gmsh .msh) or 'generator'");
  if (hasFile) {
    const std::filesystem::path f = sceneDir / entry.string("file");
    try {
      return readGmsh(f, name);
    } catch (const InputError& e) {
      throw InputError(locate(entry.file(), entry.raw("file"), entry.childPath("file")) + ": " + e.what());
    }
  }
  return generateMesh(entry.map("generator"), name);
}

}  // namespace fsi::structure
