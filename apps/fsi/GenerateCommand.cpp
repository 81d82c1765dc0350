#include "GenerateCommand.hpp"

#include <fmt/format.h>

#include <cmath>
#include <stdexcept>

#include "coupling/mapping/StateTransfer.hpp"
#include "structure/io/MeshFileWriters.hpp"
#include "structure/io/ResultsWriter.hpp"
#include "structure/io/StateFile.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/Scene.hpp"

namespace fs = std::filesystem;
using fsi::structure::MeshData;
using fsi::structure::Model;

namespace fsi::app {
namespace {

// The model's displacement at `source`'s last frame: node for node from a state file, interpolated onto the
// model's reference from a results file. Writes what it did to the console.
std::vector<double> deformedDisplacement(const Model& model, fs::path source) {
  if (fs::is_directory(source)) source /= "results.h5";
  const std::string name = "--deformed " + source.string();
  std::vector<double> u(model.nodes.x.size(), 0.0);
  if (fsi::structure::isStateFile(source)) {
    fsi::structure::StateSnapshot s;
    try {
      s = fsi::structure::readState(source);
    } catch (const fsi::InputError& e) {
      throw fsi::InputError(fmt::format("--deformed: {}", e.what()));
    }
    if (s.x.size() != u.size())
      throw fsi::InputError(
          fmt::format("{}: the state of {} nodes, but the scene builds {} nodes (a state file moves the mesh "
                      "node for node: give the scene and --set options of the run that wrote it, or its "
                      "results.h5)",
                      name, s.x.size() / 3, model.nodes.count));
    for (std::size_t d = 0; d < u.size(); ++d) {
      if (!std::isfinite(s.x[d]))
        throw fsi::InputError(fmt::format("{}: dataset /x is not finite at node {}", name, d / 3));
      u[d] = s.x[d] - model.nodes.X[d];
    }
    fmt::print("deformed  {}: state at step {} (t = {:g}), node for node\n", source.string(), s.step, s.time);
    return u;
  }
  fsi::structure::ResultsFrame frame;
  try {
    frame = fsi::structure::readLastFrame(source);
  } catch (const fsi::InputError& e) {
    throw fsi::InputError(fmt::format("--deformed: {}", e.what()));
  }
  fsi::coupling::StateTransferReport rep;
  u = fsi::coupling::transferDisplacement(frame, model, name, -1.0, &rep);
  fmt::print(
      "deformed  {} frame {} (t = {:g}, {} nodes) onto {} nodes: {} on its triangles, {} on its cables, {} "
      "at "
      "its nearest node; largest distance {:.3g} m\n",
      source.string(), frame.step, frame.time, frame.numNodes(), model.nodes.count, rep.membraneNodes,
      rep.cableNodes, rep.pointNodes, rep.largestDistance);
  return u;
}

}  // namespace

int generateCommand(const fs::path& scenePath, const fs::path& outDir, const std::vector<std::string>& sets,
                    const fs::path& deformed) {
  const fsi::structure::Scene scene = fsi::structure::loadScene(scenePath, sets);
  const Model& model = *scene.model;
  const std::vector<double> u =
      deformed.empty() ? std::vector<double>{} : deformedDisplacement(model, deformed);
  std::error_code ec;
  fs::create_directories(outDir, ec);
  if (ec)
    throw std::runtime_error(fmt::format("{}: cannot create the folder: {}", outDir.string(), ec.message()));
  for (const auto& m : model.meshes) {
    MeshData mesh = m.source;
    if (!u.empty())
      for (std::size_t i = 0; i < mesh.points.size(); ++i)
        for (std::size_t c = 0; c < 3; ++c) mesh.points[i][c] += u[3 * std::size_t(m.node[i]) + c];
    const fs::path msh = outDir / (m.name + ".msh");
    fsi::structure::writeMsh(mesh, msh);
    fmt::print("{}  {} nodes, {} triangles, {} lines, {} sets\n", msh.string(), mesh.points.size(),
               mesh.triangles.size(), mesh.lines.size(),
               mesh.nodeGroups.size() + mesh.triangleGroups.size() + mesh.lineGroups.size());
    if (mesh.triangles.empty()) continue;
    const auto skin = mesh.triangleGroups.find("skin");
    const std::vector<int> outer = skin == mesh.triangleGroups.end() ? std::vector<int>{} : skin->second;
    const fs::path stl = outDir / (m.name + ".stl");
    fsi::structure::writeStl(mesh, outer, stl, m.name);
    fmt::print("{}  {} triangles ({}{})\n", stl.string(),
               outer.empty() ? mesh.triangles.size() : outer.size(), outer.empty() ? "all" : "set 'skin'",
               u.empty() ? "" : ", deformed");
  }
  return 0;
}

}  // namespace fsi::app
