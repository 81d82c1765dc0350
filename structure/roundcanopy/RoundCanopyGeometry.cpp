#include "structure/roundcanopy/RoundCanopyGeometry.hpp"

#include <fmt/format.h>

#include <array>
#include <cmath>
#include <vector>

#include "structure/model/Error.hpp"

namespace fsi::structure::roundcanopy {

namespace {

using Vec3 = std::array<double, 3>;
constexpr double kPi = 3.14159265358979323846;

[[noreturn]] void fail(const std::string& key, const std::string& what) {
  throw InputError(fmt::format("round_canopy generator: parameter '{}' {}", key, what));
}

/// The profile (r, z) of a radial at station u, skirt radius 1, and its derivative d(r, z)/du.
struct Profile {
  double r, z, dr, dz;
};

Profile profile(const RoundCanopyParams& p, double u) {
  switch (p.shape) {
    case CanopyShape::flat:
      return {u, 0.0, 1.0, 0.0};
    case CanopyShape::conical: {
      const double t = std::tan(p.coneAngleDeg * kPi / 180.0);
      return {u, (1.0 - u) * t, 1.0, -t};
    }
    case CanopyShape::hemispherical:
      return {std::sin(0.5 * kPi * u), std::cos(0.5 * kPi * u), 0.5 * kPi * std::cos(0.5 * kPi * u),
              -0.5 * kPi * std::sin(0.5 * kPi * u)};
  }
  return {};
}

/// The station u at which the profile's radius is r (skirt radius 1, 0 <= r < 1).
double stationAtRadius(const RoundCanopyParams& p, double r) {
  return p.shape == CanopyShape::hemispherical ? 2.0 / kPi * std::asin(r) : r;
}

/// The cloth point of gore k (0-based) at radial station u and chord fraction t (0: radial k, 1: radial k+1),
/// skirt radius 1.
Vec3 clothPoint(const RoundCanopyParams& p, int k, double u, double t) {
  const int n = p.gores;
  const Profile f = profile(p, u);
  const double a0 = 2.0 * kPi * k / n, a1 = 2.0 * kPi * (k + 1) / n;
  Vec3 x{};
  const double c0 = std::cos(a0), s0 = std::sin(a0), c1 = std::cos(a1), s1 = std::sin(a1);
  x[0] = f.r * ((1.0 - t) * c0 + t * c1);
  x[1] = f.r * ((1.0 - t) * s0 + t * s1);
  x[2] = f.z;
  if (p.bulge > 0 && f.r > 0) {
    // The gore's outward normal in its centre plane: perpendicular to the chord and to the centre line
    // M(u) = (r cos(π/N) e_mid, z), pointing away from the axis and the inflow.
    const double half = kPi / n, am = a0 + half;
    double nr = -f.dz, nz = f.dr * std::cos(half);
    const double len = std::hypot(nr, nz);
    nr /= len;
    nz /= len;
    const double w = 2.0 * f.r * std::sin(half), h = p.bulge * w;
    const double rho = (0.25 * w * w + h * h) / (2.0 * h), xc = (t - 0.5) * w;
    const double d = std::sqrt(std::max(0.0, rho * rho - xc * xc)) - (rho - h);
    x[0] += d * nr * std::cos(am);
    x[1] += d * nr * std::sin(am);
    x[2] += d * nz;
  }
  return x;
}

Vec3 minus(const Vec3& a, const Vec3& b) {
  return {a[0] - b[0], a[1] - b[1], a[2] - b[2]};
}

double crossNorm(const Vec3& a, const Vec3& b) {
  return std::sqrt(std::pow(a[1] * b[2] - a[2] * b[1], 2) + std::pow(a[2] * b[0] - a[0] * b[2], 2) +
                   std::pow(a[0] * b[1] - a[1] * b[0], 2));
}

/// Gauss-Legendre nodes and weights on [0, 1].
void gaussLegendre(int n, std::vector<double>& x, std::vector<double>& w) {
  x.assign(n, 0.0);
  w.assign(n, 0.0);
  for (int i = 0; i < n; ++i) {
    double z = std::cos(kPi * (i + 0.75) / (n + 0.5)), dp = 0;
    for (int it = 0; it < 100; ++it) {
      double p0 = 1.0, p1 = z;
      for (int j = 2; j <= n; ++j) {
        const double p2 = ((2.0 * j - 1.0) * z * p1 - (j - 1.0) * p0) / j;
        p0 = p1;
        p1 = p2;
      }
      dp = n * (z * p1 - p0) / (z * z - 1.0);
      const double dz = p1 / dp;
      z -= dz;
      if (std::abs(dz) < 1e-15) break;
    }
    x[i] = 0.5 * (1.0 - z);
    w[i] = 1.0 / ((1.0 - z * z) * dp * dp);
  }
}

void check(const RoundCanopyParams& p) {
  if (!(p.nominalDiameter > 0 && p.nominalDiameter <= kMaxNominalDiameter))
    fail("nominal_diameter",
         fmt::format("must be in (0, {}] m, got {}", kMaxNominalDiameter, p.nominalDiameter));
  if (p.gores < 3 || p.gores > kMaxGores)
    fail("gores", fmt::format("must be in [3, {}], got {}", kMaxGores, p.gores));
  if (p.shape == CanopyShape::conical && !(p.coneAngleDeg > 0 && p.coneAngleDeg <= 80))
    fail("cone_angle", fmt::format("must be in (0, 80] deg, got {}", p.coneAngleDeg));
  if (!(p.bulge >= 0 && p.bulge <= 0.5)) fail("bulge", fmt::format("must be in [0, 0.5], got {}", p.bulge));
  if (p.radialDivisions < 1 || p.radialDivisions > 1000)
    fail("radial_divisions", fmt::format("must be in [1, 1000], got {}", p.radialDivisions));
  if (p.goreDivisions < 1 || p.goreDivisions > 1000)
    fail("gore_divisions", fmt::format("must be in [1, 1000], got {}", p.goreDivisions));
  if (p.lineElements < 1 || p.lineElements > 1000)
    fail("line_elements", fmt::format("must be in [1, 1000], got {}", p.lineElements));
  const double nodes = double(p.gores) * p.goreDivisions * (p.radialDivisions + 1);
  if (nodes > 4e6)
    fail("radial_divisions",
         fmt::format("with {} gores and gore_divisions {} makes {:.3g} cloth nodes, more than 4e6", p.gores,
                     p.goreDivisions, nodes));
  if (!(p.ventDiameter >= 0)) fail("vent_diameter", fmt::format("must be >= 0 m, got {}", p.ventDiameter));
  if (!(p.lineLength > 0 && p.lineLength <= kMaxLineLength))
    fail("line_length", fmt::format("(l_s/D0) must be in (0, {}], got {}", kMaxLineLength, p.lineLength));
  if (p.lineStretch && !(*p.lineStretch > 0 && *p.lineStretch <= 1))
    fail("line_stretch", fmt::format("must be in (0, 1], got {}", *p.lineStretch));
  if (p.riserLength && !(*p.riserLength > 0 && *p.riserLength <= kMaxLineLength * p.nominalDiameter))
    fail("riser_length", fmt::format("must be in (0, {}] m ({} D0), got {}",
                                     kMaxLineLength * p.nominalDiameter, kMaxLineLength, *p.riserLength));
}

}  // namespace

double clothArea(const RoundCanopyParams& params, double u0, double u1) {
  // |X_u × X_t| over one gore by a composite Gauss rule (smooth integrand), times the number of gores.
  std::vector<double> gx, gw;
  gaussLegendre(8, gx, gw);
  const int panelsU = 64, panelsT = params.bulge > 0 ? 16 : 1;
  const double hu = 1e-6, ht = 1e-6;
  double sum = 0;
  for (int pu = 0; pu < panelsU; ++pu) {
    for (int iu = 0; iu < 8; ++iu) {
      const double du = (u1 - u0) / panelsU, u = u0 + du * (pu + gx[iu]);
      for (int pt = 0; pt < panelsT; ++pt) {
        for (int it = 0; it < 8; ++it) {
          const double dt = 1.0 / panelsT, t = dt * (pt + gx[it]);
          const double ua = std::max(0.0, u - hu), ub = std::min(1.0, u + hu);
          const Vec3 xu = minus(clothPoint(params, 0, ub, t), clothPoint(params, 0, ua, t));
          const Vec3 xt = minus(clothPoint(params, 0, u, t + ht), clothPoint(params, 0, u, t - ht));
          sum += gw[iu] * du * gw[it] * dt * crossNorm(xu, xt) / ((ub - ua) * 2.0 * ht);
        }
      }
    }
  }
  return sum * params.gores;
}

RoundCanopyDesign designRoundCanopy(const RoundCanopyParams& p) {
  check(p);
  RoundCanopyDesign d;
  d.nominalArea = 0.25 * kPi * p.nominalDiameter * p.nominalDiameter;
  d.skirtRadius = std::sqrt(d.nominalArea / clothArea(p, 0.0, 1.0));
  d.constructedDiameter = 2.0 * d.skirtRadius;
  d.ventRadius = 0.5 * p.ventDiameter;
  if (d.ventRadius > 0.5 * d.skirtRadius)
    fail("vent_diameter", fmt::format("must be at most half the constructed diameter ({:.6g} m), got {}",
                                      d.skirtRadius, p.ventDiameter));
  d.ventU = stationAtRadius(p, d.ventRadius / d.skirtRadius);
  d.ventArea = d.ventU > 0 ? d.skirtRadius * d.skirtRadius * clothArea(p, 0.0, d.ventU) : 0.0;
  d.height = d.skirtRadius * profile(p, 0.0).z;
  d.lineLength = p.lineLength * p.nominalDiameter;
  if (d.lineLength <= 1.01 * d.skirtRadius)
    fail("line_length",
         fmt::format("(l_s/D0 = {}) must exceed 1.01 × the skirt radius over D0 ({:.4g}): the lines "
                     "from the skirt must reach the axis below it",
                     p.lineLength, 1.01 * d.skirtRadius / p.nominalDiameter));
  d.confluenceDepth = std::sqrt(d.lineLength * d.lineLength - d.skirtRadius * d.skirtRadius);
  return d;
}

MeshData buildRoundCanopy(const RoundCanopyParams& p, const std::string& name) {
  const RoundCanopyDesign d = designRoundCanopy(p);
  const int n = p.gores, g = p.goreDivisions, m = p.radialDivisions, ring = n * g;
  const double radius = d.skirtRadius;
  const bool apex = d.ventU == 0.0;
  MeshData mesh;
  mesh.name = name;
  auto add = [&](const Vec3& x) {
    mesh.points.push_back(x);
    return int(mesh.points.size()) - 1;
  };
  // Rings of cloth nodes, vent (or apex) to skirt.
  std::vector<int> ringStart(m + 1);
  for (int i = 0; i <= m; ++i) {
    const double u = d.ventU + (1.0 - d.ventU) * i / m;
    ringStart[i] = int(mesh.points.size());
    if (i == 0 && apex) {
      add({0.0, 0.0, radius * profile(p, 0.0).z});
      continue;
    }
    for (int k = 0; k < n; ++k)
      for (int j = 0; j < g; ++j) {
        Vec3 x = clothPoint(p, k, u, double(j) / g);
        add({radius * x[0], radius * x[1], radius * x[2]});
      }
  }
  auto node = [&](int i, int j) {
    return (i == 0 && apex) ? ringStart[0] : ringStart[i] + (j % ring + ring) % ring;
  };
  // Triangles: normals out of the canopy; each quad split along the diagonal mirrored about its gore's
  // centre.
  std::vector<int> canopy;
  for (int k = 0; k < n; ++k) {
    std::vector<int>& gore = mesh.triangleGroups[fmt::format("gore_{}", k + 1)];
    for (int i = 0; i < m; ++i)
      for (int j = k * g; j < (k + 1) * g; ++j) {
        const int a = node(i, j), b = node(i, j + 1), c = node(i + 1, j + 1), e = node(i + 1, j);
        auto tri = [&](int x, int y, int z) {
          gore.push_back(int(mesh.triangles.size()));
          canopy.push_back(int(mesh.triangles.size()));
          mesh.triangles.push_back({x, y, z});
        };
        if (i == 0 && apex) {
          tri(a, e, c);
        } else if (2 * (j - k * g) < g) {
          tri(a, c, b);
          tri(a, e, c);
        } else {
          tri(a, e, b);
          tri(b, e, c);
        }
      }
  }
  mesh.triangleGroups["canopy"] = canopy;
  mesh.triangleGroups["skin"] = canopy;
  // Reinforcement tapes.
  auto line = [&](const char* set, int a, int b) {
    mesh.lineGroups[set].push_back(int(mesh.lines.size()));
    mesh.lines.push_back({a, b});
  };
  for (const char* set : {"radials", "skirt_band", "vent_band", "tapes", "lines", "riser"})
    mesh.lineGroups[set];
  if (p.radialTapes)
    for (int k = 0; k < n; ++k)
      for (int i = 0; i < m; ++i) line("radials", node(i, k * g), node(i + 1, k * g));
  if (p.skirtBand)
    for (int j = 0; j < ring; ++j) line("skirt_band", node(m, j), node(m, j + 1));
  if (p.ventBand && !apex)
    for (int j = 0; j < ring; ++j) line("vent_band", node(0, j), node(0, j + 1));
  for (const char* set : {"radials", "skirt_band", "vent_band"})
    for (int e : mesh.lineGroups[set]) mesh.lineGroups["tapes"].push_back(e);
  // Suspension lines from the radials' skirt ends to the confluence point; the riser below it.
  const int clothNodes = int(mesh.points.size());
  const int confluence = add({0.0, 0.0, -d.confluenceDepth});
  struct RopeNode {
    int node, from, to;
    double s;
  };
  std::vector<RopeNode> ropeNodes;  // the lines' inner nodes, for the start at line stretch
  auto rope = [&](const char* set, int from, int to) {
    const Vec3 a = mesh.points[from], b = mesh.points[to];
    int prev = from;
    for (int e = 1; e <= p.lineElements; ++e) {
      const double s = double(e) / p.lineElements;
      const int next =
          e == p.lineElements
              ? to
              : add({a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])});
      if (e < p.lineElements) ropeNodes.push_back({next, from, to, s});
      line(set, prev, next);
      prev = next;
    }
  };
  for (int k = 0; k < n; ++k) rope("lines", node(m, k * g), confluence);
  int payload = confluence;
  if (p.riserLength) {
    payload = add({0.0, 0.0, -d.confluenceDepth - *p.riserLength});
    rope("riser", confluence, payload);
  }
  if (p.lineStretch) {
    // The start at line stretch (RoundCanopyGeometry.hpp): each ring s times nearer the axis, the rings
    // stacked so that the shortest meridian segment between them keeps its length, the lines straight from
    // the confluence point.
    const double s = *p.lineStretch, ls = d.lineLength;
    const double lift = std::sqrt(ls * ls - s * s * radius * radius) - d.confluenceDepth;
    std::vector<double> z(m + 1, lift);
    for (int i = m - 1; i >= 0; --i) {
      double dz = 1e300;
      for (int j = 0; j < ring; ++j) {
        const Vec3 a = mesh.points[node(i, j)], b = mesh.points[node(i + 1, j)];
        const double h2 = (b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]);
        dz = std::min(dz, std::sqrt(std::max(0.0, h2 * (1.0 - s * s) + (b[2] - a[2]) * (b[2] - a[2]))));
      }
      z[i] = z[i + 1] + dz;
    }
    mesh.startPoints = mesh.points;
    for (int i = 0; i <= m; ++i) {
      const int end = i < m ? ringStart[i + 1] : clothNodes;
      for (int q = ringStart[i]; q < end; ++q)
        mesh.startPoints[q] = {s * mesh.points[q][0], s * mesh.points[q][1], z[i]};
    }
    for (const RopeNode& r : ropeNodes) {
      const Vec3 a = mesh.startPoints[r.from], b = mesh.startPoints[r.to];
      for (int k = 0; k < 3; ++k) mesh.startPoints[r.node][k] = a[k] + r.s * (b[k] - a[k]);
    }
  }
  // Node sets.
  auto& vent = mesh.nodeGroups["vent"];
  for (int j = 0; j < (apex ? 1 : ring); ++j) vent.push_back(node(0, j));
  mesh.nodeGroups["apex"] = vent;
  auto& skirt = mesh.nodeGroups["skirt"];
  for (int j = 0; j < ring; ++j) skirt.push_back(node(m, j));
  auto& ends = mesh.nodeGroups["radial_ends"];
  for (int k = 0; k < n; ++k) ends.push_back(node(m, k * g));
  mesh.nodeGroups["confluence"] = {confluence};
  mesh.nodeGroups["payload"] = {payload};
  // 1-based ids, as the other generators.
  for (std::size_t i = 0; i < mesh.points.size(); ++i) mesh.pointTags.push_back(long(i) + 1);
  for (std::size_t i = 0; i < mesh.triangles.size(); ++i) mesh.triangleTags.push_back(long(i) + 1);
  for (std::size_t i = 0; i < mesh.lines.size(); ++i) mesh.lineTags.push_back(long(i) + 1);
  return mesh;
}

}  // namespace fsi::structure::roundcanopy
