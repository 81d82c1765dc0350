#pragma once
// MapCheck: what `fsi map-check A B` measures for two interface meshes: projections set up both ways, the
// error of linear and quadratic fields at the target nodes, the force and moment balance of the conservative
// transfer, the smoothness of a uniform pressure carried by it, the nearest-point interpolation's errors for
// comparison, the quadrature level used, unmapped points and timings.

#include <array>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/mapping/L2Projection.hpp"
#include "coupling/mapping/MappingDefaults.hpp"

namespace fsi::coupling {

struct MapCheckOptions {
  /// Absolute search tolerance; negative: mappingTolerance(A, B), A taken as the structure (as the adapter).
  double tolerance = -1.0;
  /// The projection checked: the coupled run's defaults unless changed (its tolerance is ignored).
  ProjectionOptions projection = coupledRunProjection();
  int applyRepeats = 20;  ///< applies timed per direction (the mean is reported)
  unsigned seed = 12345;  ///< of the random force field
};

/// Max and root-mean-square nodal error relative to the range of the exact field over the target nodes;
/// over the mapped target nodes only.
struct FieldError {
  double max = 0.0, rms = 0.0;
};

struct DirectionCheck {
  ProjectionReport report;                   ///< from = report.source, to = report.target
  MassMatrix mass = MassMatrix::Consistent;  ///< the variant used (what Auto chose)
  FieldError linear, quadratic;
  /// The same fields by nearest-point interpolation (each target node takes the source's value at its
  /// closest point): the reference a projection should not fall behind at the target nodes.
  FieldError linearNearest, quadraticNearest;
  /// A random-phase field of the interface's own length scales (plane waves of wavelength extent/3 and 8 ×
  /// the coarser mesh's mean edge, fixed seed) by the projection and by nearest-point interpolation.
  FieldError wave, waveNearest;
  /// A uniform unit pressure as the target's nodal forces (∫N_i) carried to the source by Hᵀ, against the
  /// source's own nodal shares ∫φ_j: RMS and max of the relative deviation, and the source nodes given no
  /// force at all (|F_j| < 1e-9 ∫φ_j). Smooth means a small RMS and no such nodes.
  double pressureRms = 0.0, pressureMax = 0.0;
  long zeroForceNodes = 0;
  /// Conservative transfer of a random nodal force field F_t on the target: |ΣF_s − ΣF_t| / Σ|F_t| and
  /// |ΣM_s − ΣM_t| / Σ|r||F_t|, moments about the target nodes' centroid.
  double forceError = 0.0, momentError = 0.0;
  double applySecondsScalar = 0.0, applySecondsVector = 0.0, applyTransposeSecondsVector = 0.0;
};

struct MapCheckResult {
  std::string meshA, meshB;
  double tolerance = 0.0;
  ProjectionOptions projection;        ///< as asked (tolerance: the one used)
  MassMatrix mass = MassMatrix::Auto;  ///< as asked
  /// Warnings with the settings to use instead (chord gap, behind nearest point, zero-force nodes); empty
  /// when there is nothing to advise.
  std::vector<std::string> advice;
  std::array<DirectionCheck, 2> directions;  ///< A → B, then B → A

  bool allMapped() const { return directions[0].report.allMapped() && directions[1].report.allMapped(); }
  nlohmann::json toJson() const;
  /// The human-readable table `fsi map-check` prints; ends by saying whether points were not mapped.
  std::string summary() const;
  /// The settings used, and whether they are the coupled run's defaults (the summary's head).
  std::string settingsLines() const;
};

/// Advice thresholds: a gap above this share of the finer mesh's mean edge; an error above this multiple
/// of nearest-point interpolation's.
inline constexpr double kAdviseGapShare = 0.1;
inline constexpr double kAdviseBehindNearest = 1.01;

MapCheckResult runMapCheck(const InterfaceMesh& a, const InterfaceMesh& b,
                           const MapCheckOptions& options = {});

}  // namespace fsi::coupling
