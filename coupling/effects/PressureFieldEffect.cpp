// pressure_field: the pressure of an outer flow computed by another code (CFD, panel method), read from a
// file and mapped ONCE at load time onto a set of triangles; each step then costs what the chordwise table
// costs (one stored pressure per triangle, the PressureDistribution kernel). One-way FSI.
//   X.vtk  a surface with connectivity (legacy ASCII VTK POLYDATA, the field as POINT_DATA): mapped with the
//          coupling library's conservative projection, or with `projection: consistent` its interpolating
//          direction (SurfacePressureMapping.hpp)
//   X.csv  a point cloud (x, y, z and the field column): no areas, so a consistent inverse-distance
//          interpolation at each triangle's reference centroid (PointCloudInterpolation.hpp)
// Sign: the flow is on the side the triangles' normals point to (an outward skin), as for
// chordwise_pressure: a positive pressure pushes against the normal, into the body; suction pulls outward.
#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>

#include "coupling/effects/CouplingEffects.hpp"
#include "coupling/effects/PointCloudInterpolation.hpp"
#include "coupling/effects/PressureFieldFiles.hpp"
#include "coupling/effects/SurfacePressureMapping.hpp"
#include "structure/effects/PressureDistribution.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/ReadTimeFunction.hpp"
#include "structure/scene/SceneSchema.hpp"

