#pragma once
// ParafoilGeometry: the reference (design, stress-free) shape of a ram-air canopy and its rigging, as one
// MeshData: upper and lower skins, a rib at every cell boundary, suspension lines cascaded from attachment
// rows on the load-bearing ribs to a confluence point, brake lines from the trailing edge to a left and a
// right toggle, and an optional riser to the payload point.
//
// Axes: x along the chord (leading edge forward at smaller x: the air flows towards +x), y along the span (+y
// = right, seen from behind), z up. The span b is measured along the arc of radius R (anhedral: the tips hang
// lower); the section at span station s sits in the plane through the arc point at angle φ = s/R, its "up"
// along the outward radius. Chord c(s) tapers linearly from the root to the tip about the quarter-chord line,
// which is straight (x = c_root/4); incidence + twist·|2s/b| rotates each section nose-up about it.
//
// Confluence point: at distance line_length·b from the reference point (the quarter chord of the centre
// section's chord line) in the symmetry plane, tilted forward (towards −x) from straight down by the rigging
// angle. Attachment rows sit at chord fractions x/c of the lower surface on the load-bearing ribs; with
// cascade k, k neighbouring attachments of one row and one half-span join at a junction placed at
// cascade_fraction of the way from their mean position to the confluence point; one main line runs from every
// junction to the confluence point. Every line is straight and stress-free in the design shape, cut into
// line_elements cables per segment.
//
// Triangulation: the skin quads between two span stations are split along diagonals mirrored about the
// symmetry plane, so the whole mesh is mirror-symmetric when cells·span_divisions is even (otherwise only the
// central strip is not). Nodes, lines and sets are always mirror-symmetric.
//
// Sets (MeshData groups): triangles upper, lower, skin (upper + lower + tip ribs: the outer surface; closed
// when the intake is), ribs, tip_ribs, inner_ribs; lines lines, lines_<row letter> (A, B, ...: attachment
// and cascade segments of that row), lines_left, lines_right (every suspension line of one half-span; those
// of a rib on the symmetry plane are in neither), main_lines, brakes_left, brakes_right, brakes, riser; nodes
// leading_edge, trailing_edge, attachments, confluence, toggle_left, toggle_right, payload, intake_edge
// (empty when closed).

#include <optional>
#include <string>
#include <vector>

#include "structure/model/MeshData.hpp"
#include "structure/parafoil/AirfoilSection.hpp"

namespace fsi::structure::parafoil {

struct ParafoilParams {
  // Planform.
  // Optional values are std::optional: unset is never a number (a tip chord of 0 is an error, not
  // "untapered").
  double span = 3.0;               ///< b, measured along the arc [m], at most kMaxSpan
  double rootChord = 1.0;          ///< [m], at most the span
  std::optional<double> tipChord;  ///< [m], at most the span; unset = rootChord (no taper)
  int cells = 8;                   ///< cells between ribs
  double arcRadius = 3.0;          ///< R [m]; 0 = flat (no anhedral)
  double incidenceDeg = 0.0;       ///< nose-up rotation of every section [deg]
  double twistDeg = 0.0;           ///< additional nose-up rotation at the tips (linear in |s|) [deg]
  // Section.
  AirfoilSection section = AirfoilSection::naca("4415", "parafoil");
  bool intakeOpen = false;  ///< open intake between intakeFrom and intakeTo (x/c) on the lower surface
  double intakeFrom = 0.0, intakeTo = 0.05;
  // Resolution (independent of any fluid mesh).
  int chordwisePoints = 24;  ///< points per surface, leading and trailing edge included
  int spanDivisions = 2;     ///< span divisions per cell
  /// Chordwise station spacing. Cosine: fine at both edges. Half-cosine: fine at the leading edge only, the
  /// trailing edge's panels as long as the mid-chord's; the edge then has no short panels that must crumple
  /// when the ballooning cells draw it forward (docs/PARAFOIL.md).
  enum class ChordSpacing { cosine, halfCosine };
  ChordSpacing chordSpacing = ChordSpacing::cosine;
  /// Designed cell bulge: height of the skins' circular arc between two ribs over the cell width (0 = flat
  /// panels), tapered along the chord with the local section thickness (none at the edges, full at the
  /// thickest point): a canopy cut with its inflated shape, as real ones are.
  double bulge = 0.0;
  // Suspension.
  bool alternateRibs = false;  ///< lines on every other rib (tips included) instead of every rib
  std::vector<double> rows{0.10, 0.30, 0.60, 0.80};  ///< attachment rows, x/c on the lower surface
  int cascade = 2;                                   ///< attachments of one row joined into one main line
  double cascadeFraction = 0.3;                      ///< junction position along attachment -> confluence
  double lineLength = 0.7;                           ///< confluence distance / span
  double riggingDeg = 5.0;                           ///< forward tilt of the confluence point [deg]
  int lineElements = 4;                              ///< cables per line segment
  /// Extra length of each row's lines [m], A first (unset: none): the trim a rigger sets. A row's line from
  /// its attachment to the confluence point is that much longer (negative: shorter) than the design distance;
  /// with cascades its main line (junction -> confluence) carries it, every cable longer in proportion.
  std::optional<std::vector<double>> rowTrim;
  // Brakes.
  int brakePoints = 3;           ///< trailing-edge points per side (at the outermost ribs); 0 = no brakes
  double toggleFraction = 0.15;  ///< toggle along confluence -> mean brake point
  /// Extra length of every brake line beyond the distance from its trailing-edge point to the toggle [m]:
  /// rigged with slack, as real brake lines are, the lines carry nothing until the toggle is drawn down by
  /// about this much or the canopy moves away from the held toggles (0: taut at the design shape).
  double brakeSlack = 0.0;
  /// A reinforcement tape (cables, the mesh's cable material) along the trailing edge from tip to tip: a
  /// brake line then pulls the edge down over the span instead of denting the skin at its attachment point.
  bool trailingEdgeTape = false;
  // Payload.
  /// Payload point this far below the confluence point, on a riser (at most kMaxLineLength spans); unset:
  /// no riser, the payload point is the confluence point.
  std::optional<double> riserLength;
};

/// Largest span [m] (the largest parafoils span about 50 m) and longest line or riser, in spans: bounds that
/// keep every coordinate of the design a sane number.
inline constexpr double kMaxSpan = 1000.0;
inline constexpr double kMaxLineLength = 10.0;

/// Builds the design shape. Throws fsi::InputError naming the parameter (as "parafoil generator: parameter
/// 'x' ...") and its valid range for an impossible design.
MeshData buildParafoil(const ParafoilParams& params, const std::string& name = "parafoil");

}  // namespace fsi::structure::parafoil
