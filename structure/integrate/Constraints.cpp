#include "structure/integrate/Constraints.hpp"

namespace fsi::structure {

namespace {
// Replaces the tied part of each member's q by the group's mass-weighted mean: q_i ← (q_i − t(q_i)) + mean,
// written as base_i + q_i into out (base = X for a displacement, null for a velocity), and moves x by dt
// times the change of q (x may be null). Written this way a tied component of an axis-aligned direction is
// the mean itself, bit for bit the same on every member.
void replaceByMean(const TieGroups& t, const double* mass, const double* base, double* out, double* x,
                   double dt) {
  auto q = [&](int i, int k) { return base ? out[3 * i + k] - base[3 * i + k] : out[3 * i + k]; };
  for (int g = 0; g < t.groups(); ++g) {
    double mean[3] = {0, 0, 0}, m = 0;
    for (int j = t.start[g]; j < t.start[g + 1]; ++j) {
      const int i = t.nodes[j];
      const double qi[3] = {q(i, 0), q(i, 1), q(i, 2)};
      double ti[3];
      t.tiedPart(g, qi, ti);
      for (int k = 0; k < 3; ++k) mean[k] += mass[i] * ti[k];
      m += mass[i];
    }
    for (int k = 0; k < 3; ++k) mean[k] /= m;
    for (int j = t.start[g]; j < t.start[g + 1]; ++j) {
      const int i = t.nodes[j];
      const double qi[3] = {q(i, 0), q(i, 1), q(i, 2)};
      double ti[3];
      t.tiedPart(g, qi, ti);
      for (int k = 0; k < 3; ++k) {
        const double qNew = (qi[k] - ti[k]) + mean[k];
        out[3 * i + k] = base ? base[3 * i + k] + qNew : qNew;
        if (x) x[3 * i + k] += dt * (qNew - qi[k]);
      }
    }
  }
}
}  // namespace

void TieGroups::shareByMass(const double* mass, double* r) const {
  for (int g = 0; g < groups(); ++g) {
    double total[3] = {0, 0, 0}, m = 0;
    for (int j = start[g]; j < start[g + 1]; ++j) {
      const int i = nodes[j];
      double t[3];
      tiedPart(g, r + 3 * i, t);
      for (int k = 0; k < 3; ++k) total[k] += t[k];
      m += mass[i];
    }
    for (int j = start[g]; j < start[g + 1]; ++j) {
      const int i = nodes[j];
      double t[3];
      tiedPart(g, r + 3 * i, t);
      for (int k = 0; k < 3; ++k) r[3 * i + k] = (r[3 * i + k] - t[k]) + mass[i] / m * total[k];
    }
  }
}

void TieGroups::project(const double* mass, double* v, double* x, double dt) const {
  replaceByMean(*this, mass, nullptr, v, x, dt);
}

void TieGroups::projectDisplacement(const double* mass, const double* X, double* x) const {
  replaceByMean(*this, mass, X, x, nullptr, 0.0);
}

void Constraints::applyTo(Nodes& nodes) const {
  for (int d : fixedDofs) {
    nodes.invMassDof[d] = 0.0;
    nodes.v[d] = 0.0;
  }
  for (const auto& p : prescribed) nodes.invMassDof[3 * p.node + p.component] = 0.0;
  if (!ties.empty()) {
    ties.project(nodes.mass.data(), nodes.v.data(), nullptr, 0.0);
    ties.projectDisplacement(nodes.mass.data(), nodes.X.data(), nodes.x.data());
  }
}

void Constraints::reactions(const Nodes& nodes, std::vector<double>& r) const {
  r.resize(nodes.fint.size());
  for (std::size_t d = 0; d < r.size(); ++d) r[d] = nodes.fint[d] - nodes.fext[d];
  ties.shareByMass(nodes.mass.data(), r.data());
}

}  // namespace fsi::structure
