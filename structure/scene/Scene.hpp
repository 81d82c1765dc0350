#pragma once
// Scene: the run state built from a scene file (SceneSpec.hpp -> builders -> Scene): the model, its
// constraints, the effects, the probes and the run controls. Everything the run needs is here; nothing is
// looked up by name in the step loop.
//
// Top-level keys: title, materials, meshes, sets, constraints, effects, coupling, solver, time, output,
// probes. See docs/SCENES.md for the full reference.

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/effects/InterfacePressure.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/integrate/Constraints.hpp"
#include "structure/integrate/MassScaling.hpp"
#include "structure/model/Model.hpp"
#include "structure/probes/ProbeSpec.hpp"
#include "structure/scene/RunControls.hpp"

namespace fsi::structure {

struct Scene {
  std::filesystem::path file;
  std::string title;
  std::unique_ptr<Model> model;
  std::vector<std::unique_ptr<Effect>> effects;
  /// The `coupling:` section: the triangles that receive the flow's load. The scene builds no effect for it:
  /// the coupling participant owns the load and adds the InterfacePressure effect that reads it.
  struct CouplingInterface {
    std::vector<int> triangles;  ///< model node indices, 3 per triangle
    std::vector<int> nodes;      ///< interface nodes (model indices, ascending): the order of per-node values
    LoadInterpolation loadInWindow = LoadInterpolation::ConstantMean;
  };
  std::optional<CouplingInterface> couplingInterface;  ///< set when the scene declares `coupling`
  Constraints constraints;
  TimeControl time;
  SolverControl solver;
  OutputControl output;
  std::vector<ProbeSpec> probes;
  MassScalingReport massScaling;
  std::vector<std::string> enabledEffects;  ///< names, for the log and summary

  std::vector<const Effect*> effectList() const;
};

/// Reads, validates and resolves a scene. `overrides` are "key.path=value" assignments applied first.
/// Throws fsi::InputError naming file, line, key and the valid choices.
Scene loadScene(const std::filesystem::path& file, const std::vector<std::string>& overrides = {});

/// The same from YAML text (for tests); `name` stands in for the file name in messages and relative paths.
Scene loadSceneFromString(const std::string& yaml, const std::string& name,
                          const std::vector<std::string>& overrides = {});

}  // namespace fsi::structure
