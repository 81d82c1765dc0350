#include "coupling/mapping/MappingDefaults.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <utility>
#include <vector>

namespace fsi::coupling {

ProjectionOptions coupledRunProjection() {
  ProjectionOptions o;
  o.mass = MassMatrix::Consistent;
  o.evaluation = ProjectionOptions::Evaluation::Pointwise;
  o.quadratureLevel = kAutoQuadrature;
  o.gapCorrection = false;
  o.defectCorrection = ProjectionOptions::Defect::Off;
  o.keepSide = false;
  return o;
}

namespace {
std::string level(int l) {
  return l == kAutoQuadrature ? "auto" : std::to_string(l);
}
const char* yesNo(bool b) {
  return b ? "yes" : "no";
}
}  // namespace

std::string describe(const ProjectionOptions& o) {
  std::string s = fmt::format(
      "projection {}, evaluation {}, quadratureLevel {}, gapCorrection {}, defectCorrection {}, keepSide {}",
      toString(o.mass), toString(o.evaluation), level(o.quadratureLevel), yesNo(o.gapCorrection),
      toString(o.defectCorrection), yesNo(o.keepSide));
  if (std::isfinite(o.tolerance)) s += fmt::format(", mapTolerance {:.4g}", o.tolerance);
  return s;
}

std::vector<std::string> differencesFromRunDefaults(const ProjectionOptions& o) {
  const ProjectionOptions d = coupledRunProjection();
  std::vector<std::string> out;
  if (o.mass != d.mass) out.push_back(fmt::format("projection {}", toString(o.mass)));
  if (o.evaluation != d.evaluation) out.push_back(fmt::format("evaluation {}", toString(o.evaluation)));
  if (o.quadratureLevel != d.quadratureLevel)
    out.push_back(fmt::format("quadratureLevel {}", level(o.quadratureLevel)));
  if (o.gapCorrection != d.gapCorrection)
    out.push_back(fmt::format("gapCorrection {}", yesNo(o.gapCorrection)));
  if (o.defectCorrection != d.defectCorrection)
    out.push_back(fmt::format("defectCorrection {}", toString(o.defectCorrection)));
  if (o.keepSide != d.keepSide) out.push_back(fmt::format("keepSide {}", yesNo(o.keepSide)));
  return out;
}

namespace {

using Vec3 = std::array<double, 3>;

Vec3 faceNormal(const InterfaceMesh& m, int f) {  // unit normal of the fan about the vertex average
  const Vec3 c = m.faceCentroid(f);
  Vec3 n{0.0, 0.0, 0.0};
  const int k = m.faceSize(f);
  for (int i = 0; i < k; ++i) {
    const Vec3& a = m.points[std::size_t(m.face(f)[i])];
    const Vec3& b = m.points[std::size_t(m.face(f)[(i + 1) % k])];
    const Vec3 u{a[0] - c[0], a[1] - c[1], a[2] - c[2]}, v{b[0] - c[0], b[1] - c[1], b[2] - c[2]};
    n[0] += u[1] * v[2] - u[2] * v[1];
    n[1] += u[2] * v[0] - u[0] * v[2];
    n[2] += u[0] * v[1] - u[1] * v[0];
  }
  const double l = std::sqrt(n[0] * n[0] + n[1] * n[1] + n[2] * n[2]);
  return l > 0.0 ? Vec3{n[0] / l, n[1] / l, n[2] / l} : n;
}

double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

// Unit vertex normals: the faces' normals around each vertex summed, each turned to agree with the first
// (a membrane mesh need not orient its faces alike). Zero where they cancel or at a crease sharper than
// kCreaseAngle (the normal is not defined there).
std::vector<Vec3> vertexNormals(const InterfaceMesh& m) {
  std::vector<Vec3> first(m.points.size(), Vec3{0.0, 0.0, 0.0}), sum(m.points.size(), Vec3{0.0, 0.0, 0.0});
  std::vector<unsigned char> crease(m.points.size(), 0);
  const double creaseCos = std::cos(kCreaseAngle);
  for (int f = 0; f < m.numFaces(); ++f) {
    const Vec3 n = faceNormal(m, f);
    const double area = m.faceArea(f);
    for (int i = 0; i < m.faceSize(f); ++i) {
      const std::size_t v = std::size_t(m.face(f)[i]);
      if (dot(first[v], first[v]) == 0.0) first[v] = n;
      const double c = dot(first[v], n);
      if (std::abs(c) < creaseCos) crease[v] = 1;
      const double sign = c < 0.0 ? -1.0 : 1.0;
      for (std::size_t k = 0; k < 3; ++k) sum[v][k] += sign * area * n[k];
    }
  }
  for (std::size_t v = 0; v < sum.size(); ++v) {
    const double l = std::sqrt(dot(sum[v], sum[v]));
    sum[v] =
        crease[v] || !(l > 0.0) ? Vec3{0.0, 0.0, 0.0} : Vec3{sum[v][0] / l, sum[v][1] / l, sum[v][2] / l};
  }
  return sum;
}

}  // namespace

double chordGap(const InterfaceMesh& m) {
  // A chord of length l between two points of a curve whose normals differ by the angle φ sags l φ / 8
  // below it (a circular arc: l² / 8R, φ = l / R); a triangle's interior sags up to 4/3 of its edges' (its
  // circumcentre on a sphere: l² / 6R against l² / 8R).
  const std::vector<Vec3> normal = vertexNormals(m);
  double gap = 0.0;
  for (int f = 0; f < m.numFaces(); ++f) {
    const int k = m.faceSize(f);
    for (int i = 0; i < k; ++i) {
      const std::size_t a = std::size_t(m.face(f)[i]), b = std::size_t(m.face(f)[(i + 1) % k]);
      if (dot(normal[a], normal[a]) == 0.0 || dot(normal[b], normal[b]) == 0.0) continue;
      const double phi = std::acos(std::clamp(std::abs(dot(normal[a], normal[b])), 0.0, 1.0));
      const Vec3 d{m.points[a][0] - m.points[b][0], m.points[a][1] - m.points[b][1],
                   m.points[a][2] - m.points[b][2]};
      gap = std::max(gap, 4.0 / 3.0 * std::sqrt(dot(d, d)) * phi / 8.0);
    }
  }
  return gap;
}

double mappingTolerance(const InterfaceMesh& structure, const InterfaceMesh& fluid) {
  const double floor = kToleranceEdgeShare * structure.meanEdgeLength();
  const double gaps = 2.0 * (chordGap(structure) + chordGap(fluid));
  return std::isfinite(gaps) ? std::max(floor, gaps) : floor;  // degenerate faces: the floor alone
}

}  // namespace fsi::coupling
