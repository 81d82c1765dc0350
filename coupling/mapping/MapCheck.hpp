#pragma once
// MapCheck: what `fsi map-check A B` measures for two interface meshes: projections set up both ways, the
// error of linear and quadratic fields at the target nodes, the force and moment balance of the conservative
// transfer, unmapped points and timings.

#include <array>
#include <nlohmann/json.hpp>
#include <string>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/mapping/L2Projection.hpp"

namespace fsi::coupling {

struct MapCheckOptions {
  /// Absolute search tolerance; negative: 0.25 × the larger mean edge length of the two meshes.
  double tolerance = -1.0;
  MassMatrix mass = MassMatrix::Consistent;
  int quadratureLevel = 1;
  int applyRepeats = 20;  ///< applies timed per direction (the mean is reported)
  unsigned seed = 12345;  ///< of the random force field
};

/// Max and root-mean-square nodal error relative to the range of the exact field over the target nodes;
/// over the mapped target nodes only.
struct FieldError {
  double max = 0.0, rms = 0.0;
};

struct DirectionCheck {
  ProjectionReport report;  ///< from = report.source, to = report.target
  FieldError linear, quadratic;
  /// Conservative transfer of a random nodal force field F_t on the target: |ΣF_s − ΣF_t| / Σ|F_t| and
  /// |ΣM_s − ΣM_t| / Σ|r||F_t|, moments about the target nodes' centroid.
  double forceError = 0.0, momentError = 0.0;
  double applySecondsScalar = 0.0, applySecondsVector = 0.0, applyTransposeSecondsVector = 0.0;
};

struct MapCheckResult {
  std::string meshA, meshB;
  double tolerance = 0.0;
  MassMatrix mass = MassMatrix::Consistent;
  std::array<DirectionCheck, 2> directions;  ///< A → B, then B → A

  bool allMapped() const { return directions[0].report.allMapped() && directions[1].report.allMapped(); }
  nlohmann::json toJson() const;
  /// The human-readable table `fsi map-check` prints; ends by saying whether points were not mapped.
  std::string summary() const;
};

MapCheckResult runMapCheck(const InterfaceMesh& a, const InterfaceMesh& b,
                           const MapCheckOptions& options = {});

}  // namespace fsi::coupling
