#pragma once
// The files a `pressure_field` effect reads: the solution of another code (CFD, panel method) as
//   a point cloud, CSV:  a header line naming the columns (x, y, z and the field, e.g. p or cp; any order,
//                        other columns ignored, names case-insensitive), then one point per line,
//                        comma-separated; empty lines and lines starting with '#' are skipped;
//   a surface, legacy ASCII VTK POLYDATA: POINTS, POLYGONS and/or TRIANGLE_STRIPS (classic cell lists or the
//                        OFFSETS/CONNECTIVITY form of version 5.1), the field as a one-component POINT_DATA
//                        array (SCALARS or FIELD); other attributes are skipped.
// Hostile input: every error names the file and line (and the column or keyword), numbers must be finite,
// declared counts are checked against what the rest of the file can hold before anything is allocated.
// Files are only read, never executed.

#include <array>
#include <filesystem>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceMesh.hpp"

namespace fsi::coupling {

/// Points and one value per point.
struct PointCloud {
  std::vector<std::array<double, 3>> points;
  std::vector<double> values;
};

/// A surface with connectivity and one value per point.
struct SurfaceField {
  InterfaceMesh mesh;
  std::vector<double> values;
};

/// Reads the columns x, y, z and `column` of a CSV file. Throws fsi::InputError ("FILE:LINE: ...").
PointCloud readPointCloudCsv(const std::filesystem::path& file, const std::string& column);

/// Reads a legacy ASCII VTK POLYDATA surface and its point-data field `field`. Throws fsi::InputError.
SurfaceField readVtkSurface(const std::filesystem::path& file, const std::string& field);

}  // namespace fsi::coupling
