// Bulk viscosity with selective mass scaling (issue 12, item 7): the viscous stress must use the element's
// scaled density, so that a scaled element keeps the damping ratio b1 that the damped stable step assumes.
#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/elements/BuildModel.hpp"
#include "structure/elements/CableForces.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/integrate/CentralDifference.hpp"
#include "structure/integrate/MassScaling.hpp"
#include "structure/scene/Generators.hpp"

using namespace fsi::structure;

namespace {

// Equal and opposite axial forces ±F on the two ends of a cable along x.
class EndForces final : public Effect {
 public:
  EndForces(int a, int b, double F) : a_(a), b_(b), F_(F) {}
  std::string name() const override { return "end_forces"; }
  void addForces(ForceContext& ctx) const override {
    ctx.fext[3 * a_] -= ctx.loadFactor * F_;
    ctx.fext[3 * b_] += ctx.loadFactor * F_;
  }

 private:
  int a_, b_;
  double F_;
};

}  // namespace

// One free–free cable, mass-scaled to 4x its density, preloaded by end forces and released from its rest
// length: its axial vibration about the preloaded length is one mass–spring–dashpot mode (reduced mass
// m/2, stiffness EA/L0, ω = 2c/L0 — the element's highest mode, which the bulk viscosity is written for).
// The viscous force b1 ρ c A L0 ε̇ with the scaled ρ and c gives the damping ratio
// ζ = b1 ρ c A / (2 (m/2) ω) = b1 exactly; with the unscaled density it would be b1/4. The ratio is measured
// from the logarithmic decrement of the elongation peaks.
TEST(BulkViscosity, ScaledCableVibratesWithTheDampingRatioB1) {
  const double L0 = 1.0, young = 1e9, area = 1e-4, density = 1000.0, b1 = 0.1;
  CableChainParams p;
  p.points = {{0, 0, 0}, {L0, 0, 0}};
  p.divisions = {1};
  MeshInput in;
  in.mesh = cableChain(p, "c");
  in.cableMaterial = 0;
  Model m = buildModel({in}, {}, {CableMaterial{"c", young, area, density}});
  const double c0 = std::sqrt(young / density);
  const double safety = 0.9;
  const MassScalingReport r = applyMassScaling(m, 2.0 * (L0 / c0) * safety, safety);  // twice the step
  ASSERT_EQ(r.scaledElements, 1);
  ASSERT_NEAR(r.addedFraction(), 3.0, 1e-12);  // density x4, wave speed /2
  const double rhoS = 4.0 * density, cS = 0.5 * c0;
  const double nodeMass = 0.5 * rhoS * area * L0;
  const double omega = std::sqrt((young * area / L0) / (0.5 * nodeMass));
  ASSERT_NEAR(omega, 2.0 * cS / L0, 1e-9 * omega);

  const int a = m.meshes[0].node[0], b = m.meshes[0].node[1];
  const double eps0 = 1e-3;  // preload strain; the motion stays in tension (0 < ε < 2 ε0)
  CableForces cable(m.cables, ElementDamping{0.0, b1});
  EndForces load(a, b, young * area * eps0);
  CentralDifferenceSettings s;
  const double period = 2.0 * M_PI / omega;
  s.fixedDt = period / 4000.0;
  CentralDifference cd(m, {&cable, &load}, Constraints{}, s);

  // Peaks of the elongation about the preloaded length over five periods.
  std::vector<double> peaks;
  double prev2 = 0, prev1 = 0;
  for (long n = 0; cd.time() < 5.0 * period; ++n) {
    ASSERT_TRUE(cd.step(1e300, false));
    const double L = std::abs(m.nodes.x[3 * b] - m.nodes.x[3 * a]);
    const double dev = (L - L0) / L0 - eps0;
    if (n >= 2 && prev1 > prev2 && prev1 >= dev && prev1 > 0) peaks.push_back(prev1);
    prev2 = prev1, prev1 = dev;
  }
  ASSERT_GE(peaks.size(), 4u);
  const int cycles = int(peaks.size()) - 1;
  const double delta = std::log(peaks.front() / peaks.back()) / cycles;
  const double zeta = delta / std::sqrt(4.0 * M_PI * M_PI + delta * delta);
  EXPECT_NEAR(zeta, b1, 0.01 * b1) << "log decrement " << delta << " over " << cycles << " cycles";
}

// The membrane's bulk viscous stress b1 ρ c L_e tr(Ė): mass scaling by s raises ρ c by √s (ρ → sρ, c → c/√s),
// so a triangle scaled to 4x its density resists the same in-plane dilatation rate with twice the force of
// the unscaled one (the old code, which kept the unscaled ρ, gave half of it).
TEST(BulkViscosity, ScaledMembraneViscousForceGrowsWithRhoC) {
  auto forces = [](bool scaled) {
    MeshData tri;
    tri.name = "t";
    tri.points = {{0, 0, 0}, {1, 0, 0}, {0.3, 0.8, 0}};
    tri.triangles = {{0, 1, 2}};
    MeshInput in;
    in.mesh = tri;
    in.membraneMaterial = 0;
    Model m = buildModel({in}, {MembraneMaterial{"m", 1e9, 0.3, 1e-3, 1000, true}}, {});
    if (scaled) {
      const double dt0 = referenceStableDt(m);
      applyMassScaling(m, 2.0 * dt0 * 0.9, 0.9);  // 4x the density for twice the step
    }
    // At the reference position (no elastic stress), a uniform in-plane dilatation rate v = 0.1 X.
    for (int i = 0; i < 3 * m.nodes.count; ++i) m.nodes.v[i] = 0.1 * m.nodes.X[i];
    MembraneForces mf(m.membranes, ElementDamping{0.0, 0.06});
    std::vector<double> fi(3 * m.nodes.count, 0.0), fe(fi);
    ForceContext ctx;
    ctx.x = m.nodes.x.data();
    ctx.v = m.nodes.v.data();
    ctx.fint = fi.data();
    ctx.fext = fe.data();
    mf.addForces(ctx);
    return fi;
  };
  const std::vector<double> f1 = forces(false), f4 = forces(true);
  double norm = 0;
  for (double v : f1) norm = std::max(norm, std::abs(v));
  ASSERT_GT(norm, 0.0);
  for (std::size_t i = 0; i < f1.size(); ++i) EXPECT_NEAR(f4[i], 2.0 * f1[i], 1e-12 * norm) << "dof " << i;
}
