#pragma once
// MappingDefaults: the one set of projection settings a coupled run uses unless told otherwise — the
// adapter's option table (fsiCoupling: projection, evaluation, quadratureLevel, gapCorrection,
// defectCorrection, keepSide) takes its defaults from coupledRunProjection(), and `fsi map-check` starts from
// the same options, so the pre-flight measures what the run gets. Both print describe() of what they use.
// Also the search tolerance both use: from the meshes' chord gaps (their curvature), mappingTolerance().
// Why these values: docs/PROJECTION.md, "Defaults in a coupled run".

#include <string>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/mapping/L2Projection.hpp"

namespace fsi::coupling {

/// The coupled run's projection options (tolerance left infinite: mappingTolerance() sets it).
ProjectionOptions coupledRunProjection();

/// One line naming every setting of `o` ("projection consistent, evaluation pointwise, quadratureLevel auto,
/// gapCorrection no, defectCorrection off, keepSide no, mapTolerance 0.0123"), in the adapter's keys.
std::string describe(const ProjectionOptions& o);
/// The settings of `o` that differ from coupledRunProjection() (tolerance aside), as "key value" words.
std::vector<std::string> differencesFromRunDefaults(const ProjectionOptions& o);

/// Largest distance by which a facet of `mesh` lies below the smooth surface through its vertices (its
/// chord sag), estimated from the curvature the vertex normals show: an edge of length l whose end normals
/// differ by φ sags l φ / 8 (exact for a circular arc), a triangle's interior up to 4/3 of that (a sphere).
/// Vertices at a crease sharper than kCreaseAngle (a trailing edge: the surface's own edge, no normal) and
/// their edges count as flat. 0 for a flat mesh.
double chordGap(const InterfaceMesh& mesh);
inline constexpr double kCreaseAngle = 1.0471975511965976;  // 60°

/// Share of the structure's mean edge accepted as a gap on any interface (a flat fluid patch offset from
/// the structure's plane by round-off or a thin wall): the floor of mappingTolerance().
inline constexpr double kToleranceEdgeShare = 0.25;
/// The distance beyond which a fluid point counts as not on the structure's surface: two meshes of one
/// curved surface are apart by up to the sum of their chord gaps, so
///     max(kToleranceEdgeShare × structure's mean edge, 2 × (chordGap(structure) + chordGap(fluid))).
double mappingTolerance(const InterfaceMesh& structure, const InterfaceMesh& fluid);

}  // namespace fsi::coupling
