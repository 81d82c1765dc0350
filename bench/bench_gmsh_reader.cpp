// Google Benchmark of readGmsh (structure/io/GmshReader) on a large mesh in the four MSH flavours.
//   fsi_bench --benchmark_filter=ReadGmsh
// Mesh: the unit square as 707 x 707 squares split into 999 698 triangles (501 264 nodes), one physical
// surface and one physical curve (y = 0, 707 lines), written once per flavour into a temporary folder.
// Arguments: MSH version 41 or 22, binary 0 or 1. items_per_second = triangles read per second. The file only
// calls readGmsh, so the same source measures an earlier reader too.
#include <benchmark/benchmark.h>
#include <unistd.h>

#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <type_traits>
#include <utility>

#include "structure/io/GmshReader.hpp"

namespace {

namespace fs = std::filesystem;

constexpr int kN = 707;                           // squares per side
constexpr long kNodes = long(kN + 1) * (kN + 1);  // tags 1..kNodes, row by row
constexpr long kTriangles = 2L * kN * kN;

long node(int i, int j) {
  return long(j) * (kN + 1) + i + 1;
}

class Out {
 public:
  Out(const fs::path& file, bool binary) : out_(file, std::ios::binary), binary_(binary) {}
  void text(const std::string& s) { out_ << s; }
  // A value as text (ASCII files) or raw (binary files), in the type the format prescribes.
  template <class T>
  void value(T v, const char* sep = " ") {
    if (binary_) {
      out_.write(reinterpret_cast<const char*>(&v), sizeof(T));
    } else {
      if constexpr (std::is_floating_point_v<T>) {
        char buf[32];
        std::snprintf(buf, sizeof buf, "%.16g", v);
        out_ << buf << sep;
      } else {
        out_ << v << sep;
      }
    }
  }
  void endLine() {
    if (!binary_) out_ << '\n';
  }

