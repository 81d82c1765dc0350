#include "structure/scene/Generators.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "structure/model/Error.hpp"
#include "structure/model/PositiveValue.hpp"

namespace fsi::structure {
namespace {

constexpr double kPi = 3.14159265358979323846;
// Keeps every index and count well inside int (MeshData stores int indices).
constexpr long long kMaxEntities = 100'000'000;

[[noreturn]] void invalid(const std::string& generator, const std::string& parameter,
                          const std::string& what) {
  throw InputError(fmt::format("{} generator: parameter '{}' {}", generator, parameter, what));
}

void requirePositive(const std::string& generator, const std::string& parameter, double value) {
  if (!isPositiveNormal(value)) {
    invalid(generator, parameter,
            fmt::format("must be positive (at least 2.2e-308, not subnormal), got {}", value));
  }
}

void requireDivisions(const std::string& generator, const std::string& parameter, int value) {
  if (value < 1) invalid(generator, parameter, fmt::format("must be at least 1, got {}", value));
}

void requireFinite(const std::string& generator, const std::string& parameter, const Point3& p) {
  if (!std::isfinite(p[0]) || !std::isfinite(p[1]) || !std::isfinite(p[2])) {
    invalid(generator, parameter, fmt::format("must be finite, got ({}, {}, {})", p[0], p[1], p[2]));
  }
}

// The count is estimated in double so that huge divisions cannot overflow the check itself.
void requireCount(const std::string& generator, const std::string& parameter, double count) {
  if (count > static_cast<double>(kMaxEntities)) {
    invalid(generator, parameter,
            fmt::format("gives {} elements or nodes, more than the limit {}", count, kMaxEntities));
  }
}

std::vector<int> range(int begin, int end) {
  std::vector<int> v(static_cast<std::size_t>(end - begin));
  std::iota(v.begin(), v.end(), begin);
  return v;
}

// Generator ids are 1-based and follow the index order.
void assignTags(MeshData& mesh) {
  const auto fill = [](std::vector<long>& tags, std::size_t n) {
    tags.resize(n);
    std::iota(tags.begin(), tags.end(), 1L);
  };
  fill(mesh.pointTags, mesh.points.size());
  fill(mesh.triangleTags, mesh.triangles.size());
  fill(mesh.lineTags, mesh.lines.size());
}

Point3 sub(const Point3& a, const Point3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}
Point3 cross(const Point3& a, const Point3& b) {
  return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
double norm(const Point3& a) {
  return std::sqrt(a[0] * a[0] + a[1] * a[1] + a[2] * a[2]);
}

// Adds the two triangles of square (a, b, c, d), counter-clockwise, cut along a-c or b-d.
void addSquare(MeshData& mesh, int a, int b, int c, int d, bool diagonalAC) {
  if (diagonalAC) {
    mesh.triangles.push_back({a, b, c});
    mesh.triangles.push_back({a, c, d});
  } else {
    mesh.triangles.push_back({a, b, d});
    mesh.triangles.push_back({b, c, d});
  }
}

// `prefix` qualifies parameter names when the pillow builds a face ("rectangle." -> 'rectangle.size[0]').
MeshData buildRectangle(const RectangleParams& p, const std::string& generator, const std::string& prefix) {
  requirePositive(generator, prefix + "size[0]", p.size[0]);
  requirePositive(generator, prefix + "size[1]", p.size[1]);
  requireDivisions(generator, prefix + "divisions[0]", p.divisions[0]);
  requireDivisions(generator, prefix + "divisions[1]", p.divisions[1]);
  requireFinite(generator, prefix + "center", p.center);
  const bool cross = p.pattern == "cross";
  const bool alternating = p.pattern == "alternating";
  if (!cross && !alternating && p.pattern != "ruled") {
    invalid(generator, prefix + "pattern",
            fmt::format("must be ruled, alternating or cross, got '{}'", p.pattern));
  }
  const int nx = p.divisions[0], ny = p.divisions[1];
  requireCount(generator, prefix + "divisions", 4.0 * (nx + 1.0) * (ny + 1.0));

  MeshData mesh;
  const double lx = p.size[0], ly = p.size[1];
  const auto& c = p.center;
  // Fractions i/nx - 1/2 make the edges and the middle line exact.
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      mesh.points.push_back({c[0] + lx * (static_cast<double>(i) / nx - 0.5),
                             c[1] + ly * (static_cast<double>(j) / ny - 0.5), c[2]});
    }
  }
  const auto grid = [nx](int i, int j) { return j * (nx + 1) + i; };
  const int firstCentre = static_cast<int>(mesh.points.size());
  if (cross) {
    for (int j = 0; j < ny; ++j) {
      for (int i = 0; i < nx; ++i) {
        mesh.points.push_back({c[0] + lx * ((i + 0.5) / nx - 0.5), c[1] + ly * ((j + 0.5) / ny - 0.5), c[2]});
      }
    }
  }
  for (int j = 0; j < ny; ++j) {
    for (int i = 0; i < nx; ++i) {
      const int a = grid(i, j), b = grid(i + 1, j), cc = grid(i + 1, j + 1), d = grid(i, j + 1);
      if (cross) {
        const int m = firstCentre + j * nx + i;
        mesh.triangles.push_back({a, b, m});
        mesh.triangles.push_back({b, cc, m});
        mesh.triangles.push_back({cc, d, m});
        mesh.triangles.push_back({d, a, m});
      } else {
        addSquare(mesh, a, b, cc, d, !alternating || (i + j) % 2 == 0);
      }
    }
  }

