#include "structure/scene/probes/ReadProbes.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <stdexcept>

#include "structure/probes/ProbeKinds.hpp"

namespace fsi::structure {

const std::vector<ProbeReader>& probeReaders() {
  // One line per probe kind, in the order of probeKinds() (ProbeRegistry.cpp).
  static const std::vector<ProbeReader> readers = [] {
    std::vector<ProbeReader> r{displacementReader(),     positionReader(),   reactionReader(),
                               volumeReader(),           stressReader(),     lineTensionReader(),
                               reactionMomentReader(),   pitchAngleReader(), appliedLoadReader(),
                               equilibriumReader(),      laplaceReader(),    foldsReader(),
                               projectedDiameterReader()};
    // What a probe computes and how a scene spells it are registered apart: one reader per kind.
    for (const ProbeKind& k : probeKinds())
      if (std::none_of(r.begin(), r.end(), [&](const ProbeReader& x) { return x.kind == k.name; }))
        throw std::logic_error("probe kind '" + k.name +
                               "' has no scene reader (scene/probes/ReadProbes.cpp)");
    for (const ProbeReader& x : r)
      if (!findProbeKind(x.kind))
        throw std::logic_error("probe reader '" + x.kind + "' has no probe kind (probes/ProbeRegistry.cpp)");
    return r;
  }();
  return readers;
}

std::string findProbeKindDescription(const std::string& kind) {
  const ProbeKind* k = findProbeKind(kind);
  if (!k) throw std::logic_error("probe reader '" + kind + "' has no probe kind (probes/ProbeRegistry.cpp)");
  return k->description;
}

SceneKey probeTypeKey(const std::string& kind) {
  return {"type", KeyType::Choice, "", "", "required", {}, {}, {kind}, "the probe kind"};
}

SceneKey selectorKey(const std::string& name, const std::string& what) {
  return {name, KeyType::Selector, "", "", "required", {}, {}, {}, what};
}

SceneKey componentKey(std::vector<std::string> components) {
  return {"component",           KeyType::Choice,         "", "", "required", {}, {},
          std::move(components), "the component reported"};
}

SceneKey reduceKey(std::vector<std::string> reductions, const std::string& fallback) {
  return {"reduce",
          KeyType::Choice,
          "",
          fallback,
          "",
          {},
          {},
          std::move(reductions),
          "how the values of several nodes or triangles become one number"};
}

ProbeComponent readComponent(const SchemaMap& entry) {
  static const std::vector<std::pair<std::string, ProbeComponent>> names{
      {"x", ProbeComponent::X},
      {"y", ProbeComponent::Y},
      {"z", ProbeComponent::Z},
      {"magnitude", ProbeComponent::Magnitude},
      {"radial", ProbeComponent::Radial}};
  const std::string c = entry.string("component");
  for (const auto& [name, value] : names)
    if (name == c) return value;
  throw std::logic_error("probe component '" + c + "' is not a component");  // the choices are checked
}

ProbeReduce readReduce(const SchemaMap& entry) {
  static const std::vector<std::pair<std::string, ProbeReduce>> names{{"value", ProbeReduce::Value},
                                                                      {"mean", ProbeReduce::Mean},
                                                                      {"max", ProbeReduce::Max},
                                                                      {"min", ProbeReduce::Min},
                                                                      {"sum", ProbeReduce::Sum}};
  const std::string r = entry.string("reduce");
  for (const auto& [name, value] : names)
    if (name == r) return value;
  throw std::logic_error("probe reduction '" + r + "' is not a reduction");  // the choices are checked
}

std::vector<ProbeSpec> readProbes(const YamlMap& top, const SetResolver& sets) {
  std::vector<ProbeSpec> probes;
  if (!top.has("probes")) return probes;
  std::vector<std::string> types;
  for (const ProbeReader& r : probeReaders()) types.push_back(r.kind);
  YamlMap ps = top.map("probes");
  for (const auto& name : ps.keys()) {
    // The name becomes a column of /tables/probes in results.h5 (next to 'time') and a key of summary.json.
    if (name.empty() || name == "." || name == "time" || name.find('/') != std::string::npos ||
        std::any_of(name.begin(), name.end(), [](char ch) { return (ch >= 0 && ch < 0x20) || ch == 0x7F; }))
      ps.failAt(name, fmt::format("'{}' cannot name a probe: it must be non-empty, not 'time' or '.', and "
                                  "without '/' or control characters",
                                  name));
    YamlMap p = ps.map(name);
    ProbeSpec spec;
    spec.name = name;
    const std::string type = p.choice("type", types);
    spec.kind = findProbeKind(type);
    for (const ProbeReader& r : probeReaders())
      if (r.kind == type) r.read(SchemaMap(p, *r.schema), sets, spec);
    probes.push_back(std::move(spec));
  }
  return probes;
}

}  // namespace fsi::structure
