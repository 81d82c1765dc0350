// ResultsWriter: HDF5 contents read back with the HDF5 C API, XDMF index checked against the HDF5 file.

#include <gtest/gtest.h>
#include <hdf5.h>
#include <unistd.h>

#include <array>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <regex>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "ScratchDir.hpp"
#include "structure/io/ResultsWriter.hpp"

namespace fsi::structure {
namespace {

namespace fs = std::filesystem;
using Center = FieldView::Center;

constexpr int kNodes = 4;
const std::vector<std::array<int, 3>> kTriangles{{0, 1, 2}, {0, 2, 3}};
const std::vector<std::array<int, 2>> kLines{{1, 3}};

// Deterministic, non-round values so that any reordering or conversion shows up.
std::vector<double> values(std::size_t n, int step, double salt) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = salt + static_cast<double>(i) / 7.0 + step * 1.0e-3 - 1.0 / 3.0;
  return v;
}

struct StepData {
  double time;
  long step;
  std::vector<double> coords, velocity, thickness, stress, tension;

  explicit StepData(int k)
      : time(0.125 * k + 1.0e-9),
        step(1000L * k + 7),
        coords(values(3 * kNodes, k, 1.0)),
        velocity(values(3 * kNodes, k, -2.0)),
        thickness(values(2, k, 3.0)),
        stress(values(2 * 6, k, 4.0)),
        tension(values(1, k, 5.0)) {}

  std::vector<FieldView> fields() const {
    return {{"velocity", Center::Node, 3, velocity.data(), velocity.size()},
            {"thickness", Center::Triangle, 1, thickness.data(), thickness.size()},
            {"stress", Center::Triangle, 6, stress.data()},  // size left unknown on purpose
            {"tension", Center::Line, 1, tension.data(), tension.size()}};
  }
};

using test::ScratchDir;

// Minimal RAII for the test's own HDF5 reads.
struct H5Handle {
  hid_t id;
  herr_t (*closer)(hid_t);
  ~H5Handle() {
    if (id >= 0) closer(id);
  }
};

struct Dataset {
  std::vector<hsize_t> dims;
  std::vector<double> doubles;
  std::vector<int> ints;
};

Dataset readDataset(hid_t file, const std::string& path) {
  Dataset d;
  const H5Handle dset{H5Dopen2(file, path.c_str(), H5P_DEFAULT), H5Dclose};
  if (dset.id < 0) throw std::runtime_error("cannot open " + path);
  const H5Handle space{H5Dget_space(dset.id), H5Sclose};
  const int rank = H5Sget_simple_extent_ndims(space.id);
  d.dims.resize(static_cast<std::size_t>(rank));
  H5Sget_simple_extent_dims(space.id, d.dims.data(), nullptr);
  const auto n = static_cast<std::size_t>(H5Sget_simple_extent_npoints(space.id));
  const H5Handle type{H5Dget_type(dset.id), H5Tclose};
  if (H5Tget_class(type.id) == H5T_INTEGER) {
    d.ints.resize(n);
    if (n > 0) H5Dread(dset.id, H5T_NATIVE_INT, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.ints.data());
  } else {
    d.doubles.resize(n);
    if (n > 0) H5Dread(dset.id, H5T_NATIVE_DOUBLE, H5S_ALL, H5S_ALL, H5P_DEFAULT, d.doubles.data());
  }
  return d;
}

template <typename T>
T readAttribute(hid_t file, const std::string& object, const char* name, hid_t memType) {
  const H5Handle attr{H5Aopen_by_name(file, object.c_str(), name, H5P_DEFAULT, H5P_DEFAULT), H5Aclose};
  if (attr.id < 0) throw std::runtime_error("cannot open attribute " + object + "@" + name);
  T value{};
  H5Aread(attr.id, memType, &value);
  return value;
}

// H5Lexists needs every intermediate link to exist, so walk the path component by component.
bool pathExists(hid_t file, const std::string& path) {
  std::string prefix;
  std::istringstream parts(path);
  for (std::string part; std::getline(parts, part, '/');) {
    if (part.empty()) continue;
    prefix += "/" + part;
    if (H5Lexists(file, prefix.c_str(), H5P_DEFAULT) <= 0) return false;
  }
  return !prefix.empty();
}

std::string readText(const fs::path& p) {
  std::ifstream is(p);
  std::stringstream ss;
  ss << is.rdbuf();
  return ss.str();
}

std::size_t countOf(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto pos = text.find(what); pos != std::string::npos; pos = text.find(what, pos + 1)) ++n;
  return n;
}

