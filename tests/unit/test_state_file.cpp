// StateFile: exact round trip, atomic replacement, and InputError naming the file for unusable inputs.

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <cfloat>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

#include "ScratchDir.hpp"
#include "structure/io/StateFile.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {
namespace {

namespace fs = std::filesystem;

using test::ScratchDir;

StateSnapshot sample(double salt) {
  StateSnapshot s;
  s.time = 1.2345678901234567 + salt;
  s.step = 123456789012L;
  s.dt = 3.3e-7;
  for (int i = 0; i < 3 * 5; ++i) {
    s.x.push_back(salt + i / 7.0);
    s.v.push_back(-salt - i / 11.0);
  }
  // Values that a lossy path (text, float, rounding) would not reproduce bit for bit.
  s.x[0] = -0.0;
  s.x[1] = DBL_MIN / 4;  // subnormal
  s.v[0] = std::numeric_limits<double>::max();
  s.scalars = {{"kinetic energy", 0.1 + salt},
               {"strain", 1.0 / 3.0},
               {"nan", std::numeric_limits<double>::quiet_NaN()}};
  s.arrays = {{"stress", {1.5, -2.25, 1e300}}, {"empty", {}}};
  return s;
}

bool sameBits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() &&
         (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0);
}
bool sameBits(double a, double b) {
  return std::memcmp(&a, &b, sizeof(double)) == 0;
}

void expectIdentical(const StateSnapshot& a, const StateSnapshot& b) {
  EXPECT_TRUE(sameBits(a.time, b.time));
  EXPECT_EQ(a.step, b.step);
  EXPECT_TRUE(sameBits(a.dt, b.dt));
  EXPECT_TRUE(sameBits(a.x, b.x));
  EXPECT_TRUE(sameBits(a.v, b.v));
  ASSERT_EQ(a.scalars.size(), b.scalars.size());
  for (const auto& [name, value] : a.scalars) {
    ASSERT_EQ(b.scalars.count(name), 1u) << name;
    EXPECT_TRUE(sameBits(value, b.scalars.at(name))) << name;
  }
  ASSERT_EQ(a.arrays.size(), b.arrays.size());
  for (const auto& [name, values] : a.arrays) {
    ASSERT_EQ(b.arrays.count(name), 1u) << name;
    EXPECT_TRUE(sameBits(values, b.arrays.at(name))) << name;
  }
}

