#pragma once
// Scene: a case as read from its YAML file, validated and resolved against the built Model.
// Everything the run needs is here; nothing is looked up by name in the step loop.
//
// Top-level keys: title, materials, meshes, sets, constraints, effects, solver, time, output, probes.
// See docs/SCENES.md for the full reference.

#include <array>
#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "structure/effects/CableForces.hpp"
#include "structure/effects/Effect.hpp"
#include "structure/effects/InterfacePressure.hpp"
#include "structure/effects/MembraneForces.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/integrate/Constraints.hpp"
#include "structure/integrate/DynamicRelaxation.hpp"
#include "structure/integrate/MassScaling.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

struct ProbeSpec {
  enum class Type { Displacement, Position, Reaction, Volume, Stress };
  enum class Reduce { Value, Mean, Max, Min, Sum };
  std::string name;
  Type type = Type::Displacement;
  Reduce reduce = Reduce::Value;
  std::vector<int> nodes;      ///< model node indices
  std::vector<int> triangles;  ///< model membrane element indices
  int component = 0;           ///< 0,1,2 = x,y,z; 3 = magnitude; 4 = radial (from `center`)
  std::array<double, 3> center{0, 0, 0};
  std::string quantity;  ///< stress probes: max_principal | min_principal
};

struct TimeControl {
  double endTime = 0;  ///< simulated end time (or the cap for until-static runs)
  bool untilStatic = false;
  double staticTolerance = 1e-8;  ///< stop when KE/strain energy stays below this
  long monitorEvery = 100;        ///< steps between energy checks
  double energyTolerance = 0.05;  ///< relative energy-balance error that counts as instability
  double massScalingMinDt = 0;    ///< > 0: selective mass scaling to this step
  CentralDifferenceSettings integrator;
};

/// Which integrator a scene runs: explicit dynamics (default) or dynamic relaxation to a static state.
struct SolverControl {
  enum class Type { ExplicitDynamics, DynamicRelaxation };
  Type type = Type::ExplicitDynamics;
  RelaxationSettings relaxation;
  std::string method;  ///< label of the DR variant (KDR, KDR1, oDR, mdDR, ...)
};

struct OutputControl {
  double interval = 0;  ///< simulated time between frames; 0 = first and last only
  std::set<std::string> fields;
};

struct Scene {
  std::filesystem::path file;
  std::string title;
  std::unique_ptr<Model> model;
  std::vector<std::unique_ptr<Effect>> effects;
  const MembraneForces* membrane = nullptr;  ///< owned by `effects`; null without triangles
  const CableForces* cable = nullptr;
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

inline const std::vector<std::string>& allOutputFields() {
  static const std::vector<std::string> f{"displacement",     "velocity",      "residual",   "stress",
                                          "principal_stress", "wrinkle_state", "cable_force"};
  return f;
}

}  // namespace fsi::structure
