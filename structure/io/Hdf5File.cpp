#include "structure/io/Hdf5File.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <cstdlib>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <type_traits>
#include <vector>

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

namespace {

// Opens the attribute after checking that it exists and is a scalar; `type` receives its type.
Hid openScalarAttribute(const Context& c, hid_t object, const char* name, const std::string& full,
                        Hid& type) {
  const htri_t exists = H5Aexists(object, name);
  if (exists < 0) c.fail("cannot query attribute", full);
  if (exists == 0) c.fail("missing attribute", full);
  Hid attr = c.check(H5Aopen(object, name, H5P_DEFAULT), H5Aclose, "cannot open attribute", full);
  const Hid space = c.check(H5Aget_space(attr.get()), H5Sclose, "cannot read the shape of attribute", full);
  const H5S_class_t shape = H5Sget_simple_extent_type(space.get());
  if (shape != H5S_SCALAR) {
    std::string found = "no value";
    if (shape == H5S_SIMPLE) {
      const int rank = H5Sget_simple_extent_ndims(space.get());
      std::vector<hsize_t> dims(static_cast<std::size_t>(std::max(rank, 0)));
      if (rank > 0) H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
      found = fmt::format("an array of shape ({})", fmt::join(dims, ", "));
    }
    c.fail(fmt::format("expected a single value (a scalar), found {}, in attribute", found), full);
  }
  type = c.check(H5Aget_type(attr.get()), H5Tclose, "cannot read the type of attribute", full);
  return attr;
}

const char* className(H5T_class_t cls) {
  switch (cls) {
    case H5T_INTEGER:
      return "an integer";
    case H5T_FLOAT:
      return "a floating-point number";
    case H5T_STRING:
      return "a string";
    case H5T_COMPOUND:
      return "a compound";
    case H5T_ARRAY:
      return "an array type";
    case H5T_ENUM:
      return "an enumeration";
    default:
      return "a non-numeric type";
  }
}

}  // namespace

template <typename T>
T readScalarAttribute(const Context& c, hid_t object, const char* name, const std::string& objectName) {
  static_assert(std::is_same_v<T, double> || std::is_same_v<T, long long>);
  const std::string full = objectName + "@" + name;
  Hid type;
  const Hid attr = openScalarAttribute(c, object, name, full, type);
  const H5T_class_t cls = H5Tget_class(type.get());
  constexpr bool integral = std::is_same_v<T, long long>;
  const bool ok = cls == H5T_INTEGER || (!integral && cls == H5T_FLOAT);
  if (!ok)
    c.fail(fmt::format("expected {}, found {}, in attribute", integral ? "an integer" : "a number",
                       className(cls)),
           full);
  // An unsigned integer above the range of long long would be clipped by HDF5's conversion: refused.
  if (integral && H5Tget_sign(type.get()) == H5T_SGN_NONE && H5Tget_size(type.get()) >= sizeof(long long)) {
    unsigned long long u = 0;
    c.check(H5Aread(attr.get(), H5T_NATIVE_ULLONG, &u), "cannot read attribute", full);
    if (u > static_cast<unsigned long long>(std::numeric_limits<long long>::max()))
      c.fail(fmt::format("value {} out of range in attribute", u), full);
    return static_cast<T>(u);
  }
  T value{};
  c.check(H5Aread(attr.get(), integral ? H5T_NATIVE_LLONG : H5T_NATIVE_DOUBLE, &value),
          "cannot read attribute", full);
  return value;
}

template double readScalarAttribute<double>(const Context&, hid_t, const char*, const std::string&);
template long long readScalarAttribute<long long>(const Context&, hid_t, const char*, const std::string&);

std::string readStringAttribute(const Context& c, hid_t object, const char* name,
                                const std::string& objectName) {
  const std::string full = objectName + "@" + name;
  Hid type;
  const Hid attr = openScalarAttribute(c, object, name, full, type);
  const H5T_class_t cls = H5Tget_class(type.get());
  if (cls != H5T_STRING)
    c.fail(fmt::format("expected a string, found {}, in attribute", className(cls)), full);
  const Hid memType = c.check(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create string type for", full);
  if (H5Tis_variable_str(type.get()) > 0) {
    c.check(H5Tset_size(memType.get(), H5T_VARIABLE), "cannot size string type for", full);
    char* text = nullptr;
    c.check(H5Aread(attr.get(), memType.get(), &text), "cannot read attribute", full);
    std::string value = text != nullptr ? text : "";
    H5free_memory(text);
    return value;
  }
  const std::size_t size = H5Tget_size(type.get());
  if (size == 0) c.fail("cannot read the size of attribute", full);
  std::string value(size, '\0');
  c.check(H5Tset_size(memType.get(), size), "cannot size string type for", full);
  c.check(H5Aread(attr.get(), memType.get(), value.data()), "cannot read attribute", full);
  value.resize(std::strlen(value.c_str()));
  return value;
}

}  // namespace fsi::structure::hdf5
