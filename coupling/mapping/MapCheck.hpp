#pragma once
// MapCheck: what `fsi map-check A B` measures for two interface meshes: projections set up both ways, the
// error of linear and quadratic fields at the target nodes, the force and moment balance of the conservative
// transfer, the smoothness of a uniform pressure carried by it, the nearest-point interpolation's errors for
// comparison, the quadrature level used, unmapped points and timings.

#include <array>
#include <nlohmann/json.hpp>
#include <string>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/mapping/L2Projection.hpp"

namespace fsi::coupling {

struct MapCheckOptions {
  /// Absolute search tolerance; negative: 0.25 × the larger mean edge length of the two meshes.
  double tolerance = -1.0;
  MassMatrix mass = MassMatrix::Auto;
  int quadratureLevel = kAutoQuadrature;  ///< or a level ≥ 1
  bool gapCorrection = true;
  ProjectionOptions::Defect defectCorrection = ProjectionOptions::Defect::Auto;
  bool keepSide = true;  ///< ProjectionOptions::keepSide
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
  MassMatrix mass = MassMatrix::Auto;        ///< as asked
  std::array<DirectionCheck, 2> directions;  ///< A → B, then B → A

  bool allMapped() const { return directions[0].report.allMapped() && directions[1].report.allMapped(); }
  nlohmann::json toJson() const;
  /// The human-readable table `fsi map-check` prints; ends by saying whether points were not mapped.
  std::string summary() const;
};

MapCheckResult runMapCheck(const InterfaceMesh& a, const InterfaceMesh& b,
                           const MapCheckOptions& options = {});

}  // namespace fsi::coupling
