#include "structure/io/MshReader.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <climits>
#include <cstdint>
#include <fstream>
#include <new>
#include <set>
#include <stdexcept>
#include <string_view>
#include <system_error>

#include "structure/io/MshInput.hpp"
#include "structure/io/MshSections.hpp"
#include "structure/io/TextNumbers.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {

namespace fs = std::filesystem;

std::string MshContent::where(std::size_t at) const {
  return binary ? fmt::format("{}, byte {}", file, at) : fmt::format("{}:{}", file, at);
}

int mshNodesPerElement(int type) {
  switch (type) {
    case kMshLine2:
      return 2;
    case kMshTriangle3:
      return 3;
    case kMshQuad4:
      return 4;
    case kMshPoint:
      return 1;
    default:
      return 0;
  }
}

const char* mshElementTypeName(int type) {
  // Gmsh's names of its element types 1..31 (the ones with a fixed node count that Gmsh writes).
  static const char* const names[] = {
      "Line 2",        "Triangle 3", "Quadrilateral 4", "Tetrahedron 4",   "Hexahedron 8",   "Prism 6",
      "Pyramid 5",     "Line 3",     "Triangle 6",      "Quadrilateral 9", "Tetrahedron 10", "Hexahedron 27",
      "Prism 18",      "Pyramid 14", "Point",           "Quadrilateral 8", "Hexahedron 20",  "Prism 15",
      "Pyramid 13",    "Triangle 9", "Triangle 10",     "Triangle 12",     "Triangle 15",    "Triangle 15I",
      "Triangle 21",   "Line 4",     "Line 5",          "Line 6",          "Tetrahedron 20", "Tetrahedron 35",
      "Tetrahedron 56"};
  if (type >= 1 && type <= int(std::size(names))) return names[type - 1];
  return "unknown";
}

namespace msh {

void NodeIndex::reserve(long long numNodes, long long maxTag) {
  // Gmsh numbers nodes 1..N: a table twice the node count (plus a little) holds the usual files.
  const long long size = std::min(maxTag, 2 * numNodes + 1024) + 1;
  dense_.assign(std::size_t(std::max(size, 0LL)), -1);
  sparse_.clear();
}

bool NodeIndex::add(long long tag, int index) {
  if (tag >= 0 && static_cast<unsigned long long>(tag) < dense_.size()) {
    int& slot = dense_[std::size_t(tag)];
    if (slot >= 0) return false;
    slot = index;
    return true;
  }
  return sparse_.emplace(tag, index).second;
}

int elementDimension(int type) {
  switch (type) {
    case kMshLine2:
      return 1;
    case kMshTriangle3:
    case kMshQuad4:
      return 2;
    case kMshPoint:
      return 0;
    default:
      return -1;
  }
}

void failUnsupportedType(const MshInput& in, long long elementTag, long long type) {
  const std::string name = type >= INT_MIN && type <= INT_MAX ? mshElementTypeName(int(type)) : "unknown";
  // Higher-order curves and surfaces are the usual mistake; say how to avoid them.
  const bool higherOrder =
      name.rfind("Line", 0) == 0 || name.rfind("Triangle", 0) == 0 || name.rfind("Quadrilateral", 0) == 0;
  in.fail(fmt::format(
      "element {} has unsupported Gmsh element type {} ('{}'); supported types are 2-node lines (1), 3-node "
      "triangles (2) and 4-node quadrangles (3), points (15) are ignored{}",
      elementTag, type, name, higherOrder ? " (mesh with first-order elements: Mesh.ElementOrder = 1)" : ""));
}

void readPhysicalNames(MshInput& in, MshContent& mesh) {
  const long long count = in.textInteger("the number of physical names", 0, INT_MAX);
  in.checkCount(count, 7, "physical names");  // 0 1 "" and a line break
  for (long long n = 0; n < count; ++n) {
    const int dim = int(in.textInteger("a physical group dimension", 0, 3));
    const std::size_t where = in.mark();
    const int tag = int(in.textInteger("a physical tag", 1, INT_MAX));
    std::string name = in.quoted("a physical name");
    if (!mesh.physicalNames.emplace(MshContent::DimTag{dim, tag}, std::move(name)).second)
      throw InputError(fmt::format("{}: in $PhysicalNames: physical group ({}, {}) is named twice",
                                   in.where(where), dim, tag));
  }
  in.expect("$EndPhysicalNames");
}

}  // namespace msh

namespace {

std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  return s;
}

std::string meshItFirst(const fs::path& file) {
  fs::path out = file;
  out.replace_extension(".msh");
  if (out == file) out.replace_filename(file.stem().string() + "_mesh.msh");
  return fmt::format(
      "fsi reads meshes only and never runs Gmsh scripts; mesh it first, e.g. 'gmsh -2 {} "
      "-format msh41 -o {}', and give the .msh file",
      file.string(), out.string());
}

