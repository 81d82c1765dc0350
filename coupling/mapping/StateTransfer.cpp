#include "coupling/mapping/StateTransfer.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <optional>

#include "coupling/interface/InterfaceMesh.hpp"
#include "coupling/interface/SurfaceSearch.hpp"
#include "structure/model/Error.hpp"

namespace fsi::coupling {

namespace {

using P3 = std::array<double, 3>;

P3 at(const std::vector<double>& v, int i) {
  return {v[3 * std::size_t(i)], v[3 * std::size_t(i) + 1], v[3 * std::size_t(i) + 2]};
}

double dist2(const P3& a, const P3& b) {
  return (a[0] - b[0]) * (a[0] - b[0]) + (a[1] - b[1]) * (a[1] - b[1]) + (a[2] - b[2]) * (a[2] - b[2]);
}

// Closest point of segment ab to p as the parameter s in [0, 1] (a + s (b - a)).
double segmentParameter(const P3& p, const P3& a, const P3& b) {
  double ab2 = 0, ap_ab = 0;
  for (int k = 0; k < 3; ++k) {
    ab2 += (b[k] - a[k]) * (b[k] - a[k]);
    ap_ab += (p[k] - a[k]) * (b[k] - a[k]);
  }
  return ab2 > 0 ? std::clamp(ap_ab / ab2, 0.0, 1.0) : 0.0;
}

}  // namespace

std::vector<double> transferDisplacement(const structure::ResultsFrame& source,
                                         const structure::Model& target, const std::string& sourceName,
                                         double maxDistance, StateTransferReport* report) {
  const int ns = source.numNodes();
  if (ns == 0) throw InputError(fmt::format("{}: the frame has no nodes", sourceName));
  std::vector<double> X0(source.coordinates.size());  // the source's reference geometry
  for (std::size_t d = 0; d < X0.size(); ++d) X0[d] = source.coordinates[d] - source.displacement[d];
  if (maxDistance < 0) {
    P3 lo{}, hi{};
    lo.fill(std::numeric_limits<double>::infinity());
    hi.fill(-std::numeric_limits<double>::infinity());
    for (int i = 0; i < ns; ++i)
      for (int k = 0; k < 3; ++k) {
        lo[std::size_t(k)] = std::min(lo[std::size_t(k)], X0[3 * std::size_t(i) + std::size_t(k)]);
        hi[std::size_t(k)] = std::max(hi[std::size_t(k)], X0[3 * std::size_t(i) + std::size_t(k)]);
      }
    maxDistance = 0.05 * std::sqrt(dist2(lo, hi));
  }

  const structure::Nodes& N = target.nodes;
  const std::size_t nt = std::size_t(N.count);
  // What each target node belongs to, and the summed normal of its triangles (the way its surface faces).
  std::vector<char> onMembrane(nt, 0), onCable(nt, 0);
  std::vector<P3> facing(nt, P3{0, 0, 0});
  const auto& mc = target.membranes.conn;
  for (int e = 0; e < target.membranes.count; ++e) {
    const int a = mc[3 * std::size_t(e)], b = mc[3 * std::size_t(e) + 1], c = mc[3 * std::size_t(e) + 2];
    const P3 A = at(N.X, a), B = at(N.X, b), C = at(N.X, c);
    const P3 n{(B[1] - A[1]) * (C[2] - A[2]) - (B[2] - A[2]) * (C[1] - A[1]),
               (B[2] - A[2]) * (C[0] - A[0]) - (B[0] - A[0]) * (C[2] - A[2]),
               (B[0] - A[0]) * (C[1] - A[1]) - (B[1] - A[1]) * (C[0] - A[0])};
    for (const int i : {a, b, c}) {
      onMembrane[std::size_t(i)] = 1;
      for (int k = 0; k < 3; ++k) facing[std::size_t(i)][std::size_t(k)] += n[std::size_t(k)];
    }
  }
  for (int e = 0; e < target.cables.count; ++e) {
    onCable[std::size_t(target.cables.conn[2 * std::size_t(e)])] = 1;
    onCable[std::size_t(target.cables.conn[2 * std::size_t(e) + 1])] = 1;
  }

  InterfaceMesh surface;
  for (int i = 0; i < ns; ++i) surface.points.push_back(at(X0, i));
  for (const auto& t : source.triangles) surface.addFace({t[0], t[1], t[2]});
  const bool haveSurface = !source.triangles.empty();
  std::optional<SurfaceSearch> search;
  if (haveSurface) search.emplace(surface);

  StateTransferReport rep;
  std::vector<double> u(3 * nt, 0.0);
  int hint = -1;
  for (std::size_t i = 0; i < nt; ++i) {
    const P3 x = at(N.X, int(i));
    double distance = 0;
    if (onMembrane[i] && haveSurface) {
      SurfacePoint p = search->closest(x, hint);
      const P3& f = facing[i];
      if (f[0] != 0 || f[1] != 0 || f[2] != 0) {
        // The facing triangle unless it is much farther: a wedge's other skin can be nearer than a coarse
        // facet's sag, but a target surface oriented unlike the source's must not jump across the body.
        const SurfacePoint q = search->closestFacing(x, f, hint);
        if (q.triangle >= 0 && q.distance <= 10.0 * p.distance + 1e-9 * maxDistance) p = q;
      }
      hint = p.triangle;
      search->fan().forEachWeight(p.triangle, p.bary, [&](int node, double w) {
        for (std::size_t k = 0; k < 3; ++k)
          u[3 * i + k] += w * source.displacement[3 * std::size_t(node) + k];
      });
      distance = p.distance;
      ++rep.membraneNodes;
    } else if (onCable[i] && !source.lines.empty()) {
      double best = std::numeric_limits<double>::infinity(), bestS = 0;
      int bestLine = -1;
      for (std::size_t l = 0; l < source.lines.size(); ++l) {
        const P3 a = at(X0, source.lines[l][0]), b = at(X0, source.lines[l][1]);
        const double s = segmentParameter(x, a, b);
        const P3 q{a[0] + s * (b[0] - a[0]), a[1] + s * (b[1] - a[1]), a[2] + s * (b[2] - a[2])};
        const double d2 = dist2(x, q);
        if (d2 < best) {
          best = d2;
          bestS = s;
          bestLine = int(l);
        }
      }
      const auto& l = source.lines[std::size_t(bestLine)];
      for (std::size_t k = 0; k < 3; ++k)
        u[3 * i + k] = (1 - bestS) * source.displacement[3 * std::size_t(l[0]) + k] +
                       bestS * source.displacement[3 * std::size_t(l[1]) + k];
      distance = std::sqrt(best);
      ++rep.cableNodes;
    } else {
      double best = std::numeric_limits<double>::infinity();
      int nearest = 0;
      for (int j = 0; j < ns; ++j) {
        const double d2 = dist2(x, at(X0, j));
        if (d2 < best) {
          best = d2;
          nearest = j;
        }
      }
      for (std::size_t k = 0; k < 3; ++k) u[3 * i + k] = source.displacement[3 * std::size_t(nearest) + k];
      distance = std::sqrt(best);
      ++rep.pointNodes;
    }
    if (distance > rep.largestDistance) {
      rep.largestDistance = distance;
      rep.farthestNode = int(i);
    }
    if (distance > maxDistance)
      throw InputError(fmt::format(
          "{}: node {} at ({:.6g}, {:.6g}, {:.6g}) is {:.3g} m from the nearest {} of that run's reference "
          "geometry (at most {:.3g} m): the start state is not of this model's geometry",
          sourceName, N.tag[i], x[0], x[1], x[2], distance,
          onMembrane[i] && haveSurface ? "triangle"
                                       : (onCable[i] && !source.lines.empty() ? "cable" : "node"),
          maxDistance));
  }
  if (report) *report = rep;
  return u;
}

}  // namespace fsi::coupling
