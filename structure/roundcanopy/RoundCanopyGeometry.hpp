#pragma once
// RoundCanopyGeometry: the constructed (design, stress-free) shape of a gored round parachute and its
// rigging, as one MeshData: the cloth of N gores around a vent, reinforcement tapes along the radial seams,
// the skirt and the vent edge, a suspension line from the skirt end of every radial to the confluence point,
// and an optional riser to the payload point.
//
// Axes: z is the canopy's axis, up (the apex is at the top; the payload hangs below and the relative wind of
// a descent blows towards +z); the skirt lies in the plane z = 0. Radial k runs at azimuth 2πk/N in the
// meridian plane, along the profile of the chosen shape from the apex (u = 0) to the skirt (u = 1), evenly in
// its arc length:
//   flat           r = R u,                z = 0                         (a flat circular canopy)
//   conical        r = R u,                z = (1 − u) R tan α           (α: the cloth's angle to the skirt
//                                                                         plane)
//   hemispherical  r = R sin(πu/2),        z = R cos(πu/2)               (a quarter circle of radius R)
// R is the skirt radius at the radials. A gore is the cloth between two neighbouring radials: at each u the
// straight chord between them (flat gores), or with `bulge` > 0 a circular arc over that chord, bulging
// outwards (away from the axis and the inflow) with sagitta bulge · chord.
//
// Sizes follow the designer's definitions: the nominal area S₀ is the cloth area of the whole canopy with the
// vent counted as cloth, and the nominal diameter D₀ = √(4 S₀/π) is the input; the generator scales the shape
// so that its cloth area is exactly π D₀²/4 (the continuous surface; the mesh converges to it at second
// order, exactly for flat gores on a straight profile). The constructed diameter D_c = 2R (across the ends of
// two opposite radials); the vent is the cloth inside the radials' station r = vent_diameter/2, left open.
// Suspension lines of length line_length · D₀ (the ratio l_s/D₀) meet on the axis below the skirt.
//
// Triangulation: ring i (i = 0 at the vent edge, or the apex node without a vent, to radial_divisions at the
// skirt) has gore_divisions nodes per gore, the first on the radial. Every quad is split along the diagonal
// mirrored about its gore's centre line, so the mesh is rotationally symmetric by one gore and mirror-
// symmetric about every gore's centre plane when gore_divisions is even. Triangle normals point out of the
// canopy (away from the axis and up): an inflating pressure pushes along them.
//
// Sets (MeshData groups): triangles canopy, skin (the same: the outer surface for `fsi generate`'s STL),
// gore_1 ... gore_N; lines radials (the radial tapes), skirt_band, vent_band, tapes (all three), lines (the
// suspension lines), riser; nodes vent (the vent edge; without a vent the apex node), apex (the same), skirt,
// radial_ends (the skirt ends of the radials, where the lines attach), confluence, payload (the riser's lower
// end; without a riser the confluence point).
//
// Line stretch (`line_stretch` s): the canopy starts slender, as it is when the lines have just pulled taut
// and before air enters: every cloth node starts at s times its distance from the axis (same azimuth), all
// nodes of a ring at one height, the rings stacked from the skirt up so that the shortest of the meridian
// segments between two rings keeps its constructed length (Δz = min over the ring of √(Δh² (1 − s²) + Δz₀²),
// Δh and Δz₀ a segment's horizontal and vertical parts as constructed): no cloth edge and no tape is longer
// than cut, so the start carries no stress (the longer meridians, the radial tapes among them, are slack).
// The skirt is at the height where the lines, straight from the confluence point, have their length l_s.
// The constructed shape stays the stress-free reference: the gores are s times narrower than cut (slack:
// wrinkled cloth carries no hoop stress).

#include <optional>
#include <string>

#include "structure/model/MeshData.hpp"

namespace fsi::structure::roundcanopy {

enum class CanopyShape { flat, conical, hemispherical };

struct RoundCanopyParams {
  CanopyShape shape = CanopyShape::flat;
  double nominalDiameter = 1.0;  ///< D₀ [m]: √(4 S₀/π), S₀ the cloth area with the vent
  int gores = 16;                ///< N, at least 3
  double ventDiameter = 0.1;     ///< diameter of the vent edge at the radials [m]; 0: closed (an apex node)
  double coneAngleDeg = 20.0;    ///< conical: the cloth's angle to the skirt plane [deg]
  double bulge = 0.0;            ///< sagitta of a gore's cross-section over its chord (0: flat gores)
  // Resolution.
  int radialDivisions = 12;  ///< cloth divisions along a radial, vent to skirt
  int goreDivisions = 2;     ///< cloth divisions across a gore
  // Reinforcement tapes (cables, the mesh's cable material).
  bool radialTapes = true;
  bool skirtBand = true;
  bool ventBand = true;
  // Rigging.
  double lineLength = 1.0;  ///< suspension-line length over D₀ (l_s/D₀)
  int lineElements = 4;     ///< cables per suspension line (and per riser)
  /// Payload point this far below the confluence point [m]; unset: no riser.
  std::optional<double> riserLength;
  /// Start at line stretch (MeshData::startPoints): the cloth gathered towards the axis, every point's
  /// distance from it this fraction (0, 1] of the constructed one, the canopy drawn out along the axis above
  /// the skirt without stretching any of it, the lines straight and taut to the confluence point, which
  /// stays; unset: start at the constructed shape.
  std::optional<double> lineStretch;
};

/// What the design is, in the designer's numbers (for logs, docs and tests).
struct RoundCanopyDesign {
  double nominalArea = 0;          ///< S₀ [m²]
  double constructedDiameter = 0;  ///< D_c = 2R [m]
  double skirtRadius = 0;          ///< R [m]
  double ventRadius = 0;           ///< [m]
  double ventArea = 0;             ///< cloth area inside the vent edge [m²] (open: geometric porosity)
  double height = 0;               ///< apex above the skirt plane [m]
  double lineLength = 0;           ///< l_s [m]
  double confluenceDepth = 0;      ///< confluence point below the skirt plane [m]
  double ventU = 0;                ///< the vent edge's station along a radial (0: apex)
};

/// Largest nominal diameter [m], most gores, longest lines (in D₀): bounds that keep a design sane.
inline constexpr double kMaxNominalDiameter = 1000.0;
inline constexpr int kMaxGores = 1000;
inline constexpr double kMaxLineLength = 10.0;

/// The design's numbers. Throws fsi::InputError naming the parameter and its valid range
/// ("round_canopy generator: parameter 'x' ...") for an impossible design.
RoundCanopyDesign designRoundCanopy(const RoundCanopyParams& params);

/// Builds the constructed shape (checks as designRoundCanopy).
MeshData buildRoundCanopy(const RoundCanopyParams& params, const std::string& name = "canopy");

/// Cloth area of the continuous shape at skirt radius 1 between the radial stations u0 and u1 (all gores);
/// S₀ = R² · clothArea(params, 0, 1). Exposed for the tests.
double clothArea(const RoundCanopyParams& params, double u0, double u1);

}  // namespace fsi::structure::roundcanopy
