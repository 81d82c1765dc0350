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

}  // namespace fsi