  auto& xmin = mesh.nodeGroups["xmin"];
  auto& xmax = mesh.nodeGroups["xmax"];
  auto& ymin = mesh.nodeGroups["ymin"];
  auto& ymax = mesh.nodeGroups["ymax"];
  auto& boundary = mesh.nodeGroups["boundary"];
  for (int j = 0; j <= ny; ++j) {
    xmin.push_back(grid(0, j));
    xmax.push_back(grid(nx, j));
  }
  for (int i = 0; i <= nx; ++i) {
    ymin.push_back(grid(i, 0));
    ymax.push_back(grid(i, ny));
  }
  for (int j = 0; j <= ny; ++j) {
    for (int i = 0; i <= nx; ++i) {
      if (i == 0 || i == nx || j == 0 || j == ny) boundary.push_back(grid(i, j));
    }
  }
  mesh.triangleGroups["all"] = range(0, static_cast<int>(mesh.triangles.size()));
  return mesh;
}

MeshData buildDisc(const DiscParams& p, const std::string& generator, const std::string& prefix) {
  requirePositive(generator, prefix + "radius", p.radius);
  requireDivisions(generator, prefix + "rings", p.rings);
  requireFinite(generator, prefix + "center", p.center);
  const int n = p.rings;
  requireCount(generator, prefix + "rings", 6.0 * n * n + 1.0);

  MeshData mesh;
  const auto& c = p.center;
  mesh.points.push_back(c);
  // Ring k starts at index 1 + 3k(k-1); node m of ring k sits at angle 2πm/(6k).
  const auto ringStart = [](int k) { return 1 + 3 * k * (k - 1); };
  for (int k = 1; k <= n; ++k) {
    const double r = p.radius * (static_cast<double>(k) / n);  // exactly R on the rim
    for (int m = 0; m < 6 * k; ++m) {
      const double angle = 2.0 * kPi * m / (6.0 * k);
      mesh.points.push_back({c[0] + r * std::cos(angle), c[1] + r * std::sin(angle), c[2]});
    }
  }
  // Each of the six sectors between ring k-1 and ring k holds k outward and k-1 inward triangles; the
  // corners of the hexagonal rings line up, which keeps all triangles close to equilateral.
  for (int k = 1; k <= n; ++k) {
    const auto outer = [&](int m) { return ringStart(k) + m % (6 * k); };
    const auto inner = [&](int m) { return k == 1 ? 0 : ringStart(k - 1) + m % (6 * (k - 1)); };
    for (int s = 0; s < 6; ++s) {
      for (int t = 0; t < k; ++t) {
        mesh.triangles.push_back({outer(s * k + t), outer(s * k + t + 1), inner(s * (k - 1) + t)});
        if (t < k - 1) {
          mesh.triangles.push_back(
              {inner(s * (k - 1) + t), outer(s * k + t + 1), inner(s * (k - 1) + t + 1)});
        }
      }
    }
  }
  mesh.nodeGroups["center"] = {0};
  mesh.nodeGroups["rim"] = range(ringStart(n), ringStart(n + 1));
  mesh.triangleGroups["all"] = range(0, static_cast<int>(mesh.triangles.size()));
  return mesh;
}

// Nodes along a polyline: every segment cut into its division count, shared corners once.
std::vector<Point3> samplePolyline(const std::string& generator, const std::string& pointsName,
                                   const std::vector<Point3>& points, const std::vector<int>& divisions) {
  if (points.size() < 2) {
    invalid(generator, pointsName, fmt::format("needs at least 2 points, got {}", points.size()));
  }
  const std::size_t segments = points.size() - 1;
  if (divisions.size() != 1 && divisions.size() != segments) {
    invalid(generator, "divisions",
            fmt::format("needs 1 value or one per segment ({}), got {}", segments, divisions.size()));
  }
  long long total = 1;
  for (std::size_t s = 0; s < segments; ++s) {
    const int d = divisions.size() == 1 ? divisions[0] : divisions[s];
    requireDivisions(generator, fmt::format("divisions[{}]", divisions.size() == 1 ? 0 : s), d);
    total += d;
  }
  for (std::size_t s = 0; s < points.size(); ++s) {
    requireFinite(generator, fmt::format("{}[{}]", pointsName, s), points[s]);
  }
  for (std::size_t s = 0; s < segments; ++s) {
    if (!(norm(sub(points[s + 1], points[s])) > 0.0)) {
      invalid(generator, pointsName,
              fmt::format("points {} and {} coincide (zero-length segment)", s, s + 1));
    }
  }
  requireCount(generator, "divisions", static_cast<double>(total));

  std::vector<Point3> nodes{points[0]};
  for (std::size_t s = 0; s < segments; ++s) {
    const int d = divisions.size() == 1 ? divisions[0] : divisions[s];
    const Point3 &a = points[s], &b = points[s + 1];
    for (int t = 1; t < d; ++t) {
      const double u = static_cast<double>(t) / d;
      nodes.push_back({a[0] + u * (b[0] - a[0]), a[1] + u * (b[1] - a[1]), a[2] + u * (b[2] - a[2])});
    }
    nodes.push_back(b);  // segment ends exactly on the given point
  }
  return nodes;
}

}  // namespace

