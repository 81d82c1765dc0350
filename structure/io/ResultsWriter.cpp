#include "structure/io/ResultsWriter.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <fstream>
#include <iterator>
#include <limits>
#include <set>
#include <stdexcept>
#include <system_error>
#include <utility>

#include "structure/io/AtomicFile.hpp"
#include "structure/io/Hdf5File.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure {
namespace {

namespace fs = std::filesystem;

static_assert(sizeof(std::array<int, 3>) == 3 * sizeof(int) && sizeof(std::array<int, 2>) == 2 * sizeof(int),
              "connectivity arrays are written as contiguous int blocks");

using hdf5::Hid;

// Error context: every failure names the file and the object concerned.
struct Context : hdf5::Context {
  Hid createGroup(hid_t parent, const std::string& name, const std::string& fullName) const {
    return check(H5Gcreate2(parent, name.c_str(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT), H5Gclose,
                 "cannot create group", fullName);
  }

  // Contiguous layout on purpose: output writes are large and rare, chunking/compression would only cost.
  Hid writeDataset(hid_t parent, const std::string& name, const std::string& fullName, hid_t fileType,
                   hid_t memType, const void* data, const std::vector<hsize_t>& dims) const {
    const Hid space = check(H5Screate_simple(static_cast<int>(dims.size()), dims.data(), nullptr), H5Sclose,
                            "cannot create dataspace for", fullName);
    Hid dset =
        check(H5Dcreate2(parent, name.c_str(), fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT, H5P_DEFAULT),
              H5Dclose, "cannot create dataset", fullName);
    hsize_t total = 1;
    for (const hsize_t d : dims) total *= d;
    if (total > 0) {
      check(H5Dwrite(dset.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, data), "cannot write dataset",
            fullName);
    }
    return dset;
  }

  template <typename T>
  void writeScalarAttribute(hid_t object, const char* name, hid_t fileType, hid_t memType, const T& value,
                            const std::string& objectName) const {
    const std::string full = objectName + "@" + name;
    const Hid space = check(H5Screate(H5S_SCALAR), H5Sclose, "cannot create dataspace for", full);
    const Hid attr = check(H5Acreate2(object, name, fileType, space.get(), H5P_DEFAULT, H5P_DEFAULT),
                           H5Aclose, "cannot create attribute", full);
    check(H5Awrite(attr.get(), memType, &value), "cannot write attribute", full);
  }

  void writeStringAttribute(hid_t object, const char* name, const std::string& value,
                            const std::string& objectName) const {
    const std::string full = objectName + "@" + name;
    const Hid type = check(H5Tcopy(H5T_C_S1), H5Tclose, "cannot create string type for", full);
    check(H5Tset_size(type.get(), value.size() + 1), "cannot size string type for", full);  // with the NUL
    const Hid space = check(H5Screate(H5S_SCALAR), H5Sclose, "cannot create dataspace for", full);
    const Hid attr = check(H5Acreate2(object, name, type.get(), space.get(), H5P_DEFAULT, H5P_DEFAULT),
                           H5Aclose, "cannot create attribute", full);
    check(H5Awrite(attr.get(), type.get(), value.c_str()), "cannot write attribute", full);
  }
};

// Reading back (append mode, --start-from): attributes through hdf5::readScalarAttribute /
// readStringAttribute, which check each one's shape and type first. Failures name the file and object like
// the writes.
using hdf5::readScalarAttribute;
using hdf5::readStringAttribute;

// Dimensions and values of a dataset, read as memType (int or double).
template <typename T>
std::vector<T> readDataset(const Context& c, hid_t parent, const std::string& name,
                           const std::string& fullName, hid_t memType, std::vector<hsize_t>& dims) {
  const Hid dset =
      c.check(H5Dopen2(parent, name.c_str(), H5P_DEFAULT), H5Dclose, "cannot open dataset", fullName);
  const Hid space = c.check(H5Dget_space(dset.get()), H5Sclose, "cannot read the shape of", fullName);
  const int rank = H5Sget_simple_extent_ndims(space.get());
  if (rank < 0) c.fail("cannot read the shape of", fullName);
  dims.assign(static_cast<std::size_t>(rank), 0);
  H5Sget_simple_extent_dims(space.get(), dims.data(), nullptr);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  std::vector<T> values(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
  if (!values.empty())
    c.check(H5Dread(dset.get(), memType, H5S_ALL, H5S_ALL, H5P_DEFAULT, values.data()), "cannot read dataset",
            fullName);
  return values;
}

// Names of the links in a group, in name order.
std::vector<std::string> linkNames(const Context& c, hid_t group, const std::string& groupName) {
  H5G_info_t info;
  c.check(H5Gget_info(group, &info), "cannot list", groupName);
  std::vector<std::string> names;
  for (hsize_t i = 0; i < info.nlinks; ++i) {
    const ssize_t size =
        H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, nullptr, 0, H5P_DEFAULT);
    if (size < 0) c.fail("cannot list", groupName);
    std::string name(static_cast<std::size_t>(size) + 1, '\0');
    H5Lget_name_by_idx(group, ".", H5_INDEX_NAME, H5_ITER_INC, i, name.data(), name.size(), H5P_DEFAULT);
    name.resize(static_cast<std::size_t>(size));
    names.push_back(name);
  }
  return names;
}

const char* attributeType(int components) {
  switch (components) {
    case 1:
      return "Scalar";
    case 3:
      return "Vector";
    default:
      return "Tensor6";
  }
}

// HDF5 link names may not contain '/', and "." names the parent itself.
void checkName(const std::string& name, const char* kind) {
  if (name.empty() || name == "." || name.find('/') != std::string::npos) {
    throw std::invalid_argument(
        fmt::format("ResultsWriter: invalid {} name '{}' (must be non-empty, without '/')", kind, name));
  }
}

std::string xmlEscape(const std::string& s) {
  std::string out;
  out.reserve(s.size());
  for (const char c : s) {
    switch (c) {
      case '&':
        out += "&amp;";
        break;
      case '<':
        out += "&lt;";
        break;
      case '>':
        out += "&gt;";
        break;
      case '"':
        out += "&quot;";
        break;
      case '\'':
        out += "&apos;";
        break;
      default:
        out += c;
    }
  }
  return out;
}

std::string stepGroupName(std::size_t index) {
  return fmt::format("{:06d}", index);
}

}  // namespace

struct ResultsWriter::Impl {
  struct FieldMeta {
    std::string name;
    std::string center;  // "Node" or a cell set's center name
    int components;
  };
  struct StepRecord {
    std::string group;  // 6-digit index below /steps
    double time;
    std::vector<FieldMeta> fields;
  };

