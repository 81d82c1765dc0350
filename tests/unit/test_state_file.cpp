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

#include "structure/io/StateFile.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {
namespace {

namespace fs = std::filesystem;

class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    path_ = fs::temp_directory_path() / ("fsi_" + std::string(info->test_suite_name()) + "_" + info->name() +
                                         "_" + std::to_string(::getpid()));
    fs::remove_all(path_);
    fs::create_directories(path_);
  }
  ~ScratchDir() {
    std::error_code ignored;
    fs::remove_all(path_, ignored);
  }
  const fs::path& path() const { return path_; }

 private:
  fs::path path_;
};

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

}  // namespace
}  // namespace fsi::structure