 private:
  std::ofstream out_;
  bool binary_;
};

// The triangles of square (i, j): (a b c) and (a c d), counter-clockwise.
template <class Fn>
void forEachTriangle(Fn fn) {
  for (int j = 0; j < kN; ++j)
    for (int i = 0; i < kN; ++i) {
      const long a = node(i, j), b = node(i + 1, j), c = node(i + 1, j + 1), d = node(i, j + 1);
      fn(a, b, c);
      fn(a, c, d);
    }
}

void write41(const fs::path& file, bool binary) {
  Out o(file, binary);
  o.text(binary ? "$MeshFormat\n4.1 1 8\n" : "$MeshFormat\n4.1 0 8\n");
  if (binary) {
    o.value<std::int32_t>(1);
    o.text("\n");
  }
  o.text("$EndMeshFormat\n$PhysicalNames\n2\n1 2 \"edge\"\n2 1 \"canopy\"\n$EndPhysicalNames\n$Entities\n");
  using Size = std::uint64_t;
  for (const Size n : {0, 1, 1, 0}) o.value<Size>(n);
  o.endLine();
  for (const int dim : {1, 2}) {  // curve 1 (y = 0) in group 2, surface 1 in group 1
    o.value<std::int32_t>(1);
    for (const double x : {0., 0., 0., 1., dim == 1 ? 0. : 1., 0.}) o.value<double>(x);
    o.value<Size>(1);
    o.value<std::int32_t>(dim == 1 ? 2 : 1);
    o.value<Size>(0);
    o.endLine();
  }
  o.text(binary ? "\n$EndEntities\n$Nodes\n" : "$EndEntities\n$Nodes\n");
  for (const Size n : {Size(1), Size(kNodes), Size(1), Size(kNodes)}) o.value<Size>(n);
  o.endLine();
  o.value<std::int32_t>(2);
  o.value<std::int32_t>(1);
  o.value<std::int32_t>(0);
  o.value<Size>(Size(kNodes));
  o.endLine();
  for (long t = 1; t <= kNodes; ++t) o.value<Size>(Size(t), "\n");
  for (int j = 0; j <= kN; ++j)
    for (int i = 0; i <= kN; ++i) {
      o.value<double>(double(i) / kN);
      o.value<double>(double(j) / kN);
      o.value<double>(0.0, "\n");
    }
  o.text(binary ? "\n$EndNodes\n$Elements\n" : "$EndNodes\n$Elements\n");
  for (const Size n : {Size(2), Size(kN + kTriangles), Size(1), Size(kN + kTriangles)}) o.value<Size>(n);
  o.endLine();
  for (const int n : {1, 1, 1}) o.value<std::int32_t>(n);
  o.value<Size>(kN);
  o.endLine();
  Size tag = 1;
  for (int i = 0; i < kN; ++i) {
    o.value<Size>(tag++);
    o.value<Size>(Size(node(i, 0)));
    o.value<Size>(Size(node(i + 1, 0)), "\n");
  }
  for (const int n : {2, 1, 2}) o.value<std::int32_t>(n);
  o.value<Size>(Size(kTriangles));
  o.endLine();
  forEachTriangle([&](long a, long b, long c) {
    o.value<Size>(tag++);
    o.value<Size>(Size(a));
    o.value<Size>(Size(b));
    o.value<Size>(Size(c), "\n");
  });
  o.text(binary ? "\n$EndElements\n" : "$EndElements\n");
}

void write22(const fs::path& file, bool binary) {
  Out o(file, binary);
  o.text(binary ? "$MeshFormat\n2.2 1 8\n" : "$MeshFormat\n2.2 0 8\n");
  if (binary) {
    o.value<std::int32_t>(1);
    o.text("\n");
  }
  o.text("$EndMeshFormat\n$PhysicalNames\n2\n1 2 \"edge\"\n2 1 \"canopy\"\n$EndPhysicalNames\n$Nodes\n");
  o.text(std::to_string(kNodes) + "\n");
  for (int j = 0; j <= kN; ++j)
    for (int i = 0; i <= kN; ++i) {
      o.value<std::int32_t>(std::int32_t(node(i, j)));
      o.value<double>(double(i) / kN);
      o.value<double>(double(j) / kN);
      o.value<double>(0.0, "\n");
    }
  o.text(binary ? "\n$EndNodes\n$Elements\n" : "$EndNodes\n$Elements\n");
  o.text(std::to_string(kN + kTriangles) + "\n");
  std::int32_t tag = 1;
  // Binary: a block header (type, count, number of tags) per element type.
  if (binary) {
    for (const int n : {1, kN, 2}) o.value<std::int32_t>(n);
  }
  for (int i = 0; i < kN; ++i) {
    o.value<std::int32_t>(tag++);
    if (!binary)
      for (const int n : {1, 2}) o.value<std::int32_t>(n);
    for (const int n : {2, 1}) o.value<std::int32_t>(n);  // physical 2, entity 1
    o.value<std::int32_t>(std::int32_t(node(i, 0)));
    o.value<std::int32_t>(std::int32_t(node(i + 1, 0)), "\n");
  }
  if (binary) {
    for (const long n : {2L, kTriangles, 2L}) o.value<std::int32_t>(std::int32_t(n));
  }
  forEachTriangle([&](long a, long b, long c) {
    o.value<std::int32_t>(tag++);
    if (!binary)
      for (const int n : {2, 2}) o.value<std::int32_t>(n);
    for (const int n : {1, 1}) o.value<std::int32_t>(n);  // physical 1, entity 1
    o.value<std::int32_t>(std::int32_t(a));
    o.value<std::int32_t>(std::int32_t(b));
    o.value<std::int32_t>(std::int32_t(c), "\n");
  });
  o.text(binary ? "\n$EndElements\n" : "$EndElements\n");
}

// The files, written on first use and removed at exit.
class Files {
 public:
  ~Files() {
    std::error_code ec;
    fs::remove_all(dir_, ec);
  }
  const fs::path& get(int version, bool binary) {
    const auto key = std::make_pair(version, binary);
    auto it = files_.find(key);
    if (it != files_.end()) return it->second;
    if (dir_.empty()) {
      dir_ = fs::temp_directory_path() / ("fsi_bench_gmsh_" + std::to_string(::getpid()));
      fs::create_directories(dir_);
    }
    const fs::path file = dir_ / ("grid_" + std::to_string(version) + (binary ? "_binary" : "") + ".msh");
    (version == 41 ? write41 : write22)(file, binary);
    return files_[key] = file;
  }

 private:
  fs::path dir_;
  std::map<std::pair<int, bool>, fs::path> files_;
};

Files& files() {
  static Files f;
  return f;
}

void BM_ReadGmsh(benchmark::State& state) {
  const fs::path& file = files().get(int(state.range(0)), state.range(1) != 0);
  for (auto _ : state) {
    const fsi::structure::MeshData m = fsi::structure::readGmsh(file, "grid");
    if (long(m.triangles.size()) != kTriangles) state.SkipWithError("wrong triangle count");
    benchmark::DoNotOptimize(m.points.data());
  }
  state.SetItemsProcessed(state.iterations() * kTriangles);
  state.counters["MB"] = double(fs::file_size(file)) / 1e6;
}
BENCHMARK(BM_ReadGmsh)
    ->ArgNames({"version", "binary"})
    ->Args({41, 0})
    ->Args({41, 1})
    ->Args({22, 0})
    ->Args({22, 1})
    ->Unit(benchmark::kMillisecond)
    ->Iterations(3);

}  // namespace