MeshData rectangle(const RectangleParams& params, const std::string& name) {
  MeshData mesh = buildRectangle(params, "rectangle", "");
  mesh.name = name;
  assignTags(mesh);
  return mesh;
}

MeshData disc(const DiscParams& params, const std::string& name) {
  MeshData mesh = buildDisc(params, "disc", "");
  mesh.name = name;
  assignTags(mesh);
  return mesh;
}

MeshData sphereOctant(const SphereOctantParams& params, const std::string& name) {
  const std::string generator = "sphereOctant";
  requirePositive(generator, "radius", params.radius);
  requireDivisions(generator, "divisions", params.divisions);
  const int n = params.divisions;
  requireCount(generator, "divisions", 2.0 * (n + 1.0) * (n + 2.0));
  const double r = params.radius;

  MeshData mesh;
  mesh.name = name;
  // Node (i, j) = A + i/n (B - A) + j/n (C - A), rows of constant j stored one after the other.
  const auto rowStart = [n](int j) { return j * (n + 1) - j * (j - 1) / 2; };
  const auto node = [&](int i, int j) { return rowStart(j) + i; };
  auto& x0 = mesh.nodeGroups["x0"];
  auto& y0 = mesh.nodeGroups["y0"];
  auto& z0 = mesh.nodeGroups["z0"];
  for (int j = 0; j <= n; ++j) {
    for (int i = 0; i <= n - j; ++i) {
      Point3 q{r * (static_cast<double>(n - i - j) / n), r * (static_cast<double>(i) / n),
               r * (static_cast<double>(j) / n)};
      const double scale = r / norm(q);
      for (double& v : q) v *= scale;
      // The symmetry planes must hold exactly so that boundary conditions on them are clean.
      const int index = static_cast<int>(mesh.points.size());
      if (i + j == n) {
        q[0] = 0.0;
        x0.push_back(index);
      }
      if (i == 0) {
        q[1] = 0.0;
        y0.push_back(index);
      }
      if (j == 0) {
        q[2] = 0.0;
        z0.push_back(index);
      }
      mesh.points.push_back(q);
    }
  }
  // (B - A) x (C - A) points away from the origin, so (i,j), (i+1,j), (i,j+1) is outward.
  for (int j = 0; j < n; ++j) {
    for (int i = 0; i < n - j; ++i) {
      mesh.triangles.push_back({node(i, j), node(i + 1, j), node(i, j + 1)});
      if (i + j < n - 1) mesh.triangles.push_back({node(i + 1, j), node(i + 1, j + 1), node(i, j + 1)});
    }
  }
  mesh.triangleGroups["all"] = range(0, static_cast<int>(mesh.triangles.size()));
  assignTags(mesh);
  return mesh;
}