std::string readBytes(const fs::path& file) {
  const std::string where = file.string();
  std::error_code ec;
  const fs::file_status status = fs::status(file, ec);
  if (!fs::exists(status)) throw InputError(fmt::format("{}: no such file (a Gmsh .msh mesh)", where));
  if (!fs::is_regular_file(status)) throw InputError(fmt::format("{}: not a regular file", where));
  const std::uintmax_t size = fs::file_size(file, ec);
  std::ifstream in(file, std::ios::binary);
  if (ec || !in) throw InputError(fmt::format("{}: the file cannot be opened for reading", where));
  std::string bytes;
  try {
    bytes.resize(std::size_t(size));
  } catch (const std::exception&) {  // bad_alloc or length_error
    throw InputError(fmt::format("{}: the file ({} bytes) is too large to read into memory", where, size));
  }
  in.read(bytes.data(), std::streamsize(size));
  if (std::uintmax_t(in.gcount()) != size)
    throw InputError(fmt::format("{}: read {} of its {} bytes (the file changed or cannot be read)", where,
                                 in.gcount(), size));
  return bytes;
}

MshContent parse(const fs::path& file, std::string bytes) {
  MshContent mesh;
  mesh.file = file.string();
  MshInput in(mesh.file, std::move(bytes));

  const std::string_view first = in.token();
  if (first == "$NOD" || first == "$NOE")
    in.fail(
        fmt::format("MSH version 1 is not supported; convert it to 4.1: gmsh {} -save -format msh41 -o "
                    "new.msh",
                    mesh.file));
  if (first != "$MeshFormat")
    throw InputError(fmt::format("{}: not a Gmsh MSH mesh (it does not start with $MeshFormat). {}",
                                 mesh.file, meshItFirst(file)));
  in.setSection("MeshFormat");
  const std::string_view versionText = in.token();
  double version = 0;
  if (parseReal(versionText, version) != NumberStatus::Ok)
    in.fail(fmt::format("expected the MSH version but found '{}'", printable(versionText)));
  const bool binary = in.textInteger("the file type (0 ASCII, 1 binary)", 0, 1) == 1;
  const long long dataSize = in.textInteger("the data size", INT_MIN, INT_MAX);
  const bool v2 = version >= 2.0 && version < 3.0;
  if (!v2 && version != 4.1)
    in.fail(
        fmt::format("MSH version {} is not supported (2.2 and 4.1 are); convert it: gmsh {} -save -format "
                    "msh41 -o new.msh",
                    printable(versionText), mesh.file));
  if (dataSize != 8) in.fail(fmt::format("data size {} is not supported (8 expected)", dataSize));
  if (binary) {
    // The int 1, written in the writer's byte order.
    in.endLine();
    in.setBinary(false);
    const long long one = in.int32("the byte order mark (the int 1)", INT32_MIN, INT32_MAX);
    if (one == 0x01000000)
      in.setBinary(true);
    else if (one != 1)
      in.fail(fmt::format("the byte order mark is {} (1 expected)", one));
  }
  mesh.binary = binary;
  in.expect("$EndMeshFormat");

  msh::NodeIndex index;
  bool haveNodes = false, haveElements = false;
  while (!in.atEnd()) {
    in.setSection("");
    const std::string_view t = in.token();
    if (t.size() < 2 || t[0] != '$')
      in.fail(fmt::format("expected a section start such as $Nodes but found '{}'", printable(t)));
    const std::string name(t.substr(1));
    if (name.rfind("End", 0) == 0) in.fail(fmt::format("{} without its section start", printable(t)));
    in.setSection(name);
    if (name == "PhysicalNames") {
      msh::readPhysicalNames(in, mesh);
    } else if (name == "Entities" && !v2) {
      msh::readEntities4(in, mesh);
    } else if (name == "PartitionedEntities") {
      in.fail("partitioned meshes are not supported; save the mesh unpartitioned");
    } else if (name == "Nodes" || (name == "ParametricNodes" && v2)) {
      if (haveNodes) in.fail("a second $Nodes section");
      haveNodes = true;
      if (v2)
        msh::readNodes2(in, mesh, index, name == "ParametricNodes");
      else
        msh::readNodes4(in, mesh, index);
    } else if (name == "Elements") {
      if (!haveNodes) in.fail("$Elements before $Nodes (the nodes must come first)");
      if (haveElements) in.fail("a second $Elements section");
      haveElements = true;
      if (v2)
        msh::readElements2(in, mesh, index);
      else
        msh::readElements4(in, mesh, index);
    } else {
      in.skipSection(name);  // $Comments, $Periodic, $NodeData, ...: nothing the project uses
    }
  }
  return mesh;
}

}  // namespace

MshContent readMshFile(const fs::path& file) {
  const std::string extension = lower(file.extension().string());
  if (extension == ".geo" || extension == ".geo_unrolled" || extension == ".py")
    throw InputError(
        fmt::format("{}: this is a Gmsh script, not a mesh. {}", file.string(), meshItFirst(file)));
  std::string bytes = readBytes(file);
  const std::size_t size = bytes.size();
  try {
    return parse(file, std::move(bytes));
  } catch (const std::bad_alloc&) {
    // Every allocation is bounded by a small multiple of the file size; this machine has not that much.
    throw InputError(fmt::format("{}: not enough memory to read this {}-byte mesh", file.string(), size));
  }
}

}  // namespace fsi::structure
