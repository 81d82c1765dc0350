#include "structure/parafoil/ParafoilScene.hpp"

#include <fmt/format.h>

#include "structure/model/Error.hpp"
#include "structure/scene/GeneratorKinds.hpp"

namespace fsi::structure::parafoil {

namespace {}  // namespace

const SchemaSection& parafoilSchema() {
  // The one list of the generator's keys: the reader below reads each through it, docs/SCENES.md's key
  // reference is made from it. Ranges that depend on other keys (chords at most the span, brake points at
  // most the ribs of a half-span, ...) are buildParafoil's checks.
  using T = KeyType;
  static const SchemaSection s{
      "meshes.NAME.generator (parafoil)",
      "ram-air canopy: skins, ribs, cascaded suspension lines, brakes (docs/PARAFOIL.md)",
      {
          {"type", T::Choice, "", "", "required", {}, {}, {"parafoil"}, "the generator"},
          {"span", T::Number, "m", "3.0", "", excl(0), incl(kMaxSpan), {}, "span b along the arc"},
          {"root_chord", T::Number, "m", "1.0", "", excl(0), {}, {}, "chord at the centre, at most the span"},
          {"tip_chord",
           T::Number,
           "m",
           "",
           "unset: the root chord",
           excl(0),
           {},
           {},
           "chord at the tips, at most the span"},
          {"cells", T::Integer, "", "8", "", incl(1), incl(10000), {}, "cells between ribs"},
          {"arc_radius",
           T::Number,
           "m",
           "3.0",
           "",
           incl(0),
           {},
           {},
           "anhedral radius R; 0 = flat; else at least span/π"},
          {"incidence",
           T::Number,
           "deg",
           "0",
           "",
           excl(-45),
           excl(45),
           {},
           "nose-up rotation of every section"},
          {"twist", T::Number, "deg", "0", "", excl(-45), excl(45), {}, "extra nose-up rotation at the tips"},
          {"section",
           T::Any,
           "",
           "NACA 4415",
           "",
           {},
           {},
           {},
           "`NACA xxxx`/`NACA xxxxx`, or `{file: NAME.dat}` (Selig coordinates, relative to the scene)"},
          {"thickness_scale",
           T::Number,
           "-",
           "1",
           "",
           excl(0),
           incl(5),
           {},
           "multiplies the section's thickness about its mean line"},
          {"intake",
           T::Any,
           "",
           "closed",
           "",
           {},
           {},
           {},
           "`closed`, or `{from: x/c, to: x/c}`: open between these on the lower surface"},
          {"chordwise_points",
           T::Integer,
           "",
           "24",
           "",
           incl(4),
           incl(10000),
           {},
           "points per surface, edges included"},
          {"span_divisions",
           T::Integer,
           "",
           "2",
           "",
           incl(1),
           incl(10000),
           {},
           "span divisions per cell (>= 2 with a bulge)"},
          {"chordwise_spacing",
           T::Choice,
           "",
           "cosine",
           "",
           {},
           {},
           {"cosine", "half_cosine"},
           "where the chordwise stations crowd: both edges, or the leading edge only"},
          {"bulge",
           T::Number,
           "-",
           "0",
           "",
           incl(0),
           incl(0.5),
           {},
           "designed cell bulge over the cell width; 0 = flat panels"},
          {"ribs",
           T::Choice,
           "",
           "all",
           "",
           {},
           {},
           {"all", "alternate"},
           "`alternate`: lines on every other rib (an even number of cells)"},
          {"rows",
           T::Numbers,
           "-",
           "[0.1, 0.3, 0.6, 0.8]",
           "",
           excl(0),
           excl(1),
           {},
           "attachment rows A, B, ... as x/c on the lower surface, increasing"},
          {"cascade",
           T::Integer,
           "",
           "2",
           "",
           incl(1),
           incl(10000),
           {},
           "attachments per main line (1 = no cascade)"},
          {"cascade_fraction",
           T::Number,
           "-",
           "0.3",
           "",
           excl(0),
           excl(1),
           {},
           "junction position towards the confluence point (only with cascade >= 2)"},
          {"line_length",
           T::Number,
           "-",
           "0.7",
           "",
           excl(0),
           incl(kMaxLineLength),
           {},
           "confluence distance / span"},
          {"rigging_angle",
           T::Number,
           "deg",
           "5",
           "",
           excl(-45),
           excl(45),
           {},
           "forward tilt of the confluence point"},
          {"line_elements", T::Integer, "", "4", "", incl(1), incl(10000), {}, "cables per line segment"},
          {"row_trim",
           T::Numbers,
           "m",
           "",
           "none",
           {},
           {},
           {},
           "per row, A first: each row's line into the confluence point longer by this (negative: shorter)"},
          {"brake_points",
           T::Integer,
           "",
           "3",
           "",
           incl(0),
           incl(10000),
           {},
           "trailing-edge points per side (0: no brakes), at most the ribs of a half-span"},
          {"toggle_fraction",
           T::Number,
           "-",
           "0.15",
           "",
           incl(0),
           excl(1),
           {},
           "toggle position from the confluence point (only with brakes)"},
          {"brake_slack",
           T::Number,
           "m",
           "0",
           "",
           incl(0),
           {},
           {},
           "extra length of every brake line, below the span"},
          {"trailing_edge_tape",
           T::Boolean,
           "",
           "false",
           "",
           {},
           {},
           {},
           "a tape (cable_material) along the trailing edge, tip to tip"},
          {"riser_length",
           T::Number,
           "m",
           "",
           "unset: no riser",
           excl(0),
           {},
           {},
           "payload point this far below the confluence point, at most 10 spans"},
      }};
  return s;
}

const std::vector<std::string>& parafoilKeys() {
  static const std::vector<std::string> keys = parafoilSchema().names();
  return keys;
}

ParafoilParams readParafoilParams(const YamlMap& entry, const std::filesystem::path& sceneDir) {
  ParafoilParams q;
  const SchemaMap g(entry, parafoilSchema());
  q.span = g.number("span");
  q.rootChord = g.number("root_chord");
  q.tipChord = g.optionalNumber("tip_chord");  // unset: no taper
  q.cells = int(g.integer("cells"));
  q.arcRadius = g.number("arc_radius");
  q.incidenceDeg = g.number("incidence");
  q.twistDeg = g.number("twist");
  if (g.has("section")) {
    const YAML::Node s = entry.raw("section");
    const std::string where = locate(entry.file(), s, entry.childPath("section"));
    if (s.IsMap()) {
      YamlMap f = entry.map("section");
      const std::string file = f.string("file");
      f.finish({"file"});
      try {
        q.section = AirfoilSection::seligFile(sceneDir / file);
      } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
      }
    } else {
      q.section = AirfoilSection::naca(entry.string("section"), where);
    }
  }
  const double scale = g.number("thickness_scale");
  if (scale != 1.0) q.section = q.section.scaledThickness(scale);
  if (g.has("intake")) {
    const YAML::Node n = entry.raw("intake");
    if (n.IsScalar()) {
      entry.choice("intake", {"closed"});
    } else {
      YamlMap in = entry.map("intake");
      q.intakeOpen = true;
      q.intakeFrom = in.number("from");
      q.intakeTo = in.number("to");
      in.finish({"from", "to"});
    }
  }
  q.chordwisePoints = int(g.integer("chordwise_points"));
  q.spanDivisions = int(g.integer("span_divisions"));
  q.chordSpacing = g.string("chordwise_spacing") == "half_cosine" ? ParafoilParams::ChordSpacing::halfCosine
                                                                  : ParafoilParams::ChordSpacing::cosine;
  q.bulge = g.number("bulge");
  q.alternateRibs = g.string("ribs") == "alternate";
  if (g.has("rows")) q.rows = g.numbers("rows");
  q.cascade = int(g.integer("cascade"));
  q.cascadeFraction = g.number("cascade_fraction");
  q.lineLength = g.number("line_length");
  q.riggingDeg = g.number("rigging_angle");
  q.lineElements = int(g.integer("line_elements"));
  if (g.has("row_trim")) q.rowTrim = g.numbers("row_trim");  // a list, one per row (checked with the rows)
  q.brakePoints = int(g.integer("brake_points"));
  q.toggleFraction = g.number("toggle_fraction");
  q.brakeSlack = g.number("brake_slack");
  q.trailingEdgeTape = g.boolean("trailing_edge_tape");
  q.riserLength = g.optionalNumber("riser_length");  // unset: no riser
  g.finish();
  // A key given with a value that cannot take effect is an error (the rest: buildParafoil's checks).
  if (g.has("cascade_fraction") && q.cascade == 1)
    entry.failAt("cascade_fraction",
                 "has no effect with cascade 1 (no junctions); leave it out or set cascade >= 2");
  if (g.has("toggle_fraction") && q.brakePoints == 0)
    entry.failAt("toggle_fraction", "has no effect with brake_points 0 (no brakes); leave it out");
  return q;
}

namespace {

// A section file is read relative to the scene's folder (the folder of the file the entry is in).
MeshData parafoilFrom(const YamlMap& g, const std::string& meshName) {
  const ParafoilParams p = readParafoilParams(g, std::filesystem::path(g.file()).parent_path());
  return locatedGenerate(g, buildParafoil, p, meshName);
}

}  // namespace

}  // namespace fsi::structure::parafoil

namespace fsi::structure {

GeneratorKind parafoilGenerator() {
  return {"parafoil", parafoil::parafoilKeys(), parafoil::parafoilSchema().description,
          parafoil::parafoilFrom, &parafoil::parafoilSchema()};
}

}  // namespace fsi::structure