  fs::path h5Path;
  fs::path xdmfPath;
  int numNodes = 0;
  std::vector<CellSet> cells;  // in the order given: the order of the grids
  Hid file;
  Hid steps;
  Hid tables;
  std::vector<StepRecord> records;
  std::size_t nextIndex = 0;  // of the next step group (append mode: after the kept ones)

  Context ctx() const { return Context{{h5Path, "ResultsWriter"}}; }
  static std::unique_ptr<Impl> prepare(fs::path h5File, int numNodes, std::vector<CellSet> cells);
  void create();
  void open(double keepUntil);

  // The cell set whose fields have center `center`; nullptr for "Node" or an unknown one.
  const CellSet* cellSet(const std::string& center) const {
    for (const CellSet& s : cells)
      if (s.center == center) return &s;
    return nullptr;
  }
  std::size_t count(const std::string& center) const {
    if (center == "Node") return static_cast<std::size_t>(numNodes);
    const CellSet* s = cellSet(center);
    return s ? s->cells() : 0;
  }

  void requireOpen(const char* operation) const {
    if (!file.valid()) {
      throw std::logic_error(
          fmt::format("ResultsWriter::{} called after close() for '{}'", operation, h5Path.string()));
    }
  }

  void flush() const { ctx().check(H5Fflush(file.get(), H5F_SCOPE_LOCAL), "cannot flush", ""); }

  void writeXdmf() const;

  // Groups first, the file last; the flush status is checked because it performs the final metadata write.
  void close() {
    if (!file.valid()) return;
    const hdf5::QuietErrors quiet;
    std::string error;
    auto note = [&error](herr_t status, const char* what) {
      if (status < 0 && error.empty()) error = what + hdf5::errorDetail();
    };
    note(steps.close(), "cannot close /steps");
    note(tables.close(), "cannot close /tables");
    note(H5Fflush(file.get(), H5F_SCOPE_LOCAL), "cannot flush");
    note(file.close(), "cannot close");
    if (!error.empty())
      throw std::runtime_error(fmt::format("ResultsWriter: {} in '{}'", error, h5Path.string()));
  }