MeshData cableChain(const CableChainParams& params, const std::string& name) {
  MeshData mesh;
  mesh.name = name;
  mesh.points = samplePolyline("cableChain", "points", params.points, params.divisions);
  const int count = static_cast<int>(mesh.points.size());
  for (int k = 0; k + 1 < count; ++k) mesh.lines.push_back({k, k + 1});
  mesh.nodeGroups["start"] = {0};
  mesh.nodeGroups["end"] = {count - 1};
  mesh.lineGroups["all"] = range(0, count - 1);
  assignTags(mesh);
  return mesh;
}

MeshData strip(const StripParams& params, const std::string& name) {
  const std::string generator = "strip";
  const std::vector<Point3> path = samplePolyline(generator, "path", params.path, params.divisions);
  requireFinite(generator, "width", params.width);
  const double widthLength = norm(params.width);
  if (!(widthLength > 0.0)) invalid(generator, "width", "must be a non-zero vector");
  requireDivisions(generator, "across", params.across);
  const bool alternating = params.pattern == "alternating";
  if (!alternating && params.pattern != "ruled") {
    invalid(generator, "pattern", fmt::format("must be ruled or alternating, got '{}'", params.pattern));
  }
  // A width along a path segment would give zero-area triangles there.
  for (std::size_t s = 0; s + 1 < params.path.size(); ++s) {
    const Point3 along = sub(params.path[s + 1], params.path[s]);
    if (norm(cross(along, params.width)) <= 1e-9 * norm(along) * widthLength) {
      invalid(generator, "width",
              fmt::format("is parallel to path segment {} (points {} and {})", s, s, s + 1));
    }
  }
  const int nAlong = static_cast<int>(path.size());
  const int nAcross = params.across;
  requireCount(generator, "across", 2.0 * nAlong * (nAcross + 1.0));

  MeshData mesh;
  mesh.name = name;
  for (int j = 0; j <= nAcross; ++j) {
    const double s = static_cast<double>(j) / nAcross;
    for (const Point3& p : path) {
      mesh.points.push_back(
          {p[0] + s * params.width[0], p[1] + s * params.width[1], p[2] + s * params.width[2]});
    }
  }
  const auto node = [nAlong](int i, int j) { return j * nAlong + i; };
  // In (along, width) coordinates (i,j), (i+1,j), (i+1,j+1) turns counter-clockwise about along x w.
  for (int j = 0; j < nAcross; ++j) {
    for (int i = 0; i + 1 < nAlong; ++i) {
      addSquare(mesh, node(i, j), node(i + 1, j), node(i + 1, j + 1), node(i, j + 1),
                !alternating || (i + j) % 2 == 0);
    }
  }
  auto& start = mesh.nodeGroups["start"];
  auto& end = mesh.nodeGroups["end"];
  for (int j = 0; j <= nAcross; ++j) {
    start.push_back(node(0, j));
    end.push_back(node(nAlong - 1, j));
  }
  mesh.nodeGroups["side0"] = range(node(0, 0), node(0, 0) + nAlong);
  mesh.nodeGroups["side1"] = range(node(0, nAcross), node(0, nAcross) + nAlong);
  mesh.triangleGroups["all"] = range(0, static_cast<int>(mesh.triangles.size()));
  assignTags(mesh);
  return mesh;
}

