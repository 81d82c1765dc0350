// Output of a coupled run that continues across restarts: structure/coupling.csv (CouplingCsv),
// structure/timing.json (CouplingTiming), and the participant's results series, tables and clock.
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <sstream>
#include <string>
#include <tuple>
#include <vector>

#include "TestScenes.hpp"
#include "coupling/CouplingCsv.hpp"
#include "coupling/CouplingTiming.hpp"
#include "coupling/StructureParticipant.hpp"
#include "structure/io/ResultsWriter.hpp"
#include "structure/model/Error.hpp"
#include "structure/scene/Scene.hpp"

using namespace fsi::coupling;
namespace fs = std::filesystem;

namespace {

fs::path scratch() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const fs::path p = fs::path(FSI_BINARY_DIR) / "test-output" /
                     ("coupling-output-" + std::string(info->name()) + "-" + std::to_string(::getpid()));
  fs::remove_all(p);
  fs::create_directories(p);
  return p;
}

std::vector<std::string> lines(const fs::path& p) {
  std::ifstream is(p);
  std::vector<std::string> out;
  for (std::string l; std::getline(is, l);) out.push_back(l);
  return out;
}

const std::string kHeader = "time,iterations,mid_z";

void writeRows(CouplingCsv& csv, int from, int to) {  // times k / 100
  for (int k = from; k <= to; ++k) {
    std::ostringstream os;
    os << k / 100.0 << ",1," << k;
    csv.row(os.str());
  }
}

}  // namespace

TEST(CouplingCsv, RestartKeepsRowsUpToTheRestartAndMarksIt) {
  const fs::path file = scratch() / "coupling.csv";
  {
    CouplingCsv csv(file, kHeader);
    writeRows(csv, 1, 6);
  }
  {
    CouplingCsv csv(file, kHeader, CsvRestart{0.04 + 0.005, "0.04"});
    writeRows(csv, 5, 8);
  }
  EXPECT_EQ(lines(file), (std::vector<std::string>{kHeader, "0.01,1,1", "0.02,1,2", "0.03,1,3", "0.04,1,4",
                                                   "# restart at t = 0.04", "0.05,1,5", "0.06,1,6",
                                                   "0.07,1,7", "0.08,1,8"}));
  // Again from the same time: one mark, not two.
  {
    CouplingCsv csv(file, kHeader, CsvRestart{0.04 + 0.005, "0.04"});
    writeRows(csv, 5, 5);
  }
  EXPECT_EQ(lines(file), (std::vector<std::string>{kHeader, "0.01,1,1", "0.02,1,2", "0.03,1,3", "0.04,1,4",
                                                   "# restart at t = 0.04", "0.05,1,5"}));
  // A restart from an earlier time drops the later rows and the later restart's mark with them.
  {
    CouplingCsv csv(file, kHeader, CsvRestart{0.02 + 0.005, "0.02"});
    writeRows(csv, 3, 3);
  }
  EXPECT_EQ(lines(file),
            (std::vector<std::string>{kHeader, "0.01,1,1", "0.02,1,2", "# restart at t = 0.02", "0.03,1,3"}));
  // A fresh run starts the file again; a restart without a file starts one.
  { CouplingCsv csv(file, kHeader); }
  EXPECT_EQ(lines(file), std::vector<std::string>{kHeader});
  fs::remove(file);
  { CouplingCsv csv(file, kHeader, CsvRestart{1.0, "1"}); }
  EXPECT_EQ(lines(file), (std::vector<std::string>{kHeader, "# restart at t = 1"}));
}

TEST(CouplingCsv, ChangedColumnsOrABrokenRowAreRefusedNamingTheFile) {
  const fs::path file = scratch() / "coupling.csv";
  { CouplingCsv csv(file, kHeader); }
  try {
    CouplingCsv csv(file, kHeader + ",tip_z", CsvRestart{1.0, "1"});
    FAIL() << "expected fsi::InputError";
  } catch (const fsi::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string()), std::string::npos) << e.what();
  }
  std::ofstream(file) << kHeader << "\nabc,1,1\n";
  try {
    CouplingCsv csv(file, kHeader, CsvRestart{1.0, "1"});
    FAIL() << "expected fsi::InputError";
  } catch (const fsi::InputError& e) {
    EXPECT_NE(std::string(e.what()).find(file.string() + ", line 2"), std::string::npos) << e.what();
  }
}