  ~Impl() {
    try {
      close();
    } catch (...) {
      // Never throw from a destructor; callers who need to know call close() themselves.
    }
  }
};

void ResultsWriter::Impl::writeXdmf() const {
  const std::string h5Name = xmlEscape(h5Path.filename().string());  // relative: the folder may be moved
  const std::size_t n = static_cast<std::size_t>(numNodes);
  std::string x;
  auto out = std::back_inserter(x);
  auto dataItem = [&](const std::string& dims, const char* type, int precision, const std::string& path,
                      int indent) {
    fmt::format_to(out,
                   "{:{}}<DataItem Dimensions=\"{}\" NumberType=\"{}\" Precision=\"{}\" "
                   "Format=\"HDF\">{}:{}</DataItem>\n",
                   "", indent, dims, type, precision, h5Name, xmlEscape(path));
  };

  x += "<?xml version=\"1.0\" ?>\n<!DOCTYPE Xdmf SYSTEM \"Xdmf.dtd\" []>\n";
  x += "<Xdmf Version=\"3.0\" xmlns:xi=\"http://www.w3.org/2001/XInclude\">\n  <Domain>\n";
  x += "    <Grid Name=\"TimeSeries\" GridType=\"Collection\" CollectionType=\"Temporal\">\n";
  for (const StepRecord& r : records) {
    const std::string time = fmt::format("{}", r.time);  // shortest representation that round-trips
    const std::string stepPath = "/steps/" + r.group;
    fmt::format_to(out, "      <Grid Name=\"step_{}\" GridType=\"Collection\" CollectionType=\"Spatial\">\n",
                   r.group);
    fmt::format_to(out, "        <Time Value=\"{}\"/>\n", time);

    auto grid = [&](const std::string& name, const std::string& topology, int nodesPerElement,
                    std::size_t numElements, const std::string& connectivity, const std::string& cellCenter) {
      fmt::format_to(out, "        <Grid Name=\"{}\" GridType=\"Uniform\">\n", name);
      fmt::format_to(out, "          <Time Value=\"{}\"/>\n", time);
      fmt::format_to(
          out, "          <Topology TopologyType=\"{}\" NumberOfElements=\"{}\" NodesPerElement=\"{}\">\n",
          topology, numElements, nodesPerElement);
      dataItem(fmt::format("{} {}", numElements, nodesPerElement), "Int", 4, connectivity, 12);
      x += "          </Topology>\n          <Geometry GeometryType=\"XYZ\">\n";
      dataItem(fmt::format("{} 3", n), "Float", 8, stepPath + "/coordinates", 12);
      x += "          </Geometry>\n";
      for (const FieldMeta& f : r.fields) {
        if (f.center != "Node" && f.center != cellCenter) continue;
        const std::size_t cnt = count(f.center);
        fmt::format_to(out, "          <Attribute Name=\"{}\" AttributeType=\"{}\" Center=\"{}\">\n",
                       xmlEscape(f.name), attributeType(f.components), f.center == "Node" ? "Node" : "Cell");
        dataItem(f.components == 1 ? fmt::format("{}", cnt) : fmt::format("{} {}", cnt, f.components),
                 "Float", 8, stepPath + "/" + f.name, 12);
        x += "          </Attribute>\n";
      }
      x += "        </Grid>\n";
    };
    // One grid per element kind's cell set that has cells, in the order given.
    for (const CellSet& s : cells)
      if (s.cells() > 0) grid(s.grid, s.topology, s.nodesPerCell, s.cells(), "/mesh/" + s.dataset, s.center);
    x += "      </Grid>\n";
  }
  x += "    </Grid>\n  </Domain>\n</Xdmf>\n";

  // Replace atomically so that a reader (or a crash) never sees a half-written index.
  replaceFileAtomically(xdmfPath, "ResultsWriter", [&](const fs::path& tmp) {
    std::ofstream os(tmp, std::ios::binary | std::ios::trunc);
    os.write(x.data(), static_cast<std::streamsize>(x.size()));
    os.close();
    if (!os) throw std::runtime_error(fmt::format("ResultsWriter: cannot write '{}'", tmp.string()));
  });
}

namespace {

void checkCells(const std::vector<CellSet>& cells, int numNodes) {
  std::set<std::string> centers, datasets;
  for (const CellSet& s : cells) {
    checkName(s.dataset, "cell set");
    if (s.center == "Node" || s.center.empty() || !centers.insert(s.center).second ||
        !datasets.insert(s.dataset).second || s.nodesPerCell <= 0 ||
        s.conn.size() % static_cast<std::size_t>(s.nodesPerCell) != 0)
      throw std::invalid_argument(fmt::format(
          "ResultsWriter: cell set '{}' (center '{}') is given twice, is named 'Node' or has a partial cell",
          s.dataset, s.center));
    for (std::size_t i = 0; i < s.conn.size(); ++i) {
      const int node = s.conn[i];
      if (node < 0 || node >= numNodes) {
        throw std::invalid_argument(fmt::format("ResultsWriter: {} {} references node {} outside [0, {})",
                                                s.dataset, i / static_cast<std::size_t>(s.nodesPerCell), node,
                                                numNodes));
      }
    }
  }
}

}  // namespace

void ResultsWriter::Impl::create() {
  const hdf5::QuietErrors quiet;
  const Context c = ctx();
  file = c.check(H5Fcreate(h5Path.c_str(), H5F_ACC_TRUNC, H5P_DEFAULT, H5P_DEFAULT), H5Fclose,
                 "cannot create file", "");
  c.writeScalarAttribute(file.get(), "num_nodes", H5T_STD_I64LE, H5T_NATIVE_LLONG,
                         static_cast<long long>(numNodes), "/");
  {
    const Hid mesh = c.createGroup(file.get(), "mesh", "/mesh");
    for (const CellSet& s : cells)
      c.writeDataset(mesh.get(), s.dataset, "/mesh/" + s.dataset, H5T_STD_I32LE, H5T_NATIVE_INT,
                     s.conn.data(), {s.cells(), static_cast<hsize_t>(s.nodesPerCell)});
  }
  steps = c.createGroup(file.get(), "steps", "/steps");
  tables = c.createGroup(file.get(), "tables", "/tables");
  flush();
  writeXdmf();  // an empty but valid index replaces any stale one from a previous run
}

void ResultsWriter::Impl::open(double keepUntil) {
  const hdf5::QuietErrors quiet;
  const Context c = ctx();
  file =
      c.check(H5Fopen(h5Path.c_str(), H5F_ACC_RDWR, H5P_DEFAULT), H5Fclose, "cannot open for appending", "");
  // The series must be of this mesh: a restart with another scene starts a new file instead.
  const auto nodes = readScalarAttribute<long long>(c, file.get(), "num_nodes", "/");
  bool same = nodes == numNodes;
  std::string held = fmt::format("{} nodes", nodes), given = fmt::format("{} nodes", numNodes);
  for (const CellSet& s : cells) {
    const std::string path = "/mesh/" + s.dataset;
    std::vector<hsize_t> dims;
    const std::vector<int> conn =
        H5Lexists(file.get(), path.c_str(), H5P_DEFAULT) > 0
            ? readDataset<int>(c, file.get(), path.substr(1), path, H5T_NATIVE_INT, dims)
            : std::vector<int>{-1};
    same = same && conn == s.conn;
    held += fmt::format(", {} {}", conn.size() / static_cast<std::size_t>(s.nodesPerCell), s.dataset);
    given += fmt::format(", {}", s.cells());
  }
  if (!same)
    throw std::runtime_error(fmt::format(
        "ResultsWriter: cannot continue '{}': it holds another mesh ({}; this run has {}); move it away to "
        "start a new series",
        h5Path.string(), held, given));
  steps = c.check(H5Gopen2(file.get(), "steps", H5P_DEFAULT), H5Gclose, "cannot open group", "/steps");
  tables = c.check(H5Gopen2(file.get(), "tables", H5P_DEFAULT), H5Gclose, "cannot open group", "/tables");

  std::vector<std::string> stale;
  for (const std::string& name : linkNames(c, steps.get(), "/steps")) {
    const std::string groupPath = "/steps/" + name;
    const Hid group =
        c.check(H5Gopen2(steps.get(), name.c_str(), H5P_DEFAULT), H5Gclose, "cannot open group", groupPath);
    const double time = readScalarAttribute<double>(c, group.get(), "time", groupPath);
    if (!(time <= keepUntil)) {
      stale.push_back(name);
      continue;
    }
    StepRecord r{name, time, {}};
    for (const std::string& field : linkNames(c, group.get(), groupPath)) {
      if (field == "coordinates") continue;
      const std::string path = groupPath + "/" + field;
      const Hid dset =
          c.check(H5Dopen2(group.get(), field.c_str(), H5P_DEFAULT), H5Dclose, "cannot open dataset", path);
      const Hid space = c.check(H5Dget_space(dset.get()), H5Sclose, "cannot read the shape of", path);
      hsize_t dims[2] = {0, 1};
      const int rank = H5Sget_simple_extent_ndims(space.get());
      if (rank < 1 || rank > 2) c.fail("unexpected rank of", path);
      H5Sget_simple_extent_dims(space.get(), dims, nullptr);
      r.fields.push_back({field, readStringAttribute(c, dset.get(), "center", path),
                          rank == 1 ? 1 : static_cast<int>(dims[1])});
    }
    nextIndex = std::max(nextIndex, static_cast<std::size_t>(std::stoul(name)) + 1);
    records.push_back(std::move(r));
  }
  for (const std::string& name : stale)
    c.check(H5Ldelete(steps.get(), name.c_str(), H5P_DEFAULT), "cannot drop the later step",
            "/steps/" + name);
  flush();
  writeXdmf();
}

// Everything both constructors do before touching the file.
std::unique_ptr<ResultsWriter::Impl> ResultsWriter::Impl::prepare(fs::path h5File, int numNodes,
                                                                  std::vector<CellSet> cells) {
  if (numNodes < 0) throw std::invalid_argument("ResultsWriter: negative node count");
  checkCells(cells, numNodes);
  auto m = std::make_unique<Impl>();
  m->h5Path = std::move(h5File);
  m->xdmfPath = m->h5Path;
  m->xdmfPath.replace_extension(".xdmf");
  m->numNodes = numNodes;
  m->cells = std::move(cells);
  if (m->h5Path.has_parent_path()) {
    std::error_code ec;
    fs::create_directories(m->h5Path.parent_path(), ec);
    if (ec) {
      throw std::runtime_error(fmt::format("ResultsWriter: cannot create directory '{}': {}",
                                           m->h5Path.parent_path().string(), ec.message()));
    }
  }
  return m;
}

std::vector<CellSet> ResultsWriter::surfaceAndLines(const std::vector<std::array<int, 3>>& triangles,
                                                    const std::vector<std::array<int, 2>>& lines) {
  CellSet t{"membranes", "triangles", "Triangle", "Triangle", 3, {}};
  for (const auto& e : triangles) t.conn.insert(t.conn.end(), e.begin(), e.end());
  CellSet l{"cables", "lines", "Line", "Polyline", 2, {}};
  for (const auto& e : lines) l.conn.insert(l.conn.end(), e.begin(), e.end());
  return {std::move(t), std::move(l)};
}

ResultsWriter::ResultsWriter(fs::path h5File, int numNodes, std::vector<CellSet> cells)
    : impl_(Impl::prepare(std::move(h5File), numNodes, std::move(cells))) {
  impl_->create();
}

ResultsWriter::ResultsWriter(fs::path h5File, int numNodes, const std::vector<std::array<int, 3>>& triangles,
                             const std::vector<std::array<int, 2>>& lines)
    : ResultsWriter(std::move(h5File), numNodes, surfaceAndLines(triangles, lines)) {}

ResultsWriter ResultsWriter::append(fs::path h5File, int numNodes, std::vector<CellSet> cells,
                                    double keepUntil) {
  ResultsWriter w;
  w.impl_ = Impl::prepare(std::move(h5File), numNodes, std::move(cells));
  std::error_code ec;
  if (fs::exists(w.impl_->h5Path, ec))
    w.impl_->open(keepUntil);
  else
    w.impl_->create();
  return w;
}

ResultsWriter ResultsWriter::append(fs::path h5File, int numNodes,
                                    const std::vector<std::array<int, 3>>& triangles,
                                    const std::vector<std::array<int, 2>>& lines, double keepUntil) {
  return append(std::move(h5File), numNodes, surfaceAndLines(triangles, lines), keepUntil);
}

ResultsWriter::~ResultsWriter() = default;  // Impl closes the file
ResultsWriter::ResultsWriter(ResultsWriter&&) noexcept = default;
ResultsWriter& ResultsWriter::operator=(ResultsWriter&&) noexcept = default;

void ResultsWriter::writeStep(double time, long step, const double* coordinates,
                              const std::vector<FieldView>& fields) {
  Impl& m = *impl_;
  m.requireOpen("writeStep");
  if (!std::isfinite(time))
    throw std::invalid_argument(fmt::format("ResultsWriter: non-finite time {}", time));
  if (coordinates == nullptr && m.numNodes > 0)
    throw std::invalid_argument("ResultsWriter: null coordinates");

  // Validate everything before touching the file so that a bad call leaves no partial step behind.
  std::set<std::string> names;
  for (const FieldView& f : fields) {
    checkName(f.name, "field");
    if (f.name == "coordinates" || !names.insert(f.name).second) {
      throw std::invalid_argument(
          fmt::format("ResultsWriter: field '{}' is reserved or given twice", f.name));
    }
    if (f.components != 1 && f.components != 3 && f.components != 6) {
      throw std::invalid_argument(fmt::format(
          "ResultsWriter: field '{}' has {} components; expected 1, 3 or 6", f.name, f.components));
    }
    const std::string center = f.centerName();
    if (center != "Node" && m.cellSet(center) == nullptr)
      throw std::invalid_argument(fmt::format(
          "ResultsWriter: field '{}' is centred on '{}', a cell set the file does not have", f.name, center));
    const std::size_t expected = m.count(center) * static_cast<std::size_t>(f.components);
    if (f.size != FieldView::kUnknownSize && f.size != expected) {
      throw std::invalid_argument(fmt::format(
          "ResultsWriter: field '{}' has {} values but {} {}-centred entities x {} components need {}",
          f.name, f.size, m.count(center), center, f.components, expected));
    }
    if (f.data == nullptr && expected > 0) {
      throw std::invalid_argument(fmt::format("ResultsWriter: field '{}' has no data", f.name));
    }
  }

  const hdf5::QuietErrors quiet;
  const Context c = m.ctx();
  Impl::StepRecord record{stepGroupName(m.nextIndex), time, {}};
  const std::string groupPath = "/steps/" + record.group;
  try {
    const Hid group = c.createGroup(m.steps.get(), record.group, groupPath);
    c.writeScalarAttribute(group.get(), "time", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, time, groupPath);
    c.writeScalarAttribute(group.get(), "step", H5T_STD_I64LE, H5T_NATIVE_LLONG, static_cast<long long>(step),
                           groupPath);
    const hsize_t n = static_cast<hsize_t>(m.numNodes);
    c.writeDataset(group.get(), "coordinates", groupPath + "/coordinates", H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                   coordinates, {n, 3});
    for (const FieldView& f : fields) {
      const std::string path = groupPath + "/" + f.name;
      const std::string center = f.centerName();
      std::vector<hsize_t> dims{m.count(center)};
      if (f.components > 1) dims.push_back(static_cast<hsize_t>(f.components));
      const Hid dset =
          c.writeDataset(group.get(), f.name, path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE, f.data, dims);
      c.writeStringAttribute(dset.get(), "center", center, path);
      if (f.components == 6) c.writeStringAttribute(dset.get(), "component_order", "xx yy zz xy yz xz", path);
      record.fields.push_back({f.name, center, f.components});
    }
  } catch (...) {
    // Drop the partial group so that the index can be reused; best effort, the original error matters.
    H5Ldelete(m.steps.get(), record.group.c_str(), H5P_DEFAULT);
    throw;
  }
  m.flush();
  m.records.push_back(std::move(record));
  ++m.nextIndex;
  try {
    m.writeXdmf();
  } catch (...) {
    // Forget the step entirely so that the next call can reuse its index.
    H5Ldelete(m.steps.get(), m.records.back().group.c_str(), H5P_DEFAULT);
    m.records.pop_back();
    --m.nextIndex;
    throw;
  }
}

void ResultsWriter::writeTable(const std::string& name, const std::vector<std::string>& columns,
                               const std::vector<std::vector<double>>& data) {
  Impl& m = *impl_;
  m.requireOpen("writeTable");
  checkName(name, "table");
  if (columns.size() != data.size()) {
    throw std::invalid_argument(fmt::format("ResultsWriter: table '{}' has {} column names but {} columns",
                                            name, columns.size(), data.size()));
  }
  std::set<std::string> names;
  for (std::size_t i = 0; i < columns.size(); ++i) {
    checkName(columns[i], "column");
    if (!names.insert(columns[i]).second) {
      throw std::invalid_argument(
          fmt::format("ResultsWriter: table '{}' repeats column '{}'", name, columns[i]));
    }
    if (data[i].size() != data.front().size()) {
      throw std::invalid_argument(
          fmt::format("ResultsWriter: table '{}' column '{}' has {} rows, column '{}' has {}", name,
                      columns[i], data[i].size(), columns.front(), data.front().size()));
    }
  }

  const hdf5::QuietErrors quiet;
  const Context c = m.ctx();
  const std::string groupPath = "/tables/" + name;
  // Histories are rewritten whole at each output; the old copy's space is not reclaimed, which is negligible.
  const htri_t exists = H5Lexists(m.tables.get(), name.c_str(), H5P_DEFAULT);
  if (exists < 0) c.fail("cannot query", groupPath);
  if (exists > 0) c.check(H5Ldelete(m.tables.get(), name.c_str(), H5P_DEFAULT), "cannot replace", groupPath);
  const Hid group = c.createGroup(m.tables.get(), name, groupPath);
  for (std::size_t i = 0; i < columns.size(); ++i) {
    const std::string path = groupPath + "/" + columns[i];
    const Hid dset = c.writeDataset(group.get(), columns[i], path, H5T_IEEE_F64LE, H5T_NATIVE_DOUBLE,
                                    data[i].data(), {data[i].size()});
    // HDF5 lists links by name: the position keeps the table's column order for readTable.
    c.writeScalarAttribute(dset.get(), "column", H5T_STD_I64LE, H5T_NATIVE_LLONG, static_cast<long long>(i),
                           path);
  }
  m.flush();
}

std::pair<std::vector<std::string>, std::vector<std::vector<double>>> ResultsWriter::readTable(
    const std::string& name) const {
  const Impl& m = *impl_;
  m.requireOpen("readTable");
  checkName(name, "table");
  const hdf5::QuietErrors quiet;
  const Context c = m.ctx();
  const std::string groupPath = "/tables/" + name;
  const htri_t exists = H5Lexists(m.tables.get(), name.c_str(), H5P_DEFAULT);
  if (exists < 0) c.fail("cannot query", groupPath);
  if (exists == 0) return {};
  const Hid group =
      c.check(H5Gopen2(m.tables.get(), name.c_str(), H5P_DEFAULT), H5Gclose, "cannot open group", groupPath);
  struct Column {
    long long position;
    std::string name;
    std::vector<double> data;
  };
  std::vector<Column> cols;
  for (const std::string& column : linkNames(c, group.get(), groupPath)) {
    const std::string path = groupPath + "/" + column;
    std::vector<hsize_t> dims;
    Column col{std::numeric_limits<long long>::max(), column,
               readDataset<double>(c, group.get(), column, path, H5T_NATIVE_DOUBLE, dims)};
    const Hid dset =
        c.check(H5Dopen2(group.get(), column.c_str(), H5P_DEFAULT), H5Dclose, "cannot open dataset", path);
    if (H5Aexists(dset.get(), "column") > 0)
      col.position = readScalarAttribute<long long>(c, dset.get(), "column", path);
    cols.push_back(std::move(col));
  }
  std::stable_sort(cols.begin(), cols.end(),
                   [](const Column& a, const Column& b) { return a.position < b.position; });
  std::pair<std::vector<std::string>, std::vector<std::vector<double>>> out;
  for (Column& col : cols) {
    out.first.push_back(col.name);
    out.second.push_back(std::move(col.data));
  }
  return out;
}

void ResultsWriter::writeRootAttribute(const std::string& name, const std::vector<double>& values) {
  Impl& m = *impl_;
  m.requireOpen("writeRootAttribute");
  checkName(name, "attribute");
  const hdf5::QuietErrors quiet;
  const Context c = m.ctx();
  const std::string full = "/@" + name;
  const htri_t exists = H5Aexists(m.file.get(), name.c_str());
  if (exists < 0) c.fail("cannot query", full);
  if (exists > 0) c.check(H5Adelete(m.file.get(), name.c_str()), "cannot replace", full);
  const hsize_t n = values.size();
  const Hid space = c.check(H5Screate_simple(1, &n, nullptr), H5Sclose, "cannot create dataspace for", full);
  const Hid attr =
      c.check(H5Acreate2(m.file.get(), name.c_str(), H5T_IEEE_F64LE, space.get(), H5P_DEFAULT, H5P_DEFAULT),
              H5Aclose, "cannot create attribute", full);
  if (n > 0) c.check(H5Awrite(attr.get(), H5T_NATIVE_DOUBLE, values.data()), "cannot write attribute", full);
  m.flush();
}

std::vector<double> ResultsWriter::rootAttribute(const std::string& name) const {
  const Impl& m = *impl_;
  m.requireOpen("rootAttribute");
  const hdf5::QuietErrors quiet;
  const Context c = m.ctx();
  const std::string full = "/@" + name;
  const htri_t exists = H5Aexists(m.file.get(), name.c_str());
  if (exists < 0) c.fail("cannot query", full);
  if (exists == 0) return {};
  const Hid attr =
      c.check(H5Aopen(m.file.get(), name.c_str(), H5P_DEFAULT), H5Aclose, "cannot open attribute", full);
  const Hid space = c.check(H5Aget_space(attr.get()), H5Sclose, "cannot read the shape of", full);
  const hssize_t n = H5Sget_simple_extent_npoints(space.get());
  std::vector<double> values(static_cast<std::size_t>(std::max<hssize_t>(n, 0)));
  if (!values.empty())
    c.check(H5Aread(attr.get(), H5T_NATIVE_DOUBLE, values.data()), "cannot read attribute", full);
  return values;
}

void ResultsWriter::close() {
  if (impl_) impl_->close();
}

int ResultsWriter::stepsWritten() const {
  return static_cast<int>(impl_->records.size());
}
double ResultsWriter::lastStepTime() const {
  return impl_->records.empty() ? -std::numeric_limits<double>::infinity() : impl_->records.back().time;
}
const fs::path& ResultsWriter::h5Path() const {
  return impl_->h5Path;
}
const fs::path& ResultsWriter::xdmfPath() const {
  return impl_->xdmfPath;
}

ResultsFrame readLastFrame(const fs::path& h5File) {
  std::error_code ec;
  if (!fs::is_regular_file(h5File, ec))
    throw InputError(fmt::format("{}: no such results file", h5File.string()));
  const hdf5::QuietErrors quiet;
  if (H5Fis_hdf5(h5File.c_str()) <= 0)
    throw InputError(fmt::format("{}: not an HDF5 results file{}", h5File.string(), hdf5::errorDetail()));
  const Context c{{h5File, "reading results", true}};
  const Hid file = c.check(H5Fopen(h5File.c_str(), H5F_ACC_RDONLY, H5P_DEFAULT), H5Fclose, "cannot open", "");
  ResultsFrame r;
  std::vector<hsize_t> dims;
  auto connectivity = [&](const char* name, std::size_t width, auto& out) {
    const std::string full = std::string("/") + name;
    const std::vector<int> v = readDataset<int>(c, file.get(), name, full, H5T_NATIVE_INT, dims);
    if (!v.empty() && (dims.size() != 2 || dims[1] != width))
      c.fail(fmt::format("expected {} columns in", width), full);
    out.resize(v.size() / width);
    std::copy(v.begin(), v.end(), out.empty() ? nullptr : out.front().data());
  };
  connectivity("mesh/triangles", 3, r.triangles);
  connectivity("mesh/lines", 2, r.lines);
  const Hid steps =
      c.check(H5Gopen2(file.get(), "steps", H5P_DEFAULT), H5Gclose, "cannot open group", "/steps");
  const std::vector<std::string> names = linkNames(c, steps.get(), "/steps");
  if (names.empty()) c.fail("no frame in", "/steps");
  r.step = names.back();  // zero-padded indices: name order is write order
  const std::string group = "/steps/" + r.step;
  const Hid g =
      c.check(H5Gopen2(steps.get(), r.step.c_str(), H5P_DEFAULT), H5Gclose, "cannot open group", group);
  // Every attribute the frame is read with is checked (a scalar of its type: an array `time` was once read
  // into one double), and its value too.
  r.time = readScalarAttribute<double>(c, g.get(), "time", group);
  if (!std::isfinite(r.time))
    c.fail(fmt::format("non-finite value {} in attribute", r.time), group + "@time");
  r.stepNumber = readScalarAttribute<long long>(c, g.get(), "step", group);
  if (r.stepNumber < 0) c.fail(fmt::format("negative value {} in attribute", r.stepNumber), group + "@step");
  for (auto [name, out] :
       {std::pair{"coordinates", &r.coordinates}, std::pair{"displacement", &r.displacement}}) {
    const std::string full = group + "/" + name;
    *out = readDataset<double>(c, g.get(), name, full, H5T_NATIVE_DOUBLE, dims);
    if (dims.size() != 2 || dims[1] != 3) c.fail("expected 3 columns in", full);
    for (const double x : *out)
      if (!std::isfinite(x)) c.fail("non-finite value in", full);
  }
  if (r.coordinates.size() != r.displacement.size()) c.fail("not one displacement per node in", group);
  const int n = r.numNodes();
  const long long declared = readScalarAttribute<long long>(c, file.get(), "num_nodes", "/");
  if (declared != n)
    c.fail(fmt::format("the frame {} holds {} nodes, not the {} of attribute", group, n, declared),
           "/@num_nodes");
  for (const auto& t : r.triangles)
    for (const int i : t)
      if (i < 0 || i >= n)
        c.fail(fmt::format("node {} out of range (nodes: {}) in", i, n), "/mesh/triangles");
  for (const auto& l : r.lines)
    for (const int i : l)
      if (i < 0 || i >= n) c.fail(fmt::format("node {} out of range (nodes: {}) in", i, n), "/mesh/lines");
  return r;
}

}  // namespace fsi::structure
