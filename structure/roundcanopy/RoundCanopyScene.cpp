#include "structure/roundcanopy/RoundCanopyScene.hpp"

#include "structure/scene/GeneratorKinds.hpp"

namespace fsi::structure::roundcanopy {

namespace {}  // namespace

const SchemaSection& roundCanopySchema() {
  // Ranges that depend on other keys (the vent at most half the canopy, lines long enough to reach the axis,
  // the mesh size) are designRoundCanopy's checks, located at the entry.
  using T = KeyType;
  static const SchemaSection s{
      "meshes.NAME.generator (round_canopy)",
      "gored round parachute: vent, radial/skirt/vent tapes, suspension lines, riser (docs/ROUND_CANOPY.md)",
      {
          {"type", T::Choice, "", "", "required", {}, {}, {"round_canopy"}, "the generator"},
          {"shape",
           T::Choice,
           "",
           "flat",
           "",
           {},
           {},
           {"flat", "conical", "hemispherical"},
           "the radials' profile: flat circular, a cone, a quarter circle"},
          {"nominal_diameter",
           T::Number,
           "m",
           "1.0",
           "",
           excl(0),
           incl(kMaxNominalDiameter),
           {},
           "D0 = sqrt(4 S0/pi), S0 the cloth area with the vent"},
          {"gores", T::Integer, "", "16", "", incl(3), incl(kMaxGores), {}, "number of gores N"},
          {"vent_diameter",
           T::Number,
           "m",
           "0.1",
           "",
           incl(0),
           {},
           {},
           "the vent edge's diameter at the radials; 0: closed (an apex node)"},
          {"cone_angle",
           T::Number,
           "deg",
           "20",
           "",
           excl(0),
           incl(80),
           {},
           "conical: the cloth's angle to the skirt plane"},
          {"bulge",
           T::Number,
           "-",
           "0",
           "",
           incl(0),
           incl(0.5),
           {},
           "sagitta of a gore's cross-section over its chord (0: flat gores)"},
          {"radial_divisions",
           T::Integer,
           "",
           "12",
           "",
           incl(1),
           incl(1000),
           {},
           "cloth divisions along a radial, vent to skirt"},
          {"gore_divisions",
           T::Integer,
           "",
           "2",
           "",
           incl(1),
           incl(1000),
           {},
           "cloth divisions across a gore (even: mirror-symmetric gores)"},
          {"radial_tapes", T::Boolean, "", "true", "", {}, {}, {}, "cables along the radial seams"},
          {"skirt_band", T::Boolean, "", "true", "", {}, {}, {}, "cables along the skirt"},
          {"vent_band", T::Boolean, "", "true", "", {}, {}, {}, "cables along the vent edge"},
          {"line_length",
           T::Number,
           "-",
           "1.0",
           "",
           excl(0),
           incl(kMaxLineLength),
           {},
           "suspension-line length over D0 (l_s/D0)"},
          {"line_elements",
           T::Integer,
           "",
           "4",
           "",
           incl(1),
           incl(1000),
           {},
           "cables per suspension line and per riser"},
          {"riser_length",
           T::Number,
           "m",
           "",
           "unset: no riser",
           excl(0),
           {},
           {},
           "payload point this far below the confluence point"},
          {"line_stretch",
           T::Number,
           "-",
           "",
           "unset: start at the constructed shape",
           excl(0),
           incl(1),
           {},
           "start at line stretch: the cloth gathered to this fraction of its distance from the axis, drawn "
           "out along it unstretched, lines taut (the constructed shape stays the stress-free reference)"},
      }};
  return s;
}

RoundCanopyParams readRoundCanopyParams(const YamlMap& entry) {
  RoundCanopyParams q;
  const SchemaMap g(entry, roundCanopySchema());
  const std::string shape = g.string("shape");
  q.shape = shape == "conical"         ? CanopyShape::conical
            : shape == "hemispherical" ? CanopyShape::hemispherical
                                       : CanopyShape::flat;
  q.nominalDiameter = g.number("nominal_diameter");
  q.gores = int(g.integer("gores"));
  q.ventDiameter = g.number("vent_diameter");
  q.coneAngleDeg = g.number("cone_angle");
  q.bulge = g.number("bulge");
  q.radialDivisions = int(g.integer("radial_divisions"));
  q.goreDivisions = int(g.integer("gore_divisions"));
  q.radialTapes = g.boolean("radial_tapes");
  q.skirtBand = g.boolean("skirt_band");
  q.ventBand = g.boolean("vent_band");
  q.lineLength = g.number("line_length");
  q.lineElements = int(g.integer("line_elements"));
  q.riserLength = g.optionalNumber("riser_length");
  q.lineStretch = g.optionalNumber("line_stretch");
  g.finish();
  // A key given with a value that cannot take effect is an error.
  if (g.has("cone_angle") && q.shape != CanopyShape::conical)
    entry.failAt("cone_angle", "applies to shape: conical only; leave it out");
  if (g.has("vent_band") && q.ventBand && q.ventDiameter == 0)
    entry.failAt("vent_band", "needs a vent (vent_diameter > 0)");
  return q;
}

namespace {

MeshData roundCanopyFrom(const YamlMap& g, const std::string& meshName) {
  const RoundCanopyParams p = readRoundCanopyParams(g);
  return locatedGenerate(
      g, [](const RoundCanopyParams& q, const std::string& n) { return buildRoundCanopy(q, n); }, p,
      meshName);
}

}  // namespace

}  // namespace fsi::structure::roundcanopy

namespace fsi::structure {

GeneratorKind roundCanopyGenerator() {
  return {"round_canopy", roundcanopy::roundCanopySchema().names(),
          roundcanopy::roundCanopySchema().description, roundcanopy::roundCanopyFrom,
          &roundcanopy::roundCanopySchema()};
}

}  // namespace fsi::structure