TEST(CouplingTiming, TotalsAreTheSumOfTheSegments) {
  const fs::path file = scratch() / "timing.json";
  TimingSegment a;
  a.startTime = 0;
  a.endTime = 0.25;
  a.wallSeconds = 10;
  a.structureSeconds = 2;
  a.windows = 25;
  a.fluidSolves = 70;
  a.iterations = 70;
  a.maxIterations = 5;
  a.structuralSteps = 250;
  CouplingTiming(file).write(a);
  TimingSegment b = a;
  b.startTime = 0.25;
  b.endTime = 0.5;
  b.wallSeconds = 12;
  b.iterations = 80;
  b.maxIterations = 4;
  b.ranks = 2;
  const CouplingTiming restarted(file, 0.25, 0.005);
  ASSERT_EQ(restarted.earlier().size(), 1u);
  restarted.write(b);
  const nlohmann::json j = nlohmann::json::parse(std::ifstream(file));
  EXPECT_EQ(j["segments"].size(), 2u);
  EXPECT_EQ(j["restart_times"], nlohmann::json::array({0.25}));
  EXPECT_DOUBLE_EQ(j["wall_seconds"].get<double>(), 22.0);
  EXPECT_EQ(j["windows"].get<long>(), 50);
  EXPECT_EQ(j["iterations"].get<long>(), 150);
  EXPECT_DOUBLE_EQ(j["mean_iterations"].get<double>(), 3.0);
  EXPECT_EQ(j["max_iterations"].get<long>(), 5);
  EXPECT_EQ(j["structural_steps"].get<long>(), 500);
  EXPECT_DOUBLE_EQ(j["start_time"].get<double>(), 0.0);
  EXPECT_DOUBLE_EQ(j["end_time"].get<double>(), 0.5);
  EXPECT_EQ(j["ranks"].get<int>(), 2);
  // A restart from an earlier time forgets the segments that started later.
  const CouplingTiming again(file, 0.1, 0.005);
  ASSERT_EQ(again.earlier().size(), 1u);
  EXPECT_DOUBLE_EQ(again.earlier()[0].startTime, 0.0);
  EXPECT_TRUE(CouplingTiming(file, 0.0, 0.005).earlier().empty());
  std::ofstream(file) << "{ not json";
  EXPECT_THROW(CouplingTiming(file, 0.25, 0.005), fsi::InputError);
}

// ---------------------------------------------------------------------------------------------------------
// The participant across a restart

namespace {

const std::string kDrum = fsi::test::drumScene(R"(effects:
  pressure: {triangles: sheet, value: 100}
coupling: {interface: sheet}
probes:
  centre_z: {type: displacement, nodes: {box: {min: [-0.01, -0.01, -1], max: [0.01, 0.01, 1]}}, component: z, reduce: mean}
time: {end: 1.0}
)");

StructureParticipant drum() {
  fsi::coupling::ParticipantOptions options;
  options.loadKind = fsi::structure::InterfaceLoadKind::NodalForces;
  return StructureParticipant(fsi::structure::loadSceneFromString(kDrum, "drum.yaml"), options);
}

// n windows of dt through solve() with the scheme's clock t0 + k dt and zero interface forces.
void run(StructureParticipant& s, double t0, double dt, int from, int to, bool record = false) {
  const Eigen::VectorXd f = Eigen::VectorXd::Zero(3 * s.numInterfaceNodes());
  for (int k = from; k < to; ++k) {
    s.solve(t0 + k * dt, dt, f, f);
    if (record) s.recordHistory(t0 + (k + 1) * dt);
  }
}

}  // namespace

TEST(StructureParticipantClock, WindowEndsComeFromTheSchemesClockWithoutDrift) {
  // 1000 windows of 0.01 s: summing the window size drifts to 9.999999999999831; the scheme's clock
  // t0 + k dt does not. (An unloaded drum: only the clock matters here.)
  fsi::coupling::ParticipantOptions options;
  options.loadKind = fsi::structure::InterfaceLoadKind::NodalForces;
  StructureParticipant s(
      fsi::structure::loadSceneFromString(
          fsi::test::drumScene("coupling: {interface: sheet}\ntime: {end: 1.0}\n"), "drum.yaml"),
      options);
  run(s, 0.0, 0.01, 0, 1000);
  EXPECT_LE(std::abs(s.time() - 10.0), 2e-15) << std::setprecision(17) << s.time();
  double sum = 0;
  for (int k = 0; k < 1000; ++k) sum += 0.01;
  EXPECT_GT(std::abs(sum - 10.0), 1e-13);  // what the structure's own running sum would have been
}

