#pragma once
// SceneFrames: writes the frames of a scene's run (deformed mesh + the fields the scene's `output.fields`
// asks for) into a ResultsWriter time series. Shared by the stand-alone run and the coupled structure, so
// both produce the same HDF5/XDMF layout for ParaView. It takes the scene's parts it writes (model,
// constraints, field names), not the Scene: io/ sits below scene/ (docs/ARCHITECTURE.md "Layers").

#include <filesystem>
#include <memory>
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "structure/elements/ElementKind.hpp"
#include "structure/integrate/Constraints.hpp"
#include "structure/io/ResultsWriter.hpp"
#include "structure/model/Model.hpp"

namespace fsi::structure {

class SceneFrames {
 public:
  /// Creates (truncates) `file` and writes the mesh connectivity; with `keepUntil`, continues the series in
  /// `file` instead, dropping its frames later than keepUntil (ResultsWriter::append). `model`, `constraints`
  /// and `fields` (a scene's *scene.model, constraints and output.fields) are referenced, not copied: they
  /// must outlive the object.
  SceneFrames(const Model& model, const Constraints& constraints, const std::set<std::string>& fields,
              const std::filesystem::path& file, std::optional<double> keepUntil = std::nullopt);

  /// One frame of the scene's current state (positions, velocities and forces as last evaluated).
  void write(double time, long step);
  double lastTime() const { return writer_->lastStepTime(); }
  ResultsWriter& writer() { return *writer_; }

 private:
  const Model& model_;
  const Constraints& constraints_;
  const std::set<std::string>& fields_;
  std::unique_ptr<ResultsWriter> writer_;
  std::vector<double> u_, r_;
  std::vector<ElementFieldBuffers> elementFields_;  ///< one per element kind, kept between frames
};

}  // namespace fsi::structure
