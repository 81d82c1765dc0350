#include "structure/io/Hdf5File.hpp"

#include <fmt/format.h>

#include <stdexcept>

#include "structure/model/Error.hpp"

namespace fsi::structure::hdf5 {

QuietErrors::QuietErrors() {
  if (H5Eget_auto2(H5E_DEFAULT, &func_, &data_) >= 0) {
    saved_ = true;
    H5Eset_auto2(H5E_DEFAULT, nullptr, nullptr);
  }
}

QuietErrors::~QuietErrors() {
  if (saved_) H5Eset_auto2(H5E_DEFAULT, func_, data_);
}

std::string errorDetail() {
  std::string text;
  auto collect = [](unsigned n, const H5E_error2_t* err, void* out) -> herr_t {
    if (n == 0 && err != nullptr && err->desc != nullptr) *static_cast<std::string*>(out) = err->desc;
    return 0;
  };
  if (H5Ewalk2(H5E_DEFAULT, H5E_WALK_UPWARD, collect, &text) < 0 || text.empty()) return {};
  return " (HDF5: " + text + ")";
}

void Context::fail(const std::string& what, const std::string& object) const {
  const std::string where = object.empty() ? fmt::format("'{}'", file.string())
                                           : fmt::format("'{}' in '{}'", object, file.string());
  const std::string message = fmt::format("{}: {} {}{}", who, what, where, errorDetail());
  if (userInput) throw InputError(message);
  throw std::runtime_error(message);
}

}  // namespace fsi::structure::hdf5
