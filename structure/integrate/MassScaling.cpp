#include "structure/integrate/MassScaling.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace fsi::structure {

double referenceStableDt(const Model& model) {
  double dt = std::numeric_limits<double>::infinity();
  const MembraneTriangles& T = model.membranes;
  for (int e = 0; e < T.count; ++e)
    dt = std::min(dt, std::sqrt(T.refStep2[e]));  // smallest reference altitude / c
  const Cables& C = model.cables;
  for (int e = 0; e < C.count; ++e) dt = std::min(dt, C.restLength[e] * C.invWaveSpeed[e]);
  return dt;
}

MassScalingReport applyMassScaling(Model& model, double targetDt, double safety) {
  MassScalingReport r;
  Nodes& N = model.nodes;
  for (double m : N.physicalMass) r.physicalMass += m;
  const double need = targetDt / safety;  // required L_e/c_e
  MembraneTriangles& T = model.membranes;
  for (const auto& b : T.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const double* g = &T.geo[MembraneTriangles::kGeo * e];
      const double dt = std::sqrt(T.refStep2[e]);
      if (dt >= need) continue;
      const double s = (need / dt) * (need / dt);               // c ∝ ρ^-1/2
      const double extra = (s - 1.0) * b.density * g[3] / 3.0;  // g[3] = t A0
      for (int k = 0; k < 3; ++k) N.mass[T.conn[3 * e + k]] += extra;
      r.addedMass += 3.0 * extra;
      T.invWaveSpeed[e] *= std::sqrt(s);
      T.refStep2[e] *= s;
      ++r.scaledElements;
    }
  Cables& C = model.cables;
  for (const auto& b : C.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const double dt = C.restLength[e] * C.invWaveSpeed[e];
      if (dt >= need) continue;
      const double s = (need / dt) * (need / dt);
      const double extra = 0.5 * (s - 1.0) * b.density * b.area * C.restLength[e];
      N.mass[C.conn[2 * e]] += extra;
      N.mass[C.conn[2 * e + 1]] += extra;
      r.addedMass += 2.0 * extra;
      C.invWaveSpeed[e] *= std::sqrt(s);
      ++r.scaledElements;
    }
  for (int i = 0; i < N.count; ++i)
    for (int k = 0; k < 3; ++k) N.invMassDof[3 * i + k] = 1.0 / N.mass[i];
  return r;
}

}  // namespace fsi::structure
