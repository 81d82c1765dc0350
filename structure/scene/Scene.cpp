#include "structure/scene/Scene.hpp"

#include <fmt/format.h>

#include <fstream>
#include <sstream>

#include "structure/elements/ElementKind.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/BuildConstraints.hpp"
#include "structure/scene/ReadControls.hpp"
#include "structure/scene/ReadCoupling.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/SceneSpec.hpp"
#include "structure/scene/SetResolver.hpp"
#include "structure/scene/YamlAccess.hpp"
#include "structure/scene/effects/EffectKinds.hpp"
#include "structure/scene/probes/ReadProbes.hpp"

namespace fsi::structure {

std::vector<const Effect*> Scene::effectList() const {
  std::vector<const Effect*> list;
  for (const auto& e : effects) list.push_back(e.get());
  return list;
}

namespace {

const std::vector<std::string>& topLevelKeys() {
  static const std::vector<std::string> keys = topLevelSchema().names();
  return keys;
}

// An unknown top-level key is reported before anything else is read: a misspelt section (`couplng:`) would
// otherwise surface as a confusing error elsewhere (a missing `time:`) before its own "did you mean".
void checkTopLevelKeys(const YAML::Node& root, const std::string& fileName) {
  YamlMap check(root, fileName, "");
  for (const auto& k : topLevelKeys())
    if (check.has(k)) check.raw(k);
  check.finish(topLevelKeys());
}

// ---------------------------------------------------------------- spec: what the file says, validated
SceneSpec readSceneSpec(const YamlMap& top, const std::string& fileName, const std::filesystem::path& dir) {
  SceneSpec spec;
  spec.file = fileName;
  spec.dir = dir;
  spec.title = top.string("title", "");
  spec.materials = readSceneMaterials(top);
  spec.meshes = readMeshes(top, spec.materials, dir);
  spec.solver = readSolver(top);
  spec.time = readTime(top, spec.relaxation());
  spec.time.integrator.threads = spec.solver.threads;
  spec.output = readOutput(top);
  return spec;
}

// Element forces: one effect per element kind the model has (structure/elements registry), in registry order,
// ahead of the loads, with the damping the `effects:` section asked for.
void addElementForces(Scene& scene, const ElementDamping& damping) {
  const Model& model = *scene.model;
  for (const ElementKind* kind : elementKinds())
    if (kind->count(model) > 0)
      if (std::unique_ptr<Effect> forces = kind->makeForces(model, damping)) {
        scene.effects.push_back(std::move(forces));
        scene.enabledEffects.insert(scene.enabledEffects.begin(), kind->name());
      }
}

// ---------------------------------------------------------------- builders: spec -> run state
Scene buildScene(const YamlMap& top, SceneSpec spec) {
  Scene scene;
  scene.file = spec.file;
  scene.title = spec.title;
  scene.solver = spec.solver;
  scene.time = spec.time;
  scene.output = spec.output;
  scene.model = std::make_unique<Model>(buildSceneModel(std::move(spec.meshes), spec.materials, spec.file));
  Model& model = *scene.model;

  // Mass scaling must precede the effects, which cache wave speeds.
  if (scene.time.massScalingMinDt > 0)
    scene.massScaling = applyMassScaling(model, scene.time.massScalingMinDt, scene.time.integrator.safety);

  SetResolver sets(model, spec.file);
  defineSets(top, model, sets);
  scene.constraints = buildConstraints(top, model, sets);

  // Effects: only what is listed is ever computed. The element forces come first, then the loads.
  ElementDamping damping;
  std::vector<std::unique_ptr<Effect>> loads;
  EffectContext effects{model, sets, scene.time.integrator, damping, loads, spec.dir};
  buildEffects(top, spec.relaxation(), effects, scene.enabledEffects);
  addElementForces(scene, damping);
  for (auto& l : loads) scene.effects.push_back(std::move(l));

  readCoupling(top, sets, scene);
  scene.probes = readProbes(top, sets);
  top.finish(topLevelKeys());
  return scene;
}

Scene loadRoot(YAML::Node root, const std::string& fileName, const std::filesystem::path& dir) {
  checkTopLevelKeys(root, fileName);
  YamlMap top(root, fileName, "");
  SceneSpec spec = readSceneSpec(top, fileName, dir);
  return buildScene(top, std::move(spec));
}

}  // namespace

Scene loadSceneFromString(const std::string& yaml, const std::string& name,
                          const std::vector<std::string>& overrides) {
  requireUtf8Text(yaml, name);
  YAML::Node root = parseDocument(yaml, name);
  for (const auto& o : overrides) applyOverride(root, o);
  checkDocument(root, name);  // after the overrides, so that their values are checked too
  return loadRoot(root, name, std::filesystem::path(name).parent_path());
}

Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides) {
  std::error_code ec;
  if (std::filesystem::is_directory(file, ec))
    throw InputError(fmt::format("{}: is a directory, not a scene file", file.string()));
  std::ifstream in(file);
  if (!in) throw InputError(fmt::format("{}: cannot open scene file", file.string()));
  std::stringstream ss;
  ss << in.rdbuf();
  if (in.bad()) throw InputError(fmt::format("{}: cannot read scene file", file.string()));
  return loadSceneFromString(ss.str(), file.string(), overrides);
}

}  // namespace fsi::structure
