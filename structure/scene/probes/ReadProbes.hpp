#pragma once
// How a scene spells its probes: the `probes:` section and one reader per probe kind (ReadNodeProbes.cpp,
// ReadSurfaceProbes.cpp), registered in ReadProbes.cpp under the name of the probe kind it fills
// (structure/probes/ProbeKinds: what the probe computes). Each reader has its schema section (SceneSchema):
// its keys, their types, defaults and choices, read through a SchemaMap; selectors resolve through the
// scene's sets, and a reader checks at load time what its kind needs of them.

#include <string>
#include <vector>

#include "structure/probes/ProbeSpec.hpp"
#include "structure/scene/SceneSchema.hpp"
#include "structure/scene/SetResolver.hpp"

namespace fsi::structure {

struct ProbeReader {
  std::string kind;             ///< the probe's `type:`: a name of probeKinds()
  const SchemaSection* schema;  ///< the entry's keys (with `type`)
  /// Reads the entry (calling p.finish()) into `spec`; selectors resolve through `sets`.
  void (*read)(const SchemaMap& p, const SetResolver& sets, ProbeSpec& spec) = nullptr;
};

/// Every probe reader, in the order of probeKinds() (one per kind: checked on first use).
const std::vector<ProbeReader>& probeReaders();

/// Reads the `probes:` section of the top-level map `top`.
std::vector<ProbeSpec> readProbes(const YamlMap& top, const SetResolver& sets);

// For the readers.

/// `component:` of a probe entry (a Choice key of its section: x, y, z, magnitude, radial).
ProbeComponent readComponent(const SchemaMap& entry);
/// `reduce:` of a probe entry (a Choice key of its section: value, mean, max, min, sum).
ProbeReduce readReduce(const SchemaMap& entry);

/// The keys most probes share, for their sections: the `type` naming `kind`, a required selector, a
/// `component` among `components`, a `reduce` among `reductions` defaulting to `fallback`.
SceneKey probeTypeKey(const std::string& kind);
/// The description of the probe kind `kind` (for its section).
std::string findProbeKindDescription(const std::string& kind);
SceneKey selectorKey(const std::string& name, const std::string& what);
SceneKey componentKey(std::vector<std::string> components);
SceneKey reduceKey(std::vector<std::string> reductions, const std::string& fallback);

// The readers, one per kind (ReadNodeProbes.cpp, ReadSurfaceProbes.cpp).
ProbeReader displacementReader();
ProbeReader positionReader();
ProbeReader reactionReader();
ProbeReader appliedLoadReader();
ProbeReader reactionMomentReader();
ProbeReader pitchAngleReader();
ProbeReader equilibriumReader();
ProbeReader volumeReader();
ProbeReader stressReader();
ProbeReader lineTensionReader();
ProbeReader laplaceReader();
ProbeReader foldsReader();
ProbeReader projectedDiameterReader();

}  // namespace fsi::structure
