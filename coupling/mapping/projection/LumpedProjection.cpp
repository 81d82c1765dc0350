#include "coupling/mapping/projection/LumpedProjection.hpp"

namespace fsi::coupling {

LumpedProjection::LumpedProjection(const ProjectionSetup& setup, ProjectionReport& report)
    : ProjectionVariant(assembleNodalRows(setup, /*unitDiagonal=*/false, report)) {}

std::unique_ptr<ProjectionVariant> makeLumpedProjection(const ProjectionSetup& setup,
                                                        ProjectionReport& report) {
  return std::make_unique<LumpedProjection>(setup, report);
}

}  // namespace fsi::coupling