struct Reference {
  std::vector<hsize_t> dims;
  std::string file, path;
};

std::vector<Reference> dataItems(const std::string& xdmf) {
  static const std::regex item(
      R"re(<DataItem Dimensions="([0-9 ]+)"[^>]*Format="HDF">([^:<]+):([^<]+)</DataItem>)re");
  std::vector<Reference> refs;
  for (auto it = std::sregex_iterator(xdmf.begin(), xdmf.end(), item); it != std::sregex_iterator(); ++it) {
    Reference r;
    std::istringstream dims((*it)[1].str());
    for (hsize_t d; dims >> d;) r.dims.push_back(d);
    r.file = (*it)[2].str();
    r.path = (*it)[3].str();
    refs.push_back(r);
  }
  return refs;
}

// Every DataItem names the h5 file relatively and points at an existing dataset of the declared shape.
void expectReferencesResolve(const fs::path& h5, const std::string& xdmf, std::size_t expectedItems) {
  const std::vector<Reference> refs = dataItems(xdmf);
  EXPECT_EQ(refs.size(), expectedItems);
  const H5Handle file{H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(file.id, 0) << h5;
  for (const Reference& r : refs) {
    EXPECT_EQ(r.file, h5.filename().string());
    ASSERT_TRUE(pathExists(file.id, r.path)) << r.path;
    EXPECT_EQ(readDataset(file.id, r.path).dims, r.dims) << r.path;
  }
}

std::size_t openHdf5Objects() {
  return static_cast<std::size_t>(H5Fget_obj_count(H5F_OBJ_ALL, H5F_OBJ_ALL));
}

// DataItems per step: membranes (topology, geometry, 3 attributes) + cables (topology, geometry, 2
// attributes).
constexpr std::size_t kItemsPerStep = 5 + 4;

TEST(ResultsWriter, StepsReadBackExactly) {
  const ScratchDir dir;
  const fs::path h5 = dir.path() / "out" / "results.h5";  // parent directory is created by the writer
  const std::size_t objectsBefore = openHdf5Objects();
  {
    ResultsWriter writer(h5, kNodes, kTriangles, kLines);
    for (int k = 0; k < 3; ++k) {
      const StepData s(k);
      writer.writeStep(s.time, s.step, s.coords.data(), s.fields());
    }
    EXPECT_EQ(writer.stepsWritten(), 3);
    EXPECT_EQ(writer.xdmfPath(), dir.path() / "out" / "results.xdmf");
    writer.close();
  }
  EXPECT_EQ(openHdf5Objects(), objectsBefore) << "HDF5 identifiers leaked";

  const H5Handle file{H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(file.id, 0);
  const Dataset tri = readDataset(file.id, "/mesh/triangles");
  EXPECT_EQ(tri.dims, (std::vector<hsize_t>{2, 3}));
  EXPECT_EQ(tri.ints, (std::vector<int>{0, 1, 2, 0, 2, 3}));
  const Dataset lines = readDataset(file.id, "/mesh/lines");
  EXPECT_EQ(lines.dims, (std::vector<hsize_t>{1, 2}));
  EXPECT_EQ(lines.ints, (std::vector<int>{1, 3}));

  for (int k = 0; k < 3; ++k) {
    const StepData s(k);
    const std::string g = "/steps/00000" + std::to_string(k);
    EXPECT_EQ(readAttribute<double>(file.id, g, "time", H5T_NATIVE_DOUBLE), s.time);
    EXPECT_EQ(readAttribute<long long>(file.id, g, "step", H5T_NATIVE_LLONG), s.step);
    const auto check = [&](const std::string& name, std::vector<hsize_t> dims,
                           const std::vector<double>& expected) {
      const Dataset d = readDataset(file.id, g + "/" + name);
      EXPECT_EQ(d.dims, dims) << g << "/" << name;
      EXPECT_EQ(d.doubles, expected) << g << "/" << name;  // exact: no conversion or reordering
    };
    check("coordinates", {kNodes, 3}, s.coords);
    check("velocity", {kNodes, 3}, s.velocity);
    check("thickness", {2}, s.thickness);
    check("stress", {2, 6}, s.stress);
    check("tension", {1}, s.tension);
  }
  EXPECT_FALSE(pathExists(file.id, "/steps/000003"));
}

TEST(ResultsXdmf, IndexIsCompleteAfterEveryStep) {
  const ScratchDir dir;
  const fs::path h5 = dir.path() / "results.h5";
  ResultsWriter writer(h5, kNodes, kTriangles, kLines);
  const fs::path xdmfPath = dir.path() / "results.xdmf";
  ASSERT_TRUE(fs::exists(xdmfPath)) << "an empty index is written at construction";
  EXPECT_EQ(countOf(readText(xdmfPath), "<Time "), 0u);

  for (int k = 0; k < 3; ++k) {
    const StepData s(k);
    writer.writeStep(s.time, s.step, s.coords.data(), s.fields());
    const std::string xdmf = readText(xdmfPath);
    const std::size_t steps = static_cast<std::size_t>(k) + 1;
    EXPECT_EQ(countOf(xdmf, "<Time "), 3 * steps);  // spatial collection + membranes + cables
    EXPECT_EQ(countOf(xdmf, "CollectionType=\"Spatial\""), steps);
    EXPECT_EQ(countOf(xdmf, "<Grid Name=\"membranes\""), steps);
    EXPECT_EQ(countOf(xdmf, "<Grid Name=\"cables\""), steps);
    EXPECT_EQ(countOf(xdmf, "results.h5:/steps/00000" + std::to_string(k) + "/coordinates"), 2u);
    EXPECT_EQ(xdmf.find(dir.path().string()), std::string::npos) << "paths must be relative";
    EXPECT_FALSE(fs::exists(xdmfPath.string() + ".tmp"));
    // While the writer is open, check a copy: it shows exactly what a crash would leave on disk.
    const fs::path copy = dir.path() / "copy" / "results.h5";
    fs::create_directories(copy.parent_path());
    fs::copy_file(h5, copy, fs::copy_options::overwrite_existing);
    expectReferencesResolve(copy, xdmf, kItemsPerStep * steps);
  }
}

// Structural check with a real XML parser (Python's ElementTree), if available.
TEST(ResultsXdmf, IsWellFormedWithExpectedGridsAndAttributes) {
  const char* python = "/usr/bin/python3";
  if (::access(python, X_OK) != 0) GTEST_SKIP() << "python3 not available";
  const ScratchDir dir;
  {
    ResultsWriter writer(dir.path() / "results.h5", kNodes, kTriangles, kLines);
    for (int k = 0; k < 3; ++k) {
      const StepData s(k);
      writer.writeStep(s.time, s.step, s.coords.data(), s.fields());
    }
  }  // destructor closes
  const fs::path script = dir.path() / "check.py";
  std::ofstream(script) << R"py(import sys, xml.etree.ElementTree as E
root = E.parse(sys.argv[1]).getroot()
assert root.tag == "Xdmf" and root.get("Version") == "3.0"
series = root.find("Domain/Grid")
assert series.get("CollectionType") == "Temporal"
steps = series.findall("Grid")
assert len(steps) == 3, len(steps)
for k, step in enumerate(steps):
    assert step.get("CollectionType") == "Spatial"
    t = float(step.find("Time").get("Value"))
    assert t == 0.125 * k + 1.0e-9, t
    grids = {g.get("Name"): g for g in step.findall("Grid")}
    assert sorted(grids) == ["cables", "membranes"], sorted(grids)
    expected = {"membranes": {"velocity": ("Node", "Vector"), "thickness": ("Cell", "Scalar"),
                              "stress": ("Cell", "Tensor6")},
                "cables": {"velocity": ("Node", "Vector"), "tension": ("Cell", "Scalar")}}
    for name, g in grids.items():
        assert float(g.find("Time").get("Value")) == t
        topo = g.find("Topology")
        assert topo.get("TopologyType") == ("Triangle" if name == "membranes" else "Polyline")
        assert topo.get("NodesPerElement") == ("3" if name == "membranes" else "2")
        geo = g.find("Geometry/DataItem").text
        assert geo == "results.h5:/steps/%06d/coordinates" % k, geo
        attrs = {a.get("Name"): (a.get("Center"), a.get("AttributeType")) for a in g.findall("Attribute")}
        assert attrs == expected[name], attrs
)py";
  const std::string command =
      std::string(python) + " " + script.string() + " " + (dir.path() / "results.xdmf").string();
  EXPECT_EQ(std::system(command.c_str()), 0) << command;
}

TEST(ResultsXdmf, MembraneOnlyMeshHasNoCablesGrid) {
  const ScratchDir dir;
  const fs::path h5 = dir.path() / "results.h5";
  {
    ResultsWriter writer(h5, kNodes, kTriangles, {});
    const StepData s(0);
    writer.writeStep(
        s.time, s.step, s.coords.data(),
        {{"velocity", Center::Node, 3, s.velocity.data()}, {"tension", Center::Line, 1, nullptr, 0}});
  }
  const std::string xdmf = readText(dir.path() / "results.xdmf");
  EXPECT_EQ(countOf(xdmf, "<Grid Name=\"membranes\""), 1u);
  EXPECT_EQ(countOf(xdmf, "cables"), 0u);
  EXPECT_EQ(countOf(xdmf, "tension"), 0u);
  expectReferencesResolve(h5, xdmf, 3);
}

TEST(ResultsWriter, TableRoundTripAndReplacement) {
  const ScratchDir dir;
  const fs::path h5 = dir.path() / "results.h5";
  const std::vector<std::string> columns{"time", "kinetic", "strain energy"};
  const std::vector<std::vector<double>> last{values(5, 0, 0.0), values(5, 1, 1.0), values(5, 2, 2.0)};
  {
    ResultsWriter writer(h5, kNodes, kTriangles, kLines);
    writer.writeTable("energies", columns, {values(2, 0, 9.0), values(2, 1, 9.0), values(2, 2, 9.0)});
    writer.writeTable("energies", columns, last);  // histories are rewritten whole
    writer.writeTable("empty", {"a"}, {{}});
    writer.close();
    writer.close();  // idempotent
  }
  const H5Handle file{H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  ASSERT_GE(file.id, 0);
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const Dataset d = readDataset(file.id, "/tables/energies/" + columns[i]);
    EXPECT_EQ(d.dims, (std::vector<hsize_t>{5}));
    EXPECT_EQ(d.doubles, last[i]);
  }
  EXPECT_EQ(readDataset(file.id, "/tables/empty/a").dims, (std::vector<hsize_t>{0}));
}

template <typename F>
std::string invalidArgumentMessage(F&& f) {
  try {
    f();
  } catch (const std::invalid_argument& e) {
    return e.what();
  }
  ADD_FAILURE() << "no std::invalid_argument thrown";
  return {};
}

TEST(ResultsWriter, RejectsInconsistentInputNamingTheField) {
  const ScratchDir dir;
  ResultsWriter writer(dir.path() / "results.h5", kNodes, kTriangles, kLines);
  const StepData s(0);
  auto write = [&](std::vector<FieldView> fields) { writer.writeStep(0.0, 0, s.coords.data(), fields); };

  // Line-sized data declared as a triangle field: count/center mismatch.
  EXPECT_NE(invalidArgumentMessage([&] {
              write({{"tension", Center::Triangle, 1, s.tension.data(), 1}});
            }).find("tension"),
            std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] {
              write({{"velocity", Center::Node, 3, s.velocity.data(), 3}});
            }).find("velocity"),
            std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] {
              write({{"weird", Center::Node, 4, s.velocity.data()}});
            }).find("weird"),
            std::string::npos);
  EXPECT_NE(invalidArgumentMessage([&] {
              write({{"nodata", Center::Node, 1, nullptr}});
            }).find("nodata"),
            std::string::npos);
  EXPECT_NE(
      invalidArgumentMessage([&] {
        write({{"twice", Center::Line, 1, s.tension.data()}, {"twice", Center::Line, 1, s.tension.data()}});
      }).find("twice"),
      std::string::npos);
  invalidArgumentMessage([&] { write({{"a/b", Center::Line, 1, s.tension.data()}}); });
  invalidArgumentMessage([&] { write({{"coordinates", Center::Node, 3, s.velocity.data()}}); });
  invalidArgumentMessage([&] { writer.writeTable("t", {"a", "b"}, {{1.0}, {1.0, 2.0}}); });
  invalidArgumentMessage([&] { writer.writeTable("t", {"a"}, {}); });
  invalidArgumentMessage([&] { ResultsWriter bad(dir.path() / "bad.h5", 2, kTriangles, {}); });

  // Rejected calls leave nothing behind: the next step still gets index 000000.
  EXPECT_EQ(writer.stepsWritten(), 0);
  writer.writeStep(s.time, s.step, s.coords.data(), s.fields());
  EXPECT_EQ(writer.stepsWritten(), 1);
  EXPECT_NE(readText(writer.xdmfPath()).find("/steps/000000/coordinates"), std::string::npos);
}

