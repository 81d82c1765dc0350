#include "coupling/mapping/projection/Quadrature.hpp"

namespace fsi::coupling {

std::vector<QuadPoint> quadraturePoints(const FanTriangulation& fan, int level,
                                        std::vector<std::pair<int, double>>* perTriangle) {
  const int nt = fan.numTriangles();
  const int nc = int(fan.corners.size());
  // Corner → triangles, to find the earlier neighbour across an edge.
  std::vector<int> start(std::size_t(nc) + 1, 0), tris(std::size_t(3 * nt));
  for (const auto& c : fan.triangles)
    for (int k : c) ++start[std::size_t(k) + 1];
  for (int k = 0; k < nc; ++k) start[std::size_t(k) + 1] += start[std::size_t(k)];
  {
    std::vector<int> fill(start.begin(), start.end() - 1);
    for (int t = 0; t < nt; ++t)
      for (int k : fan.triangles[std::size_t(t)]) tris[std::size_t(fill[std::size_t(k)]++)] = t;
  }
  const int s = level, twoS = 2 * level;
  std::vector<QuadPoint> qp;
  qp.reserve(std::size_t(nt) * std::size_t(3 * s * (s + 1) / 2) / 2 + 16);
  std::vector<int> edgeBase(std::size_t(3 * nt), -1);
  for (int t = 0; t < nt; ++t) {
    const std::array<int, 3>& c = fan.triangles[std::size_t(t)];
    const double wSub = fan.area(t) / (3.0 * s * s);
    for (int e = 0; e < 3; ++e) {
      const int a = c[std::size_t(e)], b = c[std::size_t((e + 1) % 3)];
      int base = -1;
      for (int p = start[std::size_t(a)]; p < start[std::size_t(a) + 1] && base < 0; ++p) {
        const int t2 = tris[std::size_t(p)];
        if (t2 >= t) continue;
        const std::array<int, 3>& c2 = fan.triangles[std::size_t(t2)];
        for (int e2 = 0; e2 < 3; ++e2) {
          const int a2 = c2[std::size_t(e2)], b2 = c2[std::size_t((e2 + 1) % 3)];
          if ((a2 == a && b2 == b) || (a2 == b && b2 == a)) {
            base = edgeBase[std::size_t(3 * t2 + e2)];
            break;
          }
        }
      }
      if (base < 0) {
        base = int(qp.size());
        // Points ordered from the smaller corner id, so that both neighbours agree on them.
        const bool aFirst = a < b;
        for (int k = 0; k < s; ++k) {
          const double frac = double(2 * k + 1) / twoS;  // distance from the smaller corner
          std::array<double, 3> bary{0.0, 0.0, 0.0};
          bary[std::size_t(e)] = aFirst ? 1.0 - frac : frac;
          bary[std::size_t((e + 1) % 3)] = aFirst ? frac : 1.0 - frac;
          qp.push_back({t, bary, 0.0});
        }
      }
      edgeBase[std::size_t(3 * t + e)] = base;
      for (int k = 0; k < s; ++k) {
        qp[std::size_t(base + k)].weight += wSub;
        if (perTriangle) perTriangle->push_back({base + k, wSub});
      }
    }
    for (int i = 1; i < twoS; ++i)
      for (int j = 1; i + j < twoS; ++j) {
        const int k = twoS - i - j;
        if ((i % 2) + (j % 2) + (k % 2) != 2) continue;
        qp.push_back({t, {double(i) / twoS, double(j) / twoS, double(k) / twoS}, 2.0 * wSub});
        if (perTriangle) perTriangle->push_back({int(qp.size()) - 1, 2.0 * wSub});
      }
  }
  return qp;
}

}  // namespace fsi::coupling
