#include "structure/parafoil/ParafoilScene.hpp"

#include <fmt/format.h>

#include "structure/model/Error.hpp"
#include "structure/scene/GeneratorKinds.hpp"

namespace fsi::structure::parafoil {

const std::vector<std::string>& parafoilKeys() {
  static const std::vector<std::string> keys{"type",
                                             "span",
                                             "root_chord",
                                             "tip_chord",
                                             "cells",
                                             "arc_radius",
                                             "incidence",
                                             "twist",
                                             "section",
                                             "thickness_scale",
                                             "intake",
                                             "chordwise_points",
                                             "span_divisions",
                                             "chordwise_spacing",
                                             "bulge",
                                             "ribs",
                                             "rows",
                                             "cascade",
                                             "cascade_fraction",
                                             "line_length",
                                             "rigging_angle",
                                             "line_elements",
                                             "row_trim",
                                             "brake_points",
                                             "toggle_fraction",
                                             "brake_slack",
                                             "trailing_edge_tape",
                                             "riser_length"};
  return keys;
}

ParafoilParams readParafoilParams(const YamlMap& g, const std::filesystem::path& sceneDir) {
  ParafoilParams q;
  const IntRange positive{1, 10000};
  q.span = g.number("span", q.span);
  q.rootChord = g.number("root_chord", q.rootChord);
  if (g.has("tip_chord")) q.tipChord = g.number("tip_chord");  // unset: no taper
  q.cells = int(g.integer("cells", q.cells, {1, 10000}));
  q.arcRadius = g.number("arc_radius", q.arcRadius);
  q.incidenceDeg = g.number("incidence", q.incidenceDeg);
  q.twistDeg = g.number("twist", q.twistDeg);
  if (g.has("section")) {
    const YAML::Node s = g.raw("section");
    const std::string where = locate(g.file(), s, g.childPath("section"));
    if (s.IsMap()) {
      YamlMap f = g.map("section");
      const std::string file = f.string("file");
      f.finish({"file"});
      try {
        q.section = AirfoilSection::seligFile(sceneDir / file);
      } catch (const InputError& e) {
        throw InputError(where + ": " + e.what());
      }
    } else {
      q.section = AirfoilSection::naca(g.string("section"), where);
    }
  }
  const double scale = g.number("thickness_scale", 1.0);
  if (!(scale > 0 && scale <= 5)) g.failAt("thickness_scale", fmt::format("is {}; valid: (0, 5]", scale));
  if (scale != 1.0) q.section = q.section.scaledThickness(scale);
  if (g.has("intake")) {
    const YAML::Node n = g.raw("intake");
    if (n.IsScalar()) {
      g.choice("intake", {"closed"});
    } else {
      YamlMap in = g.map("intake");
      q.intakeOpen = true;
      q.intakeFrom = in.number("from");
      q.intakeTo = in.number("to");
      in.finish({"from", "to"});
    }
  }
  q.chordwisePoints = int(g.integer("chordwise_points", q.chordwisePoints, {4, 10000}));
  q.spanDivisions = int(g.integer("span_divisions", q.spanDivisions, positive));
  q.chordSpacing = g.choice("chordwise_spacing", {"cosine", "half_cosine"}, "cosine") == "half_cosine"
                       ? ParafoilParams::ChordSpacing::halfCosine
                       : ParafoilParams::ChordSpacing::cosine;
  q.bulge = g.number("bulge", q.bulge);
  q.alternateRibs = g.choice("ribs", {"all", "alternate"}, "all") == "alternate";
  if (g.has("rows")) q.rows = g.numbers("rows");
  q.cascade = int(g.integer("cascade", q.cascade, positive));
  q.cascadeFraction = g.number("cascade_fraction", q.cascadeFraction);
  q.lineLength = g.number("line_length", q.lineLength);
  q.riggingDeg = g.number("rigging_angle", q.riggingDeg);
  q.lineElements = int(g.integer("line_elements", q.lineElements, positive));
  if (g.has("row_trim")) q.rowTrim = g.numbers("row_trim");  // a list, one per row (checked with the rows)
  q.brakePoints = int(g.integer("brake_points", q.brakePoints, {0, 10000}));
  q.toggleFraction = g.number("toggle_fraction", q.toggleFraction);
  q.brakeSlack = g.number("brake_slack", q.brakeSlack);
  q.trailingEdgeTape = g.boolean("trailing_edge_tape", q.trailingEdgeTape);
  if (g.has("riser_length")) q.riserLength = g.number("riser_length");  // unset: no riser
  g.finish(parafoilKeys());
  // A key given with a value that cannot take effect is an error (the rest: buildParafoil's checks).
  if (g.has("cascade_fraction") && q.cascade == 1)
    g.failAt("cascade_fraction",
             "has no effect with cascade 1 (no junctions); leave it out or set cascade >= 2");
  if (g.has("toggle_fraction") && q.brakePoints == 0)
    g.failAt("toggle_fraction", "has no effect with brake_points 0 (no brakes); leave it out");
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
  return {"parafoil", parafoil::parafoilKeys(),
          "ram-air canopy: skins, ribs, cascaded suspension lines, brakes (docs/PARAFOIL.md)",
          parafoil::parafoilFrom};
}

}  // namespace fsi::structure