TEST(ResultsWriter, WritesAfterCloseThrow) {
  const ScratchDir dir;
  ResultsWriter writer(dir.path() / "results.h5", kNodes, kTriangles, kLines);
  writer.close();
  const StepData s(0);
  EXPECT_THROW(writer.writeStep(s.time, s.step, s.coords.data(), s.fields()), std::logic_error);
  EXPECT_THROW(writer.writeTable("t", {"a"}, {{1.0}}), std::logic_error);
}

TEST(ResultsWriter, IoFailureNamesTheFile) {
  const ScratchDir dir;
  const fs::path blocked = dir.path() / "is_a_directory.h5";
  fs::create_directories(blocked);
  try {
    ResultsWriter writer(blocked, kNodes, kTriangles, kLines);
    FAIL() << "expected std::runtime_error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find(blocked.string()), std::string::npos) << e.what();
  }
}

// ---------------------------------------------------------------------------------------------------------
// Append mode: a restarted run continues one series.

std::vector<double> stepTimes(const fs::path& h5) {
  const H5Handle file{H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  std::vector<double> times;
  for (int k = 0; k < 100; ++k) {
    char g[32];
    std::snprintf(g, sizeof g, "/steps/%06d", k);
    if (pathExists(file.id, g)) times.push_back(readAttribute<double>(file.id, g, "time", H5T_NATIVE_DOUBLE));
  }
  return times;
}

std::vector<double> xdmfTimes(const fs::path& xdmf) {
  static const std::regex grid(
      R"re(<Grid Name="step_\d+" GridType="Collection" CollectionType="Spatial">\s*<Time Value="([^"]+)"/>)re");
  const std::string text = readText(xdmf);
  std::vector<double> times;
  for (auto it = std::sregex_iterator(text.begin(), text.end(), grid); it != std::sregex_iterator(); ++it)
    times.push_back(std::stod((*it)[1].str()));
  return times;
}

TEST(ResultsWriterAppend, ContinuesTheSeriesAndDropsLaterSteps) {
  const ScratchDir dir;
  const fs::path h5 = dir.path() / "results.h5";
  const std::size_t objectsBefore = openHdf5Objects();
  {
    ResultsWriter w(h5, kNodes, kTriangles, kLines);
    for (int k = 0; k < 5; ++k) {  // times 0.125 k + 1e-9
      const StepData s(k);
      w.writeStep(s.time, s.step, s.coords.data(), s.fields());
    }
    w.writeTable("energy", {"time", "kinetic"}, {{0.0, 0.25, 0.5}, {1.0, 2.0, 3.0}});
    w.writeRootAttribute("restart_times", {0.25});
  }
  {
    // Restart at t = 0.25 (step 2): steps 3 and 4 are a stale future.
    ResultsWriter w = ResultsWriter::append(h5, kNodes, kTriangles, kLines, 0.3);
    EXPECT_EQ(w.stepsWritten(), 3);
    EXPECT_DOUBLE_EQ(w.lastStepTime(), StepData(2).time);
    EXPECT_EQ(xdmfTimes(dir.path() / "results.xdmf").size(), 3u) << "the index is rewritten at once";
    const auto [columns, data] = w.readTable("energy");
    EXPECT_EQ(columns, (std::vector<std::string>{"time", "kinetic"}));  // table order, not name order
    EXPECT_EQ(data[1], (std::vector<double>{1.0, 2.0, 3.0}));
    EXPECT_TRUE(w.readTable("missing").first.empty());
    EXPECT_EQ(w.rootAttribute("restart_times"), (std::vector<double>{0.25}));
    EXPECT_TRUE(w.rootAttribute("none").empty());
    for (const double t : {0.3125, 0.4375}) {
      const StepData s(7);
      w.writeStep(t, 99, s.coords.data(), s.fields());
    }
    EXPECT_EQ(w.stepsWritten(), 5);
  }
  EXPECT_EQ(openHdf5Objects(), objectsBefore) << "HDF5 identifiers leaked";
  const std::vector<double> expected{StepData(0).time, StepData(1).time, StepData(2).time, 0.3125, 0.4375};
  EXPECT_EQ(stepTimes(h5), expected);
  EXPECT_EQ(xdmfTimes(dir.path() / "results.xdmf"), expected);
  // The kept steps are untouched; the new ones hold what was written; the index resolves everywhere.
  const H5Handle file{H5Fopen(h5.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose};
  EXPECT_EQ(readDataset(file.id, "/steps/000001/velocity").doubles, StepData(1).velocity);
  EXPECT_EQ(readDataset(file.id, "/steps/000003/coordinates").doubles, StepData(7).coords);
  EXPECT_EQ(readAttribute<long long>(file.id, "/steps/000004", "step", H5T_NATIVE_LLONG), 99);
  expectReferencesResolve(h5, readText(dir.path() / "results.xdmf"), 5 * kItemsPerStep);
}

TEST(ResultsWriterAppend, RestartFromAnEarlierTimeAndAMissingFile) {
  const ScratchDir dir;
  const fs::path h5 = dir.path() / "results.h5";
  {
    // A missing file is started as by the constructor.
    ResultsWriter w = ResultsWriter::append(h5, kNodes, kTriangles, kLines, 1.0);
    EXPECT_EQ(w.stepsWritten(), 0);
    EXPECT_EQ(w.lastStepTime(), -std::numeric_limits<double>::infinity());
    for (int k = 0; k < 4; ++k) {
      const StepData s(k);
      w.writeStep(s.time, s.step, s.coords.data(), s.fields());
    }
  }
  // First a restart at step 2, which writes on; then one from step 0: only step 0 is left before it.
  {
    ResultsWriter w = ResultsWriter::append(h5, kNodes, kTriangles, kLines, StepData(2).time);
    const StepData s(5);
    w.writeStep(0.3, s.step, s.coords.data(), s.fields());
  }
  {
    ResultsWriter w = ResultsWriter::append(h5, kNodes, kTriangles, kLines, StepData(0).time);
    const StepData s(6);
    w.writeStep(0.1, s.step, s.coords.data(), s.fields());
  }
  EXPECT_EQ(stepTimes(h5), (std::vector<double>{StepData(0).time, 0.1}));
  EXPECT_EQ(xdmfTimes(dir.path() / "results.xdmf"), (std::vector<double>{StepData(0).time, 0.1}));
}

TEST(ResultsWriterAppend, AnotherMeshIsRefusedNamingTheFile) {
  const ScratchDir dir;
  const fs::path h5 = dir.path() / "results.h5";
  { ResultsWriter w(h5, kNodes, kTriangles, kLines); }
  for (int attempt = 0; attempt < 2; ++attempt) {
    try {
      if (attempt == 0)
        ResultsWriter::append(h5, kNodes + 1, kTriangles, kLines, 1.0);
      else
        ResultsWriter::append(h5, kNodes, {{0, 1, 2}, {0, 3, 2}}, kLines, 1.0);
      FAIL() << "expected std::runtime_error";
    } catch (const std::runtime_error& e) {
      EXPECT_NE(std::string(e.what()).find(h5.string()), std::string::npos) << e.what();
      EXPECT_NE(std::string(e.what()).find("another mesh"), std::string::npos) << e.what();
    }
  }
}

}  // namespace
}  // namespace fsi::structure