TEST(StructureParticipantResults, EnergiesProbesAndFramesContinueAcrossARestart) {
  const fs::path dir = scratch();
  const double dt = 1e-3;
  // Continuous: 20 windows, a frame every 5, tables every window.
  StructureParticipant c = drum();
  c.openResults(dir / "continuous.h5");
  c.recordHistory(0.0);
  ASSERT_TRUE(c.writeResults(0.0));
  EXPECT_FALSE(c.writeResults(0.0)) << "one frame per time";
  for (int k = 0; k < 20; ++k) {
    run(c, 0.0, dt, k, k + 1, true);
    if ((k + 1) % 5 == 0) c.writeResults((k + 1) * dt);
  }
  // Segment 1 to window 15 (state written at 10), then a restart from window 10.
  StructureParticipant a = drum();
  a.openResults(dir / "restarted.h5");
  a.recordHistory(0.0);
  a.writeResults(0.0);
  for (int k = 0; k < 15; ++k) {
    run(a, 0.0, dt, k, k + 1, true);
    if ((k + 1) % 5 == 0) a.writeResults((k + 1) * dt);
    if (k + 1 == 10) a.writeState(dir / "state10.h5");
  }
  a = drum();  // closes the file
  StructureParticipant b = drum();
  b.readState(dir / "state10.h5");
  b.openResults(dir / "restarted.h5", 10 * dt + 0.5 * dt);
  b.noteRestart(10 * dt);
  EXPECT_EQ(b.framesWritten(), 3);  // 0, 5, 10 kept; 15 dropped
  EXPECT_FALSE(b.writeResults(10 * dt));
  for (int k = 10; k < 20; ++k) {
    run(b, 0.0, dt, k, k + 1, true);
    if ((k + 1) % 5 == 0) b.writeResults((k + 1) * dt);
  }
  c = drum();
  b = drum();

  // Read back through the append mode (keeping everything), with the scene's mesh.
  const fsi::structure::Scene scene = fsi::structure::loadSceneFromString(kDrum, "drum.yaml");
  const auto& model = *scene.model;
  std::vector<std::array<int, 3>> tris(model.membranes.count);
  for (int e = 0; e < model.membranes.count; ++e)
    tris[e] = {model.membranes.conn[3 * e], model.membranes.conn[3 * e + 1], model.membranes.conn[3 * e + 2]};
  auto read = [&](const fs::path& h5) {
    auto w = fsi::structure::ResultsWriter::append(h5, model.nodes.count, tris, {}, 1e300);
    return std::tuple{w.readTable("energy"), w.readTable("probes"), w.stepsWritten(), w.lastStepTime(),
                      w.rootAttribute("restart_times")};
  };
  const auto [ce, cp, cFrames, cLast, cRestarts] = read(dir / "continuous.h5");
  const auto [re, rp, rFrames, rLast, rRestarts] = read(dir / "restarted.h5");
  EXPECT_EQ(cFrames, 5);
  EXPECT_EQ(rFrames, 5);
  EXPECT_DOUBLE_EQ(rLast, 20 * dt);
  EXPECT_TRUE(cRestarts.empty());
  EXPECT_EQ(rRestarts, std::vector<double>{10 * dt});
  // Same rows, same times (0, dt, ..., 20 dt), same values: the energy ledger went through the state file.
  ASSERT_EQ(re.first, ce.first);
  ASSERT_EQ(rp.first, (std::vector<std::string>{"time", "centre_z"}));
  ASSERT_EQ(re.second[0].size(), 21u);
  ASSERT_EQ(rp.second[0].size(), 21u);
  for (std::size_t i = 0; i < ce.second.size(); ++i)
    for (std::size_t k = 0; k < 21; ++k)
      EXPECT_NEAR(re.second[i][k], ce.second[i][k], 1e-12 * (1 + std::abs(ce.second[i][k])))
          << re.first[i] << " row " << k;
  for (std::size_t k = 0; k < 21; ++k) EXPECT_DOUBLE_EQ(rp.second[1][k], cp.second[1][k]) << k;
  EXPECT_GT(ce.second[3].back(), 0.0) << "external work is done";
  EXPECT_GT(ce.second[2].back(), 0.0) << "strain energy is evaluated on the window's last step";
  EXPECT_LT(ce.second[6].back(), 0.05) << "energy balance";
}
