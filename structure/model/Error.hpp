#pragma once
// InputError: every problem a user can fix in their input (scene, mesh, command line) is reported with this
// type, whose message names the file, line, key, node or element concerned.

#include <stdexcept>
#include <string>

namespace fsi {

class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

/// An InputError about one mesh of a model being built: mesh() is its index among the builder's inputs, so
/// that the scene reader puts the message at that mesh's entry (its file or generator) without reading it.
class MeshInputError : public InputError {
 public:
  MeshInputError(int mesh, const std::string& message) : InputError(message), mesh_(mesh) {}
  int mesh() const { return mesh_; }

 private:
  int mesh_;
};

}  // namespace fsi