MeshData pillow(const PillowParams& params, const std::string& name) {
  MeshData face;
  std::vector<int> rim;
  int centre = -1;  // face node at the exact centre, if there is one
  if (params.shape == "rectangle") {
    face = buildRectangle(params.rectangle, "pillow", "rectangle.");
    rim = face.nodeGroups.at("boundary");
    const int nx = params.rectangle.divisions[0], ny = params.rectangle.divisions[1];
    if (nx % 2 == 0 && ny % 2 == 0) {
      centre = (ny / 2) * (nx + 1) + nx / 2;
    } else if (params.rectangle.pattern == "cross" && nx % 2 == 1 && ny % 2 == 1) {
      centre = (nx + 1) * (ny + 1) + (ny / 2) * nx + nx / 2;
    }
  } else if (params.shape == "disc") {
    face = buildDisc(params.disc, "pillow", "disc.");
    rim = face.nodeGroups.at("rim");
    centre = 0;
  } else {
    invalid("pillow", "shape", fmt::format("must be rectangle or disc, got '{}'", params.shape));
  }

  MeshData mesh;
  mesh.name = name;
  const int faceNodes = static_cast<int>(face.points.size());
  const int faceTriangles = static_cast<int>(face.triangles.size());
  mesh.points = face.points;
  std::vector<bool> onRim(faceNodes, false);
  for (const int v : rim) onRim[v] = true;
  // Bottom face: rim nodes shared with the top, interior nodes duplicated in the face's order.
  std::vector<int> bottomNode(faceNodes);
  for (int v = 0; v < faceNodes; ++v) {
    if (onRim[v]) {
      bottomNode[v] = v;
    } else {
      bottomNode[v] = static_cast<int>(mesh.points.size());
      mesh.points.push_back(face.points[v]);
    }
  }
  mesh.triangles = face.triangles;
  for (const auto& t : face.triangles) {
    // Reversed node order turns the bottom's normal to -z.
    mesh.triangles.push_back({bottomNode[t[0]], bottomNode[t[2]], bottomNode[t[1]]});
  }

  std::vector<int> bottom = rim;
  bottom.reserve(mesh.points.size() - faceNodes + rim.size());
  for (int v = faceNodes; v < static_cast<int>(mesh.points.size()); ++v) bottom.push_back(v);
  std::sort(bottom.begin(), bottom.end());
  std::sort(rim.begin(), rim.end());
  mesh.nodeGroups["rim"] = rim;
  mesh.nodeGroups["top"] = range(0, faceNodes);
  mesh.nodeGroups["bottom"] = bottom;
  if (centre >= 0) {
    mesh.nodeGroups["top_center"] = {centre};
    mesh.nodeGroups["bottom_center"] = {bottomNode[centre]};
  }
  mesh.triangleGroups["top"] = range(0, faceTriangles);
  mesh.triangleGroups["bottom"] = range(faceTriangles, 2 * faceTriangles);
  mesh.triangleGroups["all"] = range(0, 2 * faceTriangles);
  assignTags(mesh);
  return mesh;
}

}  // namespace fsi::structure
