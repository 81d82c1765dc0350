#pragma once
// What cables and bars share besides the force kernel (AxialKernel.hpp): lumped mass, stable steps, mass
// scaling and the stiffness bounds of a two-node axial element. `Elements` is a structure of arrays with
// count, conn (2 per element), restLength, invWaveSpeed and blocks (begin, end, density, area,
// axialStiffness per block). TensionOnly: a cable's law (slack in compression), otherwise a bar's.

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <vector>

#include "structure/elements/ElementKind.hpp"

namespace fsi::structure::twonode {

/// Half of each element's mass ρ A L0 to each of its nodes.
template <class Elements>
void addLumpedMass(const Elements& el, std::vector<double>& mass) {
  for (const auto& b : el.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const double m = 0.5 * b.density * b.area * el.restLength[e];
      mass[el.conn[2 * e]] += m;
      mass[el.conn[2 * e + 1]] += m;
    }
}

/// The smallest L0 / c (undamped).
template <class Elements>
double referenceStableDt(const Elements& el) {
  double dt = std::numeric_limits<double>::infinity();
  for (int e = 0; e < el.count; ++e) dt = std::min(dt, el.restLength[e] * el.invWaveSpeed[e]);
  return dt;
}

/// The element at `node` with the smallest L0 / c, if any.
template <class Elements>
std::optional<LimitingElement> limitingElementAt(const Elements& el, int node) {
  std::optional<LimitingElement> best;
  for (int e = 0; e < el.count; ++e) {
    if (el.conn[2 * e] != node && el.conn[2 * e + 1] != node) continue;
    const double dt = el.restLength[e] * el.invWaveSpeed[e];
    if (!best || dt < best->stableDt) best = LimitingElement{e, dt, el.restLength[e]};
  }
  return best;
}

/// Raises the density of every element whose L0 / c is below `need` so that it reaches it (c ∝ ρ^-1/2): the
/// extra mass lumped to its nodes, its wave speed lowered.
template <class Elements>
ScaledMass scaleMass(Elements& el, std::vector<double>& mass, double need) {
  ScaledMass r;
  for (const auto& b : el.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const double dt = el.restLength[e] * el.invWaveSpeed[e];
      if (dt >= need) continue;
      const double s = (need / dt) * (need / dt);  // c ∝ ρ^-1/2
      const double extra = 0.5 * (s - 1.0) * b.density * b.area * el.restLength[e];
      mass[el.conn[2 * e]] += extra;
      mass[el.conn[2 * e + 1]] += extra;
      r.added += 2.0 * extra;
      el.invWaveSpeed[e] *= std::sqrt(s);
      ++r.elements;
    }
  return r;
}

/// Row sums and diagonals of the element stiffness K = ka e⊗e + kg (I − e⊗e) on the node blocks [K −K; −K K]
/// at the positions x, with kg = N/L (a compressed bar's negative kg bounded by its magnitude).
template <bool TensionOnly, class Elements>
void addStiffnessBounds(const Elements& el, const double* x, std::vector<double>& dofRow,
                        std::vector<double>& dofDiag) {
  for (const auto& b : el.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const int i = el.conn[2 * e], j = el.conn[2 * e + 1];
      double d[3], L = 0;
      for (int k = 0; k < 3; ++k) d[k] = x[3 * j + k] - x[3 * i + k], L += d[k] * d[k];
      L = std::sqrt(L);
      const double L0 = el.restLength[e];
      const double ka = b.axialStiffness / L0;
      const double kg = TensionOnly ? b.axialStiffness * std::max(0.0, (L - L0) / L0) / L
                                    : std::abs(b.axialStiffness * (L - L0) / L0) / L;
      for (int k = 0; k < 3; ++k) {
        double row = 0;
        for (int l = 0; l < 3; ++l) {
          const double en = d[k] * d[l] / (L * L);
          row += 2.0 * std::abs(ka * en + kg * ((k == l ? 1.0 : 0.0) - en));
        }
        const double diag = ka * d[k] * d[k] / (L * L) + kg * (1.0 - d[k] * d[k] / (L * L));
        dofRow[3 * i + k] += row, dofRow[3 * j + k] += row;
        dofDiag[3 * i + k] += diag, dofDiag[3 * j + k] += diag;
      }
    }
}

}  // namespace fsi::structure::twonode
