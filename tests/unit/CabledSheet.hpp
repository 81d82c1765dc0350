#pragma once
// A pressurised membrane with cables for dynamic relaxation at scale (test_threads.cpp: threaded against
// serial relaxation; bench/bench_relaxation.cpp: the time per iteration): a 1 m square film of n x n
// cross-pattern squares (4 n² triangles) clamped on its edges, with cables sewn along both diagonals and, for
// an even n, both mid-lines, sharing the film's nodes (an MSH 2.2 file: the generators do not join meshes).
// Inflated from flat by a follower pressure.
#include <fmt/format.h>

#include <array>
#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

namespace fsi::test {

/// Writes `dir`/sheet.msh (groups: triangles `sheet`, lines `cables`, nodes `boundary`) and returns the scene
/// text that uses it (to be loaded as a file in `dir`). `solver` goes into the solver mapping, `constraints`
/// (entries, one per line) after the clamped edges.
inline std::string writeCabledSheet(const std::filesystem::path& dir, int n, const std::string& solver = "",
                                    const std::string& constraints = "") {
  std::filesystem::create_directories(dir);
  const int nc = (n + 1) * (n + 1);
  auto corner = [&](int i, int j) { return j * (n + 1) + i + 1; };
  auto centre = [&](int i, int j) { return nc + j * n + i + 1; };
  std::vector<std::array<int, 3>> tri;
  std::vector<std::array<int, 2>> lines;
  std::vector<int> boundary;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const int a = corner(i, j), b = corner(i + 1, j), c = corner(i + 1, j + 1), d = corner(i, j + 1);
      const int m = centre(i, j);
      tri.push_back({a, b, m}), tri.push_back({b, c, m}), tri.push_back({c, d, m}), tri.push_back({d, a, m});
    }
  for (int i = 0; i < n; ++i) {
    lines.push_back({corner(i, i), centre(i, i)}), lines.push_back({centre(i, i), corner(i + 1, i + 1)});
    const int j = n - 1 - i;
    lines.push_back({corner(i, j + 1), centre(i, j)}), lines.push_back({centre(i, j), corner(i + 1, j)});
    if (n % 2 == 0) {
      lines.push_back({corner(n / 2, i), corner(n / 2, i + 1)});
      lines.push_back({corner(i, n / 2), corner(i + 1, n / 2)});
    }
  }
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      if (i == 0 || j == 0 || i == n || j == n) boundary.push_back(corner(i, j));
  std::ofstream out(dir / "sheet.msh");
  out.precision(17);
  out << "$MeshFormat\n2.2 0 8\n$EndMeshFormat\n$PhysicalNames\n3\n0 1 \"boundary\"\n1 2 \"cables\"\n"
         "2 3 \"sheet\"\n$EndPhysicalNames\n$Nodes\n"
      << nc + n * n << "\n";
  for (int j = 0; j <= n; ++j)
    for (int i = 0; i <= n; ++i)
      out << corner(i, j) << " " << double(i) / n << " " << double(j) / n << " 0\n";
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) out << centre(i, j) << " " << (i + 0.5) / n << " " << (j + 0.5) / n << " 0\n";
  out << "$EndNodes\n$Elements\n" << boundary.size() + lines.size() + tri.size() << "\n";
  long id = 1;
  for (int b : boundary) out << id++ << " 15 2 1 1 " << b << "\n";
  for (const auto& l : lines) out << id++ << " 1 2 2 2 " << l[0] << " " << l[1] << "\n";
  for (const auto& t : tri) out << id++ << " 2 2 3 3 " << t[0] << " " << t[1] << " " << t[2] << "\n";
  out << "$EndElements\n";
  return fmt::format(R"(materials:
  film: {{type: membrane, young: 1.0e8, poisson: 0.3, thickness: 1.0e-3, density: 1000}}
  rope: {{type: cable, young: 1.0e10, area: 1.0e-6, density: 1000}}
meshes:
  sheet: {{file: sheet.msh, material: film, cable_material: rope, cables: all}}
constraints:
  - {{nodes: sheet/boundary, fix: all}}
{}effects:
  pressure: {{triangles: sheet, value: 1000}}
solver: {{type: dynamic_relaxation{}{}}}
)",
                     constraints, solver.empty() ? "" : ", ", solver);
}

}  // namespace fsi::test
