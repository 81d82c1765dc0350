#pragma once
// What the two HDF5 writers (ResultsWriter, StateFile) share: an owned HDF5 identifier, HDF5's error printing
// silenced for a scope, and failures reported as exceptions that name the file, the object and HDF5's own
// innermost message.

#include <hdf5.h>

#include <filesystem>
#include <string>
#include <utility>

namespace fsi::structure::hdf5 {

/// Owns one HDF5 identifier and releases it with the matching close function.
class Hid {
 public:
  using Closer = herr_t (*)(hid_t);
  Hid() = default;
  Hid(hid_t id, Closer closer) : id_(id), closer_(closer) {}
  Hid(Hid&& other) noexcept : id_(std::exchange(other.id_, H5I_INVALID_HID)), closer_(other.closer_) {}
  Hid& operator=(Hid&& other) noexcept {
    if (this != &other) {
      reset();
      id_ = std::exchange(other.id_, H5I_INVALID_HID);
      closer_ = other.closer_;
    }
    return *this;
  }
  Hid(const Hid&) = delete;
  Hid& operator=(const Hid&) = delete;
  ~Hid() { reset(); }

  hid_t get() const { return id_; }
  bool valid() const { return id_ >= 0; }
  /// Explicit close so that a failure (e.g. the final write of a file) can be reported.
  herr_t close() { return valid() ? closer_(std::exchange(id_, H5I_INVALID_HID)) : 0; }

 private:
  void reset() noexcept {
    if (valid()) closer_(std::exchange(id_, H5I_INVALID_HID));
  }
  hid_t id_ = H5I_INVALID_HID;
  Closer closer_ = nullptr;
};

/// Turns off HDF5's automatic stack printing for the scope (errors are reported by exception) and restores
/// the caller's setting afterwards, so other HDF5 users in the process are unaffected.
class QuietErrors {
 public:
  QuietErrors();
  ~QuietErrors();
  QuietErrors(const QuietErrors&) = delete;
  QuietErrors& operator=(const QuietErrors&) = delete;

 private:
  H5E_auto2_t func_ = nullptr;
  void* data_ = nullptr;
  bool saved_ = false;
};

/// " (HDF5: <innermost description>)" from the HDF5 error stack, or empty. Must run before the next HDF5
/// call clears the stack.
std::string errorDetail();

/// Error context of one file: every failure names `who` (the operation), the file and the object.
/// Failures are fsi::InputError when `userInput` (a file the user gave), std::runtime_error otherwise.
struct Context {
  const std::filesystem::path& file;
  const char* who;
  bool userInput = false;

  /// An empty object means the file itself.
  [[noreturn]] void fail(const std::string& what, const std::string& object) const;
  Hid check(hid_t id, Hid::Closer closer, const char* what, const std::string& object) const {
    if (id < 0) fail(what, object);
    return Hid(id, closer);
  }
  void check(herr_t status, const char* what, const std::string& object) const {
    if (status < 0) fail(what, object);
  }
};

/// The attribute `name` of `object` as one value. Checked before it is read, with a failure (through `c`)
/// naming the file, the object (`objectName`: "/", "/steps/000003") and the attribute ("/steps/000003@time"):
/// that it exists, that it is a scalar (not an array, however short, nor empty), and that it is a number
/// of the right kind — an integer for `long long`, an integer or a floating-point number for `double`.
/// Defined for T = double and long long.
template <typename T>
T readScalarAttribute(const Context& c, hid_t object, const char* name, const std::string& objectName);

/// A scalar string attribute (fixed or variable length), checked and named as readScalarAttribute.
std::string readStringAttribute(const Context& c, hid_t object, const char* name,
                                const std::string& objectName);

}  // namespace fsi::structure::hdf5
