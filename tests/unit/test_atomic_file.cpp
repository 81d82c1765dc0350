// replaceFileAtomically, the one way state files and the XDMF index of a results series are replaced.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "TestScenes.hpp"
#include "structure/io/AtomicFile.hpp"

using namespace fsi::structure;
namespace fs = std::filesystem;

namespace {
std::string contentOf(const fs::path& f) {
  std::ifstream in(f);
  return std::string(std::istreambuf_iterator<char>(in), {});
}
void writeText(const fs::path& f, const std::string& text) {
  std::ofstream(f) << text;
}
}  // namespace

TEST(AtomicFile, ReplacesTheContentAndLeavesNoTemporary) {
  const fs::path dir = fsi::test::outDir("atomic-replace");
  fs::create_directories(dir);
  const fs::path file = dir / "index.xdmf";
  writeText(file, "old");
  replaceFileAtomically(file, "test", [](const fs::path& tmp) { writeText(tmp, "new"); });
  EXPECT_EQ(contentOf(file), "new");
  EXPECT_FALSE(fs::exists(dir / "index.xdmf.tmp"));
}

// A writer that fails part-way: the file keeps its previous content, the temporary goes, the writer's own
// error comes through.
TEST(AtomicFile, AFailedWriteKeepsThePreviousContent) {
  const fs::path dir = fsi::test::outDir("atomic-failed");
  fs::create_directories(dir);
  const fs::path file = dir / "state.h5";
  writeText(file, "previous");
  EXPECT_THROW(replaceFileAtomically(file, "test",
                                     [](const fs::path& tmp) {
                                       writeText(tmp, "half");
                                       throw std::runtime_error("disk full");
                                     }),
               std::runtime_error);
  EXPECT_EQ(contentOf(file), "previous");
  EXPECT_FALSE(fs::exists(dir / "state.h5.tmp"));
}

// A writer that made no file: the sync fails with a message naming the operation and the file.
TEST(AtomicFile, AMissingTemporaryIsReportedNamingTheFile) {
  const fs::path dir = fsi::test::outDir("atomic-missing");
  fs::create_directories(dir);
  const fs::path file = dir / "index.xdmf";
  try {
    replaceFileAtomically(file, "ResultsWriter", [](const fs::path&) {});
    FAIL() << "no error";
  } catch (const std::runtime_error& e) {
    const std::string what = e.what();
    EXPECT_NE(what.find("ResultsWriter: cannot sync"), std::string::npos) << what;
    EXPECT_NE(what.find("index.xdmf.tmp"), std::string::npos) << what;
  }
  EXPECT_FALSE(fs::exists(file));
}
