#pragma once
// SceneFrames: writes the frames of a scene's run (deformed mesh + the fields the scene's `output.fields`
// asks for) into a ResultsWriter time series. Shared by the stand-alone run and the coupled structure, so
// both produce the same HDF5/XDMF layout for ParaView.

#include <filesystem>
#include <memory>
#include <vector>

#include "structure/effects/MembraneForces.hpp"
#include "structure/io/ResultsWriter.hpp"
#include "structure/scene/Scene.hpp"

namespace fsi::structure {

class SceneFrames {
 public:
  /// Creates (truncates) `file` and writes the mesh connectivity.
  SceneFrames(const Scene& scene, const std::filesystem::path& file);

  /// One frame of the scene's current state (positions, velocities and forces as last evaluated).
  void write(double time, long step);
  double lastTime() const { return lastTime_; }
  ResultsWriter& writer() { return *writer_; }

 private:
  const Scene& scene_;
  std::unique_ptr<ResultsWriter> writer_;
  std::vector<double> u_, r_, major_, minor_, tension_;
  MembraneStressField stress_;
  double lastTime_ = -1;
};

}  // namespace fsi::structure