namespace fsi::coupling {

using structure::EffectContext;
using structure::YamlMap;

namespace {

// The entry's keys (the structure's scene schema; the coupling library registers the effect and so declares
// its section). Read by build() with its own messages (keys that depend on the file's kind or the quantity).
const structure::SchemaSection& schema() {
  using T = structure::KeyType;
  using structure::excl;
  using structure::incl;
  static const structure::SchemaSection s{
      "effects.pressure_field",
      "outer-flow pressure (or Cp) from another code's solution (.vtk surface or .csv point cloud), mapped "
      "onto triangles once at load (flow on the normal side; an entry or a list of them)",
      {{"triangles", T::Selector, "", "", "required", {}, {}, {}, "the triangles"},
       {"file",
        T::String,
        "",
        "",
        "required",
        {},
        {},
        {},
        "a legacy VTK surface (.vtk, field as POINT_DATA) or a point cloud (.csv: x, y, z, field), relative "
        "to "
        "the scene's folder"},
       {"field", T::String, "", "", "p (cp with quantity: cp)", {}, {}, {}, "the file's field or column"},
       {"quantity",
        T::Choice,
        "",
        "pressure",
        "",
        {},
        {},
        {"pressure", "cp"},
        "the field is a pressure in Pa, or a Cp (times dynamic_pressure)"},
       {"dynamic_pressure",
        T::Number,
        "Pa",
        "",
        "required with quantity: cp (only then)",
        excl(0),
        {},
        {},
        "q for a Cp field"},
       {"scale", T::Number, "-", "1", "", {}, {}, {}, "a factor on the mapped pressure"},
       {"follower",
        T::Boolean,
        "",
        "true",
        "",
        {},
        {},
        {},
        "follow the current area and normal (false: a dead load on the reference geometry)"},
       {"function",
        T::Any,
        "",
        "",
        "constant 1",
        {},
        {},
        {},
        "a time function f(t) (docs/SCENES.md, Time functions)"},
       {"tolerance",
        T::Number,
        "m",
        "",
        "the triangles' mean edge length",
        excl(0),
        {},
        {},
        "the farthest a triangle may lie from the file's data (nothing is extrapolated)"},
       {"neighbours",
        T::Integer,
        "",
        "4",
        "",
        incl(1),
        incl(64),
        {},
        "points of the cloud interpolated at each centroid (.csv only)"},
       {"projection",
        T::Choice,
        "",
        "conservative",
        "",
        {},
        {},
        {"conservative", "consistent"},
        "the surface mapping (.vtk only)"}}};
  return s;
}

// The triangles as an interface mesh over their own nodes (local numbering), in reference coordinates.
InterfaceMesh localMesh(const structure::Model& model, const std::vector<int>& conn,
                        std::vector<int>& global) {
  InterfaceMesh m;
  std::vector<int> local(model.nodes.X.size() / 3, -1);
  for (int g : conn)
    if (local[std::size_t(g)] < 0) {
      local[std::size_t(g)] = int(global.size());
      global.push_back(g);
      m.points.push_back({model.nodes.X[3 * std::size_t(g)], model.nodes.X[3 * std::size_t(g) + 1],
                          model.nodes.X[3 * std::size_t(g) + 2]});
    }
  for (std::size_t e = 0; e < conn.size(); e += 3)
    m.addFace(
        {local[std::size_t(conn[e])], local[std::size_t(conn[e + 1])], local[std::size_t(conn[e + 2])]});
  return m;
}

std::vector<double> fromCloud(const std::filesystem::path& file, const std::string& field,
                              const InterfaceMesh& mesh, const std::vector<int>& tris, int neighbours,
                              double tolerance, const structure::Model& model) {
  const PointCloud cloud = readPointCloudCsv(file, field);
  std::vector<std::array<double, 3>> centroids(std::size_t(mesh.numFaces()));
  for (int f = 0; f < mesh.numFaces(); ++f) {
    const int* v = mesh.face(f);
    for (int k = 0; k < 3; ++k)
      centroids[std::size_t(f)][std::size_t(k)] =
          (mesh.points[std::size_t(v[0])][std::size_t(k)] + mesh.points[std::size_t(v[1])][std::size_t(k)] +
           mesh.points[std::size_t(v[2])][std::size_t(k)]) /
          3.0;
  }
  CloudInterpolation r = interpolateCloud(cloud.points, cloud.values, centroids, neighbours, tolerance);
  if (r.firstFailed >= 0) {
    const auto& c = centroids[std::size_t(r.firstFailed)];
    throw InputError(fmt::format(
        "{}: the centroid ({:g}, {:g}, {:g}) of {} is {:g} m from the nearest point of the cloud, farther "
        "than the tolerance {:g} m (the cloud must cover the whole triangle set; nothing is extrapolated)",
        file.string(), c[0], c[1], c[2], model.describeTriangle(tris[std::size_t(r.firstFailed)]),
        r.failedDistance, tolerance));
  }
  return std::move(r.values);
}

void build(const YamlMap& e, EffectContext& ctx) {
  const auto tris = ctx.sets.triangles(e.required("triangles"), e.childPath("triangles"));
  const std::string fileName = e.string("file");
  const std::string quantity = e.choice("quantity", {"pressure", "cp"}, "pressure");
  const std::string field = e.string("field", quantity == "cp" ? "cp" : "p");
  double q = 1.0;
  if (quantity == "cp") {
    q = e.number("dynamic_pressure");
    if (!(q > 0)) e.failAt("dynamic_pressure", fmt::format("is {}; valid: > 0 [Pa]", q));
  } else if (e.has("dynamic_pressure")) {
    e.failAt("dynamic_pressure", "only with `quantity: cp` (the file's field is a pressure in Pa)");
  }
  const double scale = e.number("scale", 1.0);
  const bool follower = e.boolean("follower", true);
  const structure::TimeFunction fn = structure::readTimeFunction(e, "function");

  std::vector<int> conn;
  for (int t : tris)
    for (int k = 0; k < 3; ++k) conn.push_back(ctx.model.membranes.conn[3 * std::size_t(t) + std::size_t(k)]);
  std::vector<int> global;
  const InterfaceMesh mesh = localMesh(ctx.model, conn, global);
  double tolerance = mesh.meanEdgeLength();  // default: one edge of the triangles
  if (e.has("tolerance")) {
    tolerance = e.number("tolerance");
    if (!(tolerance > 0)) e.failAt("tolerance", fmt::format("is {}; valid: > 0 [m]", tolerance));
  }
  std::string ext = std::filesystem::path(fileName).extension().string();
  for (char& c : ext) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (ext != ".csv" && ext != ".vtk")
    e.failAt("file", fmt::format("'{}': the file must be a point cloud (.csv) or a legacy VTK surface (.vtk)",
                                 fileName));
  bool conservative = true;
  if (e.has("projection")) {
    if (ext != ".vtk") e.failAt("projection", "only for a surface (.vtk); a point cloud is interpolated");
    conservative = e.choice("projection", {"conservative", "consistent"}) == "conservative";
  }
  int neighbours = 4;
  if (e.has("neighbours")) {
    if (ext != ".csv") e.failAt("neighbours", "only for a point cloud (.csv)");
    neighbours = int(e.integer("neighbours", {1, 64}));
  }
  e.finish(schema().names());

  const std::filesystem::path path = ctx.sceneDir / fileName;
  std::vector<double> values;
  try {
    values = ext == ".csv" ? fromCloud(path, field, mesh, tris, neighbours, tolerance, ctx.model)
                           : (conservative ? conservativeTrianglePressure : consistentTrianglePressure)(
                                 mesh, readVtkSurface(path, field), tolerance,
                                 [&](int i) { return ctx.model.describeNode(global[std::size_t(i)]); });
  } catch (const InputError& err) {
    throw InputError(structure::locate(e.file(), e.node()["file"], e.childPath("file")) + ": " + err.what());
  }
  // The flow's pressure acts from the side the normal points to: −scale·q·p along the normal.
  for (double& v : values) v *= -scale * q;
  structure::addTrianglePressure(e, ctx, std::move(conn), std::move(values), fn, follower);
}

}  // namespace

structure::EffectKind pressureFieldEffect() {
  return {
      "pressure_field",
      schema().names(),
      "outer-flow pressure (or Cp) from another code's solution, a .vtk surface (conservative projection) or "
      "a .csv point cloud, mapped onto triangles (flow on the normal side)",
      true,
      "",
      build,
      &schema()};
}

}  // namespace fsi::coupling