// readState must throw InputError whose message names the file.
void expectInputErrorNaming(const fs::path& file) {
  try {
    readState(file);
    ADD_FAILURE() << "no InputError for " << file;
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
}

TEST(StateFile, RoundTripIsExact) {
  const ScratchDir dir;
  const fs::path file = dir.path() / "checkpoints" / "state.h5";  // parent is created
  const StateSnapshot written = sample(0.5);
  writeState(file, written);
  expectIdentical(written, readState(file));
}

TEST(StateFile, OverwriteReplacesWholeStateAndLeavesNoTemporary) {
  const ScratchDir dir;
  const fs::path file = dir.path() / "last_good.h5";
  writeState(file, sample(0.0));
  StateSnapshot second = sample(2.0);
  second.scalars.erase("strain");  // nothing of the first state may survive
  second.arrays.clear();
  writeState(file, second);
  expectIdentical(second, readState(file));
  for (const auto& entry : fs::directory_iterator(dir.path())) {
    EXPECT_EQ(entry.path().filename(), "last_good.h5") << "stray file " << entry.path();
  }
}

TEST(StateFile, EmptyStateRoundTrips) {
  const ScratchDir dir;
  const fs::path file = dir.path() / "empty.h5";
  writeState(file, StateSnapshot{});
  expectIdentical(StateSnapshot{}, readState(file));
}

TEST(StateFile, RejectsInconsistentSnapshotWithoutTouchingTheFile) {
  const ScratchDir dir;
  const fs::path file = dir.path() / "state.h5";
  StateSnapshot bad = sample(0.0);
  bad.v.pop_back();
  EXPECT_THROW(writeState(file, bad), std::invalid_argument);
  StateSnapshot badName = sample(0.0);
  badName.scalars["a/b"] = 1.0;
  EXPECT_THROW(writeState(file, badName), std::invalid_argument);
  EXPECT_FALSE(fs::exists(file));
}

TEST(StateFile, MissingFileThrowsInputErrorNamingPath) {
  const ScratchDir dir;
  expectInputErrorNaming(dir.path() / "does_not_exist.h5");
}

TEST(StateFile, NonHdf5FileThrowsInputErrorNamingPath) {
  const ScratchDir dir;
  const fs::path file = dir.path() / "state.h5";
  std::ofstream(file) << "this is not an HDF5 file\n";
  expectInputErrorNaming(file);
}

TEST(StateFile, TruncatedFileThrowsInputErrorNamingPath) {
  const ScratchDir dir;
  const fs::path file = dir.path() / "state.h5";
  StateSnapshot big = sample(0.0);
  big.x.assign(30000, 1.0);
  big.v.assign(30000, 2.0);
  writeState(file, big);
  fs::resize_file(file, fs::file_size(file) / 2);
  expectInputErrorNaming(file);
}

TEST(StateFile, OtherHdf5FileThrowsInputErrorNamingPath) {
  const ScratchDir dir;
  const fs::path file = dir.path() / "not_a_state.h5";
  const hid_t id = H5Fcreate(file.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(id, 0);
  ASSERT_GE(H5Fclose(id), 0);
  expectInputErrorNaming(file);
}

// Replaces the root attribute `name` of `file` by one of type `type` and shape `dims` (empty: a scalar).
void replaceAttribute(const fs::path& file, const char* name, hid_t type, const std::vector<hsize_t>& dims,
                      const void* data) {
  const hid_t f = H5Fopen(file.c_str(), H5F_ACC_RDWR, H5P_DEFAULT);
  ASSERT_GE(f, 0);
  ASSERT_GE(H5Adelete(f, name), 0);
  const hid_t space =
      dims.empty() ? H5Screate(H5S_SCALAR) : H5Screate_simple(int(dims.size()), dims.data(), nullptr);
  const hid_t attr = H5Acreate2(f, name, type, space, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(attr, 0);
  ASSERT_GE(H5Awrite(attr, type, data), 0);
  H5Aclose(attr);
  H5Sclose(space);
  ASSERT_GE(H5Fclose(f), 0);
}

// Every attribute is checked for shape and type before it is read (issue 35): the old reader took a
// one-element array `time` for its value, read a fractional `step` 2.5 as 2 and a two-element version as its
// first element. Each now an InputError naming the file and the attribute.
TEST(StateFile, EveryAttributeMustBeAScalarOfItsType) {
  const ScratchDir dir;
  const double oneTime[1] = {0.25}, threeTimes[3] = {0.25, 0.5, 0.75}, fraction = 2.5;
  const int versions[2] = {1, 1};
  const hid_t text = H5Tcopy(H5T_C_S1);
  H5Tset_size(text, 4);
  struct Case {
    const char* label;
    const char* attribute;
    hid_t type;
    std::vector<hsize_t> dims;
    const void* data;
    const char* says;
  };
  const Case cases[] = {
      {"time_one_element", "time", H5T_NATIVE_DOUBLE, {1}, oneTime, "found an array of shape (1)"},
      {"time_array", "time", H5T_NATIVE_DOUBLE, {3}, threeTimes, "found an array of shape (3)"},
      {"step_fraction",
       "step",
       H5T_NATIVE_DOUBLE,
       {},
       &fraction,
       "expected an integer, found a floating-point"},
      {"dt_text", "dt", text, {}, "abc", "expected a number, found a string"},
      {"version_array", "fsi_state_version", H5T_NATIVE_INT, {2}, versions, "found an array of shape (2)"},
  };
  for (const Case& c : cases) {
    const fs::path file = dir.path() / (std::string(c.label) + ".h5");
    writeState(file, sample(0.0));
    replaceAttribute(file, c.attribute, c.type, c.dims, c.data);
    try {
      readState(file);
      ADD_FAILURE() << c.label << ": read without an error";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(file.string()), std::string::npos) << c.label << ": " << what;
      EXPECT_NE(what.find(std::string("'/@") + c.attribute + "'"), std::string::npos)
          << c.label << ": " << what;
      EXPECT_NE(what.find(c.says), std::string::npos) << c.label << ": " << what;
    }
  }
  H5Tclose(text);
  // An integer where a number is expected is a number (h5py writes `attrs["time"] = 0` so).
  const fs::path file = dir.path() / "integer_time.h5";
  writeState(file, sample(0.0));
  const long long three = 3;
  replaceAttribute(file, "time", H5T_NATIVE_LLONG, {}, &three);
  EXPECT_EQ(readState(file).time, 3.0);
}

TEST(StateFile, IsStateFileTellsAStateFromAnythingElse) {
  const ScratchDir dir;
  const fs::path state = dir.path() / "state.h5", other = dir.path() / "other.h5", text = dir.path() / "t.h5";
  writeState(state, sample(0.0));
  const hid_t id = H5Fcreate(other.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT);
  ASSERT_GE(id, 0);
  ASSERT_GE(H5Fclose(id), 0);
  std::ofstream(text) << "not HDF5\n";
  EXPECT_TRUE(isStateFile(state));
  EXPECT_FALSE(isStateFile(other));
  EXPECT_FALSE(isStateFile(text));
  EXPECT_FALSE(isStateFile(dir.path() / "missing.h5"));
  EXPECT_FALSE(isStateFile(dir.path()));
}

}  // namespace
}  // namespace fsi::structure
