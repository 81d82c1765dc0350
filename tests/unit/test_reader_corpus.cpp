// Malformed input corpus (tests/corpus): files that crashed the readers, made them allocate without bound,
// run a script, or read a wrong value without a word (Gmsh files through the Gmsh library, OpenFOAM polyMesh
// files through an unchecked parser). Each must now give an fsi::InputError that names the file, the line
// (ASCII) or byte offset (binary), and what is wrong. tests/corpus/run_cli.sh checks the exit code 2 of
// `fsi map-check` on the same files.

#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <functional>
#include <string>
#include <vector>

#include "coupling/interface/InterfaceIO.hpp"
#include "coupling/mapping/MapCheck.hpp"
#include "structure/io/GmshReader.hpp"
#include "structure/model/Error.hpp"

namespace fsi {
namespace {

namespace fs = std::filesystem;

fs::path corpus(const std::string& name) {
  return fs::path(FSI_SOURCE_DIR) / "tests" / "corpus" / name;
}

void expectLocated(const std::function<void()>& f, const std::vector<std::string>& words) {
  try {
    f();
    ADD_FAILURE() << "no InputError";
  } catch (const InputError& e) {
    for (const std::string& w : words)
      EXPECT_NE(std::string(e.what()).find(w), std::string::npos) << e.what();
  }
}

struct GmshCase {
  const char* file;
  const char* location;  // appended to the path: ":line: in $Section" or ", byte N: in $Section"
  const char* what;
};

TEST(ReaderCorpus, GmshFilesGiveLocatedErrors) {
  const GmshCase cases[] = {
      // Crashed the Gmsh library (SIGSEGV, heap corruption) or made it allocate 3e12 nodes.
      {"physical_name_dim4.msh", ":6: in $PhysicalNames", "dimension is 4"},
      {"element_node_minus1.msh", ":31: in $Elements", "-1"},
      {"nodes_header_inconsistent.msh", ":16: in $Nodes", "3, outside [0, 2]"},
      {"huge_node_count.msh", ":15: in $Nodes", "3000000000000"},
      {"element_count_beyond_file.msh", ":27: in $Elements", "2000000000 elements announced"},
      {"msh22_version_40.msh", ":2: in $MeshFormat", "version 4.0"},
      // Bytes inserted at offset 2013: the node tag read at 2012 runs into them.
      {"binary_inserted_bytes.msh", ", byte 2012: in $Elements", "which is not in $Nodes"},
      // Read as infinity or NaN before.
      {"coordinate_1e400.msh", ":22: in $Nodes", "'1e400' is out of range"},
      {"coordinate_nan.msh", ":23: in $Nodes", "'nan' is not a finite number"},
  };
  for (const GmshCase& c : cases) {
    SCOPED_TRACE(c.file);
    const fs::path file = corpus("gmsh") / c.file;
    expectLocated([&] { structure::readGmsh(file, "x"); }, {file.string() + c.location, c.what});
    expectLocated([&] { coupling::readInterface(file.string()); }, {file.string() + c.location, c.what});
  }
}

TEST(ReaderCorpus, GmshScriptsAreNeverRun) {
  // Both files hold `System "touch fsi_corpus_geo_script_was_executed";`: the Gmsh library ran it for a
  // scene's `file: script.geo`, and even for a script named .msh. Now neither is interpreted.
  const fs::path marker = "fsi_corpus_geo_script_was_executed";  // relative: where Gmsh would run it
  fs::remove(marker);
  const fs::path geo = corpus("gmsh") / "script.geo", named = corpus("gmsh") / "script_named_msh.msh";
  expectLocated([&] { structure::readGmsh(geo, "x"); },
                {geo.string(), "Gmsh script, not a mesh", "gmsh -2 " + geo.string() + " -format msh41"});
  expectLocated([&] { structure::readGmsh(named, "x"); },
                {named.string(), "does not start with $MeshFormat"});
  expectLocated([&] { coupling::readInterface(named.string()); }, {named.string(), "$MeshFormat"});
  EXPECT_FALSE(fs::exists(marker));
}

TEST(ReaderCorpus, OpenFoamFilesGiveLocatedErrors) {
  struct Case {
    const char* dir;
    const char* file;  // polyMesh file and ":line:"
    const char* what;
  };
  const Case cases[] = {
      // startFace + nFaces overflowed past the bounds check: SIGSEGV.
      {"boundary_startface_overflow",
       "boundary:14:", "9223372036854775807 faces from face 9223372036854775807"},
      // Read as 0 entries before.
      {"boundary_count_overflow", "boundary:10:", "'99999999999999999999' is out of range"},
      // std::bad_alloc (exit 1, no location) before.
      {"points_huge_count", "points:10:", "announces 3000000000000 entries"},
      {"faces_huge_count", "faces:10:", "announces 3000000000000 entries"},
      // Read as (0 0 0), label 0 and NaN before, and mapped without a word.
      {"point_1e400", "points:13:", "'1e400' is out of range"},
      {"face_label_overflow", "faces:16:", "'18446744073709551623' is out of range"},
      {"point_nan", "points:16:", "'nan' is not a finite number"},
      // Issue 35, item 10: read as if valid (exit 0, "all points mapped") before. Every patch is checked,
      // not only the one asked for ('walls' here).
      {"boundary_duplicate_patch", "boundary:13:", "patch 'inlet' is defined twice (first at line 12)"},
      {"boundary_startface_internal",
       "boundary:12:", "patch 'inlet' starts at face 0, inside the 1 internal faces"},
      {"boundary_patch_overlap",
       "boundary:13:", "patch 'outlet' starts at face 1, but patch 'inlet' ends at face 2"},
      {"boundary_other_patch_past_end", "boundary:13:", "patch 'outlet' has 1 faces from face 11"},
  };
  for (const Case& c : cases) {
    SCOPED_TRACE(c.dir);
    const fs::path dir = corpus("openfoam") / c.dir;
    const std::string file = (dir / "constant" / "polyMesh" / c.file).string();
    expectLocated([&] { coupling::readOpenFoamPatch(dir, "walls"); }, {file, c.what});
    expectLocated([&] { coupling::readInterface(dir.string() + ":walls"); }, {file, c.what});
  }
  // The case all of them were made from reads.
  EXPECT_EQ(coupling::readOpenFoamPatch(corpus("openfoam") / "valid_two_cells", "walls").numFaces(), 8);
}

// A flat square of n x n quads scaled by `scale`, as an interface mesh.
coupling::InterfaceMesh square(int n, double scale, const std::string& name) {
  coupling::InterfaceMesh m;
  m.name = name;
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i) m.points.push_back({scale * i / n, scale * j / n, 0.0});
  m.faceOffsets = {0};
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = j * (n + 1) + i;
      for (const int v : {a, a + 1, a + n + 2, a + n + 1}) m.faceNodes.push_back(v);
      m.faceOffsets.push_back(int(m.faceNodes.size()));
    }
  return m;
}

TEST(ReaderCorpus, MapCheckNeverPassesBesideNaN) {
  // 1e308 is a valid double, so the reader accepts it; map-check printed "all points mapped" beside -nan.
  const fs::path big = corpus("gmsh") / "coordinate_1e308.msh", good = corpus("gmsh") / "valid_square_41.msh";
  coupling::MapCheckOptions options;
  options.applyRepeats = 1;
  const coupling::InterfaceMesh a = coupling::readInterface(big.string()),
                                b = coupling::readInterface(good.string());
  expectLocated([&] { coupling::runMapCheck(a, b, options); }, {big.string(), "coordinate x", "rescale"});
  // Coordinates of 1e-200 pass that check, but the areas underflow: an infinite moment error was printed.
  expectLocated([&] { coupling::runMapCheck(square(4, 1e-200, "tiny"), square(4, 1e-200, "tiny"), options); },
                {"map-check tiny -> tiny", "is inf"});
  // Ordinary coordinates still pass.
  EXPECT_TRUE(coupling::runMapCheck(square(4, 1.0, "a"), square(4, 1.0, "b"), options).allMapped());
}

}  // namespace
}  // namespace fsi
