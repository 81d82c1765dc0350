#include <fmt/format.h>

#include <stdexcept>

#include "structure/scene/effects/EffectKinds.hpp"

namespace fsi::structure {

// The entries, one per effect file. Register a new effect here: its function below and in the table.
EffectKind massDampingEffect();
EffectKind stiffnessDampingEffect();
EffectKind bulkViscosityEffect();
EffectKind gravityEffect();
EffectKind pressureEffect();
EffectKind nodalForcesEffect();
EffectKind chordwisePressureEffect();  // PressureTableEffect.cpp
EffectKind lineDragEffect();           // DragEffects.cpp
EffectKind bodyDragEffect();           // DragEffects.cpp
EffectKind bendingEffect();            // BendingEffect.cpp
EffectKind impactPressureEffect();     // ImpactPressureEffect.cpp
EffectKind canopyPressureEffect();     // CanopyPressureEffect.cpp

namespace {

// The table: the built-in kinds first, then the registered ones (registerEffectKind).
std::vector<EffectKind>& table() {
  static std::vector<EffectKind> kinds{
      massDampingEffect(), stiffnessDampingEffect(), bulkViscosityEffect(),     gravityEffect(),
      pressureEffect(),    nodalForcesEffect(),      chordwisePressureEffect(), lineDragEffect(),
      bodyDragEffect(),    bendingEffect(),          impactPressureEffect(),    canopyPressureEffect()};
  return kinds;
}

}  // namespace

const std::vector<EffectKind>& effectKinds() {
  return table();
}

void registerEffectKind(const EffectKind& kind) {
  if (kind.name.empty() || kind.build == nullptr)
    throw std::logic_error("registerEffectKind: an effect kind needs a name and a build function");
  for (const EffectKind& k : table())
    if (k.name == kind.name) {
      if (k.build == kind.build) return;
      throw std::logic_error(
          fmt::format("registerEffectKind: an effect kind '{}' exists already", kind.name));
    }
  table().push_back(kind);
}

namespace {

// An effect that may be given several times takes one entry or a list of them.
std::vector<YamlMap> entriesOf(const YamlMap& fx, const std::string& key) {
  const YAML::Node n = fx.raw(key);
  std::vector<YamlMap> out;
  if (n.IsSequence()) {
    for (std::size_t i = 0; i < n.size(); ++i)
      out.emplace_back(n[i], fx.file(), fmt::format("{}[{}]", fx.childPath(key), i));
  } else {
    out.emplace_back(n, fx.file(), fx.childPath(key));
  }
  return out;
}

}  // namespace

void buildEffects(const YamlMap& top, bool relaxation, EffectContext& ctx,
                  std::vector<std::string>& enabled) {
  if (!top.has("effects")) return;
  YamlMap fx = top.map("effects");
  const auto& kinds = effectKinds();
  if (relaxation)
    for (const EffectKind& k : kinds)
      if (!k.relaxationConflict.empty() && fx.has(k.name)) fx.failAt(k.name, k.relaxationConflict);
  std::vector<std::string> names;
  for (const EffectKind& k : kinds) {
    names.push_back(k.name);
    if (!fx.has(k.name)) continue;
    if (k.several) {
      for (const YamlMap& e : entriesOf(fx, k.name)) k.build(e, ctx);
    } else {
      k.build(fx.map(k.name), ctx);
    }
    enabled.push_back(k.name);
  }
  fx.finish(names);
}

}  // namespace fsi::structure
