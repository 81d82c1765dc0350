#include "structure/io/StateFile.hpp"

#include <fmt/format.h>

#include <stdexcept>
#include <system_error>
#include <utility>

#include "structure/io/AtomicFile.hpp"
#include "structure/io/Hdf5File.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {
namespace {

namespace fs = std::filesystem;

constexpr int kFormatVersion = 1;
constexpr const char* kVersionAttribute = "fsi_state_version";

using hdf5::Hid;

// Error context: writing failures are std::runtime_error, reading failures InputError (the user gave the
// file); both name the file and the object.
struct Context : hdf5::Context {
  // ---- writing ----
  template <typename T>
  void writeAttribute(hid_t object, const char* name, hid_t fileType, hid_t memType, const T& value) const {
    const std::string full = std::string("/@") + name;
    const Hid space = check(H5Screate(H5S_SCALAR), H5Sclose, "cannot create dataspace for", full);
    const Hid attr = check(H5Acreate2(object, name, fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                           H5Aclose, "cannot create attribute", full);
    check(H5Awrite(attr.get(), memType, &value), "cannot write attribute", full);
  }

  // scalar == true writes a rank-0 dataset holding data[0].
  void writeDataset(hid_t parent, const std::string& name, const std::string& full, const double* data,
                    std::size_t n, bool scalar) const {
    const hsize_t dims[1] = {n};
    const Hid space = check(scalar ? H5Screate(H5S_SCALAR) : H5Screate_simple(1, dims, nullptr), H5Sclose,
                            "cannot create dataspace for", full);
    const Hid dset = check(
        H5Dcreate2(parent, name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
        H5Dclose, "cannot create dataset", full);
    if (scalar || n > 0) {
      check(H5Dwrite(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, data),
            "cannot write dataset", full);
    }
  }

  Hid createGroup(hid_t parent, const char* name) const {
    return check(H5Gcreate2(parent, name, H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "cannot create group", std::string("/") + name);
  }

  // ---- reading ----
  // Reads a rank-1 dataset, or a rank-0 one when scalar is true.
  std::vector<double> readDataset(hid_t parent, const std::string& name, const std::string& full,
                                  bool scalar) const {
    const Hid dset =
        check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "cannot open dataset", full);
    const Hid space = check(H5Dget_space(dset.get()), H5Sclose, "cannot get dataspace of", full);
    const int rank = H5Sget_simple_extent_ndims(space.get());
    if (rank < 0) fail("cannot get rank of", full);
    if (rank != (scalar ? 0 : 1)) fail(scalar ? "expected a scalar dataset" : "expected a 1-D dataset", full);
    const hssize_t n = H5Sget_simple_extent_npoints(space.get());
    if (n < 0) fail("cannot get size of", full);
    if (scalar && n != 1) fail("expected one value in", full);  // a null dataspace is rank 0 too
    std::vector<double> values(static_cast<std::size_t>(n));
    if (n > 0) {
      check(H5Dread(dset.get(), H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()),
            "cannot read dataset", full);
    }
    return values;
  }

  // Names of the links in an optional group (empty if the group is absent).
  std::vector<std::string> children(hid_t root, const char* group) const {
    const std::string full = std::string("/") + group;
    const htri_t exists = H5Lexists(root, group, H5P_DEFAULT);
    if (exists < 0) fail("cannot query", full);
    if (exists == 0) return {};
    const Hid g = check(H5Gopen2(root, group, H5P_DEFAULT), H5Gclose, "cannot open group", full);
    H5G_info_t info;
    check(H5Gget_info(g.get(), &info), "cannot list group", full);
    std::vector<std::string> names;
    names.reserve(info.nlinks);
    for (hsize_t i = 0; i < info.nlinks; ++i) {
      const ssize_t len =
          H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
      if (len < 0) fail("cannot list group", full);
      std::string name(static_cast<std::size_t>(len) + 1, '\0');
      if (H5Lget_name_by_idx(g.get(), ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(),
                             H5P_DEFAULT) < 0) {
        fail("cannot list group", full);
      }
      name.resize(static_cast<std::size_t>(len));
      names.push_back(std::move(name));
    }
    return names;
  }
};

void checkKey(const std::string& key, const char* kind) {
  if (key.empty() || key == "." || key.find('/') != std::string::npos) {
    throw std::invalid_argument(
        fmt::format("writeState: invalid {} name '{}' (must be non-empty, without '/')", kind, key));
  }
}

void writeHdf5(const fs::path& path, const StateSnapshot& s) {
  const hdf5::QuietErrors quiet;
  const Context c{{path, "writeState", false}};
  Hid file = c.check(H5Fcreate(path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                     "cannot create file", "");
  c.writeAttribute(file.get(), kVersionAttribute, H5T_STD_I32LE, H5T_NATIVE_INT, kFormatVersion);
  c.writeAttribute(file.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, s.time);
  c.writeAttribute(file.get(), "step", H5T_STD_I64LE, H5T_NATIVE_LLONG, static_cast<long long>(s.step));
  c.writeAttribute(file.get(), "dt", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, s.dt);
  c.writeDataset(file.get(), "x", "/x", s.x.data(), s.x.size(), false);
  c.writeDataset(file.get(), "v", "/v", s.v.data(), s.v.size(), false);
  {
    const Hid g = c.createGroup(file.get(), "scalars");
    for (const auto& [name, value] : s.scalars)
      c.writeDataset(g.get(), name, "/scalars/" + name, &value, 1, true);
  }
  {
    const Hid g = c.createGroup(file.get(), "arrays");
    for (const auto& [name, values] : s.arrays) {
      c.writeDataset(g.get(), name, "/arrays/" + name, values.data(), values.size(), false);
    }
  }
  c.check(file.close(), "cannot close", "");
}

}  // namespace

void writeState(const fs::path& file, const StateSnapshot& state) {
  if (state.x.size() % 3 != 0 || state.v.size() != state.x.size()) {
    throw std::invalid_argument(
        fmt::format("writeState: x has {} and v has {} values; expected 3N each for '{}'", state.x.size(),
                    state.v.size(), file.string()));
  }
  for (const auto& entry : state.scalars) checkKey(entry.first, "scalar");
  for (const auto& entry : state.arrays) checkKey(entry.first, "array");

  if (file.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(file.parent_path(), ec);
    if (ec) {
      throw std::runtime_error(fmt::format("writeState: cannot create directory '{}': {}",
                                           file.parent_path().string(), ec.message()));
    }
  }
  replaceFileAtomically(file, "writeState", [&](const fs::path& tmp) { writeHdf5(tmp, state); });
}

StateSnapshot readState(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) {
    throw InputError(
        fmt::format("readState: state file '{}' does not exist or is not a regular file", file.string()));
  }
  const hdf5::QuietErrors quiet;
  const htri_t isHdf5 = H5Fis_hdf5(file.c_str());
  if (isHdf5 <= 0) {
    const std::string detail = isHdf5 < 0 ? hdf5::errorDetail() : std::string();
    throw InputError(fmt::format("readState: '{}' is not a readable HDF5 file{}", file.string(), detail));
  }

  const Context c{{file, "readState", true}};
  const Hid f = c.check(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "cannot open", "");
  const htri_t tagged = H5Aexists(f.get(), kVersionAttribute);
  if (tagged < 0) c.fail("cannot query attribute", std::string("/@") + kVersionAttribute);
  if (tagged == 0) c.fail("not a state file: missing attribute", std::string("/@") + kVersionAttribute);
  const long long version = hdf5::readScalarAttribute<long long>(c, f.get(), kVersionAttribute, "/");
  if (version != kFormatVersion) {
    c.fail(fmt::format("unsupported format version {} (expected {}) in attribute", version, kFormatVersion),
           std::string("/@") + kVersionAttribute);
  }

  StateSnapshot s;
  s.time = hdf5::readScalarAttribute<double>(c, f.get(), "time", "/");
  s.step = static_cast<long>(hdf5::readScalarAttribute<long long>(c, f.get(), "step", "/"));
  s.dt = hdf5::readScalarAttribute<double>(c, f.get(), "dt", "/");
  s.x = c.readDataset(f.get(), "x", "/x", false);
  s.v = c.readDataset(f.get(), "v", "/v", false);
  if (s.x.size() % 3 != 0 || s.v.size() != s.x.size()) {
    c.fail(fmt::format("inconsistent sizes (x: {}, v: {}; expected 3N each) of", s.x.size(), s.v.size()),
           "/x, /v");
  }
  for (const std::string& name : c.children(f.get(), "scalars")) {
    s.scalars[name] = c.readDataset(f.get(), "scalars/" + name, "/scalars/" + name, true).front();
  }
  for (const std::string& name : c.children(f.get(), "arrays")) {
    s.arrays[name] = c.readDataset(f.get(), "arrays/" + name, "/arrays/" + name, false);
  }
  return s;
}

bool isStateFile(const fs::path& file) {
  std::error_code ec;
  if (!fs::is_regular_file(file, ec)) return false;
  const hdf5::QuietErrors quiet;
  if (H5Fis_hdf5(file.c_str()) <= 0) return false;
  const Hid f(H5Fopen(file.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose);
  return f.valid() && H5Aexists(f.get(), kVersionAttribute) > 0;
}

}  // namespace fsi::structure
