#pragma once
// The registry of the scene's `effects:`: every effect kind is one entry {name, keys, description, build}.
// The valid names under `effects:` (and their "did you mean") come from this table, and each entry's keys
// from its own file. Adding an effect = one file with its build function + one registration in
// EffectRegistry.cpp (docs/ARCHITECTURE.md, "How to add an effect"). Building runs once, at load time: no
// per-step cost.

#include <filesystem>
#include <memory>
#include <string>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/effects/TimeFunction.hpp"
#include "structure/elements/ElementKind.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/model/Model.hpp"
#include "structure/model/SchemaKey.hpp"
#include "structure/scene/SetResolver.hpp"
#include "structure/scene/YamlAccess.hpp"

namespace fsi::structure {

// ElementDamping (stiffness-proportional β, bulk viscosity b1): structure/elements/ElementKind.hpp; the
// damping effects only set it, the element kinds' forces are built with it.

/// What an effect's build function may read and add to.
struct EffectContext {
  Model& model;
  const SetResolver& sets;
  CentralDifferenceSettings& integrator;        ///< mass damping lives in the integrator
  ElementDamping& elementDamping;               ///< read by the element forces
  std::vector<std::unique_ptr<Effect>>& loads;  ///< effects that add forces, in build order
  std::filesystem::path sceneDir{};  ///< the scene file's folder: files an entry names are relative to it
};

struct EffectKind {
  std::string name;                ///< the key under `effects:`
  std::vector<std::string> keys;   ///< the keys of one entry
  std::string description;         ///< one line, for docs and messages
  bool several = false;            ///< the value may be a list of entries (pressure on several sets, ...)
  std::string relaxationConflict;  ///< non-empty: refused in a dynamic-relaxation scene, with this reason
  /// Reads one entry (calling entry.finish(keys)) and adds what it makes to the context.
  void (*build)(const YamlMap& entry, EffectContext& ctx) = nullptr;
  /// The entry's declared keys (SceneSchema), when the kind has them; `keys` are then its names (the
  /// coupling library's `pressure_field` declares its own, and is in sceneSchema() once registered).
  const SchemaSection* schema = nullptr;
};

/// Adds a pressure per triangle (values along the normal, times fn(t)) as a follower load, or as a dead load
/// from the reference geometry; labelled with the entry's triangle selector. Shared by the pressure tables
/// and the pressure fields mapped from files.
void addTrianglePressure(const YamlMap& entry, EffectContext& ctx, std::vector<int> conn,
                         std::vector<double> values, const TimeFunction& fn, bool follower);

/// Every effect kind, in the order they are built (which fixes the order forces are summed in): the built-in
/// kinds of EffectRegistry.cpp, then those added with registerEffectKind in the order they were added.
const std::vector<EffectKind>& effectKinds();

/// The extension point for effects built from code above the structure library (the dependency direction is
/// structure <- coupling <- adapter/apps, so an effect that needs the coupling library's projection cannot be
/// in the built-in table): appends `kind` after the built-in kinds, so every scene loaded afterwards accepts
/// it, lists it among the valid names and suggests it. Called once at start-up, before any scene is loaded
/// and not concurrently with loading (e.g. fsi::coupling::registerCouplingEffects() from `fsi` and the
/// adapter). Registering the same name again with the same build function does nothing; with another one
/// it throws std::logic_error (two kinds may not share a name).
void registerEffectKind(const EffectKind& kind);

/// Builds the `effects:` section of the top-level map `top`; appends the names of the effects built to
/// `enabled`.
void buildEffects(const YamlMap& top, bool relaxation, EffectContext& ctx, std::vector<std::string>& enabled);

}  // namespace fsi::structure
