// The scene readers of the probes on node sets: displacement, position, reaction, applied_load,
// reaction_moment, pitch_angle, equilibrium_error (what they compute: structure/probes/).
#include <fmt/format.h>

#include "structure/scene/probes/ReadProbes.hpp"

namespace fsi::structure {

namespace {

// displacement, position: a component of a node's (or reduced over nodes).
SchemaSection nodeValueSchema(const std::string& kind) {
  return {"probes.NAME (type: " + kind + ")",
          findProbeKindDescription(kind),
          {probeTypeKey(kind),
           selectorKey("nodes", "the node (or nodes, with a reduction)"),
           componentKey({"x", "y", "z", "magnitude", "radial"}),
           {"center", KeyType::Vec3, "m", "[0, 0, 0]", "", {}, {}, {}, "the centre of `component: radial`"},
           reduceKey({"value", "mean", "max", "min"}, "value")}};
}

void readNodeValue(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.nodes = sets.nodes(p.map().required("nodes"), p.map().childPath("nodes"));
  spec.component = readComponent(p);
  spec.center = p.vec3("center");
  spec.reduce = readReduce(p);
  if (spec.reduce == ProbeReduce::Value && spec.nodes.size() != 1)
    p.map().failAt("nodes",
                   fmt::format("selects {} nodes; 'reduce: value' needs exactly one (use nearest, or "
                               "reduce: mean | max | min)",
                               spec.nodes.size()));
  p.finish();
}

// reaction, applied_load: a component of a force summed over nodes.
SchemaSection nodeSumSchema(const std::string& kind) {
  return {"probes.NAME (type: " + kind + ")",
          findProbeKindDescription(kind),
          {probeTypeKey(kind), selectorKey("nodes", "the nodes summed over"),
           componentKey({"x", "y", "z", "magnitude"})}};
}

void readNodeSum(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.reduce = ProbeReduce::Sum;
  spec.nodes = sets.nodes(p.map().required("nodes"), p.map().childPath("nodes"));
  spec.component = readComponent(p);
  p.finish();
}

void readReactionMoment(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  const YamlMap& m = p.map();
  spec.reduce = ProbeReduce::Sum;
  spec.nodes = sets.nodes(m.required("nodes"), m.childPath("nodes"));
  const YAML::Node about = m.raw("about");
  if (about && about.IsScalar()) {
    // A node set: its one node's reference position (the anchor is held, so reference = current).
    const std::vector<int> one = sets.nodes(about, m.childPath("about"));
    if (one.size() != 1)
      m.failAt("about", "'" + about.as<std::string>() + "' has " + std::to_string(one.size()) +
                            " nodes; the moment's point is one node or [x, y, z]");
    const Nodes& N = sets.model().nodes;
    for (int k = 0; k < 3; ++k) spec.center[k] = N.X[3 * one[0] + k];
  } else {
    spec.center = m.vec3("about", {0, 0, 0});
  }
  spec.component = readComponent(p);
  p.finish();
}

void readPitchAngle(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.reduce = ProbeReduce::Value;
  spec.nodes = sets.nodes(p.map().required("from"), p.map().childPath("from"));
  spec.nodesTo = sets.nodes(p.map().required("to"), p.map().childPath("to"));
  p.finish();
}

void readEquilibrium(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) {
  spec.reduce = ProbeReduce::Value;
  spec.nodes = sets.nodes(p.map().required("supports"), p.map().childPath("supports"));
  p.finish();
}

}  // namespace

ProbeReader displacementReader() {
  static const SchemaSection s = nodeValueSchema("displacement");
  return {"displacement", &s, readNodeValue};
}

ProbeReader positionReader() {
  static const SchemaSection s = nodeValueSchema("position");
  return {"position", &s, readNodeValue};
}

ProbeReader reactionReader() {
  static const SchemaSection s = nodeSumSchema("reaction");
  return {"reaction", &s, readNodeSum};
}

ProbeReader appliedLoadReader() {
  static const SchemaSection s = nodeSumSchema("applied_load");
  return {"applied_load", &s, readNodeSum};
}

ProbeReader reactionMomentReader() {
  static const SchemaSection s{
      "probes.NAME (type: reaction_moment)",
      findProbeKindDescription("reaction_moment"),
      {probeTypeKey("reaction_moment"),
       selectorKey("nodes", "the nodes whose reactions turn"),
       {"about",
        KeyType::Any,
        "m",
        "[0, 0, 0]",
        "",
        {},
        {},
        {},
        "the moment's point: [x, y, z], or a node set of one node (its reference position)"},
       componentKey({"x", "y", "z", "magnitude"})}};
  return {"reaction_moment", &s, readReactionMoment};
}

ProbeReader pitchAngleReader() {
  static const SchemaSection s{"probes.NAME (type: pitch_angle)",
                               findProbeKindDescription("pitch_angle"),
                               {probeTypeKey("pitch_angle"), selectorKey("from", "the leading edge's nodes"),
                                selectorKey("to", "the trailing edge's nodes")}};
  return {"pitch_angle", &s, readPitchAngle};
}

ProbeReader equilibriumReader() {
  static const SchemaSection s{
      "probes.NAME (type: equilibrium_error)",
      findProbeKindDescription("equilibrium_error"),
      {probeTypeKey("equilibrium_error"), selectorKey("supports", "the supported nodes")}};
  return {"equilibrium_error", &s, readEquilibrium};
}

}  // namespace fsi::structure
