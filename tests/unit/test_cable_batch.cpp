// The batched cable kernel (CableBatch.hpp, 4 lanes with AVX, 2 without) and the per-cable kernel it keeps as
// its remainder loop, both against a plain per-cable evaluation written out here: forces, strain energy and
// stable step to round-off for every cable count (whole batches and remainders), several material blocks,
// slack cables (zero elastic force), cables at and across the slack/taut boundary, with and without Rayleigh
// β and bulk viscosity, whole and in ranges (the threads' shares).
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "ForceDifference.hpp"
#include "structure/effects/ThreadedForces.hpp"
#include "structure/elements/BuildModel.hpp"
#include "structure/elements/CableForces.hpp"
#include "structure/model/Model.hpp"

using namespace fsi::structure;

namespace {

constexpr double kTol = 1e-12;
const ElementDamping kNone{}, kViscous{2.0e-6, 0.06};

struct Result {
  std::vector<double> f;  ///< internal forces, 3 per node
  double energy = 0, dt = 0;
};

// The cable as docs/ARCHITECTURE.md and CableForces.hpp state it, one cable at a time: ε = (L − L0)/L0,
// T = EA max(0, ε) + (β + b1 L0/c) EA ε̇ with ε̇ = (v_j − v_i)·d/(L L0), f_j = T d/L = −f_i; energy
// ½ EA max(0, ε)² L0; stable step (L0/c)(sqrt(1 + ξ²) − ξ), ξ = b1 + β c/L0.
Result reference(const Model& m, const ElementDamping& d) {
  const Cables& C = m.cables;
  Result r;
  r.f.assign(3 * std::size_t(m.nodes.count), 0.0);
  r.dt = std::numeric_limits<double>::infinity();
  const double* x = m.nodes.x.data();
  const double* v = m.nodes.v.data();
  for (const CableBlock& b : C.blocks)
    for (int e = b.begin; e < b.end; ++e) {
      const int i = C.conn[2 * e], j = C.conn[2 * e + 1];
      double dx[3], dv[3];
      for (int k = 0; k < 3; ++k) dx[k] = x[3 * j + k] - x[3 * i + k], dv[k] = v[3 * j + k] - v[3 * i + k];
      const double L = std::sqrt(dx[0] * dx[0] + dx[1] * dx[1] + dx[2] * dx[2]);
      const double L0 = C.restLength[e];
      const double stretch = std::max(0.0, (L - L0) / L0);
      double T = b.axialStiffness * stretch;
      r.energy += 0.5 * b.axialStiffness * stretch * stretch * L0;
      if (d.enabled()) {
        const double rate = (dv[0] * dx[0] + dv[1] * dx[1] + dv[2] * dx[2]) / (L * L0);
        T += (d.beta + d.bulkB1 * C.invWaveSpeed[e] * L0) * b.axialStiffness * rate;
      }
      for (int k = 0; k < 3; ++k) {
        r.f[3 * std::size_t(i) + k] -= T * dx[k] / L;
        r.f[3 * std::size_t(j) + k] += T * dx[k] / L;
      }
      const double t0 = L0 * C.invWaveSpeed[e], xi = d.bulkB1 + d.beta / t0;
      r.dt = std::min(r.dt, t0 * (std::sqrt(1.0 + xi * xi) - xi));
    }
  return r;
}

// The effect's evaluation: whole (addForces), or as consecutive ranges [cuts[k], cuts[k+1]) into one context
// (what the threads' shares do, each into its own buffer; here one buffer, so the sums are the same).
Result evaluate(const Model& m, const ElementDamping& d, CableKernel kernel,
                const std::vector<int>& cuts = {}) {
  const CableForces cf(m.cables, d, kernel);
  Result r;
  r.f.assign(3 * std::size_t(m.nodes.count), 0.0);
  std::vector<double> fext(r.f.size(), 0.0);
  ForceContext ctx;
  ctx.x = m.nodes.x.data();
  ctx.v = m.nodes.v.data();
  ctx.fint = r.f.data();
  ctx.fext = fext.data();
  ctx.wantEnergy = true;
  if (cuts.empty()) {
    cf.addForces(ctx);
  } else {
    for (std::size_t k = 0; k + 1 < cuts.size(); ++k) cf.addRange(ctx, cuts[k], cuts[k + 1]);
  }
  r.energy = ctx.strainEnergy;
  r.dt = ctx.minStableDt;
  for (double fe : fext) EXPECT_EQ(fe, 0.0);  // internal forces only
  return r;
}

// Largest force difference relative to the largest reference force (at a node shared by several cables the
// sums are added in another order, so the node's own small resultant is no scale).
double forceError(const Result& a, const Result& ref) {
  return test::largestRelativeDifference(a.f, ref.f);
}

// Both kernels against the reference: forces, energy, step.
void expectAgree(const Model& m, const ElementDamping& d, const std::string& what,
                 const std::vector<int>& cuts = {}) {
  const Result ref = reference(m, d);
  for (CableKernel kernel : {CableKernel::Batched, CableKernel::PerElement}) {
    const std::string k = what + (kernel == CableKernel::Batched ? ", batched" : ", per cable");
    const Result r = evaluate(m, d, kernel, cuts);
    EXPECT_LE(forceError(r, ref), kTol) << k;
    EXPECT_LE(std::abs(r.energy - ref.energy), kTol * ref.energy) << k;
    EXPECT_LE(std::abs(r.dt - ref.dt), kTol * ref.dt) << k;
    EXPECT_TRUE(std::isfinite(r.dt)) << k;
  }
}

// A connected random net: `counts[b]` cables of block b (its own material, EA differing per block so a lane
// reading another block's constant would show) between the points of a jittered 3D lattice, each cable from
// a point to one of its lattice neighbours, so nodes are shared by several cables and by neighbouring lanes.
// Displaced so that the strains scatter by about ±2 % around zero: about half the cables slack. Random
// velocities for the viscous term.
Model randomNet(const std::vector<int>& counts, unsigned seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<MeshInput> meshes;
  std::vector<CableMaterial> materials;
  for (std::size_t b = 0; b < counts.size(); ++b) {
    const int side = 4;  // 4 x 4 x n lattice
    MeshInput in;
    in.mesh.name = "net" + std::to_string(b);
    const int layers = counts[b] / (side * side) + 2;
    auto at = [&](int i, int j, int k) { return (k * side + j) * side + i; };
    for (int k = 0; k < layers; ++k)
      for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i)
          in.mesh.points.push_back({10.0 * double(b) + i + 0.2 * u(rng), j + 0.2 * u(rng), k + 0.2 * u(rng)});
    std::vector<std::array<int, 2>> candidates;
    for (int k = 0; k < layers; ++k)
      for (int j = 0; j < side; ++j)
        for (int i = 0; i < side; ++i) {
          if (i + 1 < side) candidates.push_back({at(i, j, k), at(i + 1, j, k)});
          if (j + 1 < side) candidates.push_back({at(i, j, k), at(i, j + 1, k)});
          if (k + 1 < layers) candidates.push_back({at(i, j, k), at(i, j, k + 1)});
          if (i + 1 < side && j + 1 < side) candidates.push_back({at(i + 1, j, k), at(i, j + 1, k)});
        }
    std::shuffle(candidates.begin(), candidates.end(), rng);
    candidates.resize(std::size_t(counts[b]));
    // Keep only the points the cables use (a node without an element has no mass); random end order.
    std::vector<int> used(in.mesh.points.size(), -1);
    MeshData kept;
    kept.name = in.mesh.name;
    for (auto& c : candidates) {
      if (u(rng) < 0) std::swap(c[0], c[1]);
      for (int& p : c) {
        if (used[std::size_t(p)] < 0) {
          used[std::size_t(p)] = int(kept.points.size());
          kept.points.push_back(in.mesh.points[std::size_t(p)]);
          kept.pointTags.push_back(long(kept.points.size()));
        }
        p = used[std::size_t(p)];
      }
      kept.lines.push_back(c);
    }
    in.mesh = kept;
    in.cableMaterial = int(b);
    meshes.push_back(in);
    materials.push_back({"c" + std::to_string(b), 1.0e9 * (1.0 + double(b)), 1.0e-5 * (1.0 + 0.5 * double(b)),
                         1000.0 + 300.0 * double(b)});
  }
  Model m = buildModel(meshes, {}, materials);
  for (int i = 0; i < m.nodes.count; ++i)
    for (int k = 0; k < 3; ++k) {
      m.nodes.x[3 * i + k] = m.nodes.X[3 * i + k] + 0.01 * u(rng);
      m.nodes.v[3 * i + k] = 3.0 * u(rng);
    }
  return m;
}

// Disjoint cables (two nodes each), cable e along the unit direction dir(e) with length (1 + strain(e)) L0:
// every node's force is one cable's force, so each cable can be checked against its own scale.
template <class Strain>
Model disjointCables(int count, Strain strain) {
  MeshInput in;
  in.mesh.name = "cables";
  for (int e = 0; e < count; ++e) {
    const double a = 0.7 * e, b = 0.3 * e;  // directions all round
    const double dir[3] = {std::cos(a) * std::cos(b), std::sin(a) * std::cos(b), std::sin(b)};
    const double L0 = 0.5 + 0.01 * e;
    const double o[3] = {3.0 * e, 0.0, 0.0};
    in.mesh.points.push_back({o[0], o[1], o[2]});
    in.mesh.points.push_back({o[0] + L0 * dir[0], o[1] + L0 * dir[1], o[2] + L0 * dir[2]});
    in.mesh.pointTags.push_back(2 * e + 1);
    in.mesh.pointTags.push_back(2 * e + 2);
    in.mesh.lines.push_back({2 * e, 2 * e + 1});
  }
  in.cableMaterial = 0;
  Model m = buildModel({in}, {}, {CableMaterial{"line", 7.0e10, 1.26e-5, 1440}});
  // Cable e of the model (sorted by its lowest node) may be another index than in the mesh: move the second
  // end of every model cable along the cable to its strain.
  for (int e = 0; e < m.cables.count; ++e) {
    const int i = m.cables.conn[2 * e], j = m.cables.conn[2 * e + 1];
    const double s = 1.0 + strain(e);
    for (int k = 0; k < 3; ++k) {
      m.nodes.x[3 * j + k] = m.nodes.X[3 * i + k] + s * (m.nodes.X[3 * j + k] - m.nodes.X[3 * i + k]);
      m.nodes.v[3 * i + k] = 0.0;
      m.nodes.v[3 * j + k] = 0.2 * std::sin(1.0 + e + k);
    }
  }
  return m;
}

// Per-cable comparison on disjoint cables: each cable's end forces to 1e-12 of its own magnitude, and
// exactly zero where the reference is (slack cables without viscosity).
void expectEachCableAgrees(const Model& m, const ElementDamping& d, const std::string& what) {
  const Result ref = reference(m, d);
  for (CableKernel kernel : {CableKernel::Batched, CableKernel::PerElement}) {
    const Result r = evaluate(m, d, kernel);
    for (int e = 0; e < m.cables.count; ++e) {
      double diff = 0, scale = 0;
      for (int end = 0; end < 2; ++end)
        for (int k = 0; k < 3; ++k) {
          const std::size_t dof = 3 * std::size_t(m.cables.conn[2 * e + end]) + std::size_t(k);
          diff = std::max(diff, std::abs(r.f[dof] - ref.f[dof]));
          scale = std::max(scale, std::abs(ref.f[dof]));
        }
      if (scale == 0.0) {
        EXPECT_EQ(diff, 0.0) << what << ", cable " << e;
      } else {
        EXPECT_LE(diff, kTol * scale) << what << ", cable " << e;
      }
    }
    EXPECT_LE(std::abs(r.energy - ref.energy), kTol * ref.energy) << what;
  }
}

}  // namespace

// Every cable count from 1 to 13 (no whole batch, whole batches, every remainder) and two larger ones, with
// and without viscosity.
TEST(CableBatch, MatchesReferenceForEveryRemainder) {
  for (int count : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 201, 402}) {
    const Model m = randomNet({count}, 17u + unsigned(count));
    ASSERT_EQ(m.cables.count, count);
    for (const ElementDamping& d : {kNone, kViscous})
      expectAgree(m, d, "count " + std::to_string(count) + (d.enabled() ? ", viscous" : ""));
  }
}

// The random displacements leave both slack and taut cables (so the max with zero takes both sides).
TEST(CableBatch, RandomNetHasSlackAndTautCables) {
  const Model m = randomNet({402}, 17u + 402u);
  std::vector<double> T;
  cableTensions(m.cables, m.nodes.x.data(), T);
  const long slack = std::count(T.begin(), T.end(), 0.0);
  EXPECT_GE(slack, 100);
  EXPECT_GE(long(T.size()) - slack, 100);
}

// Several material blocks, each with a remainder (7, 10 and 5 cables: the batches must restart at each
// block's first cable and use its EA).
TEST(CableBatch, MatchesReferenceOverSeveralBlocks) {
  const Model m = randomNet({7, 10, 5}, 5u);
  ASSERT_EQ(m.cables.blocks.size(), 3u);
  for (const ElementDamping& d : {kNone, kViscous}) expectAgree(m, d, d.enabled() ? "viscous" : "plain");
}

// Evaluated in ranges (a thread's share: any start, within and across blocks, whole batches or not), the
// forces, energy and step are those of the whole evaluation.
TEST(CableBatch, RangesAddUpToTheWhole) {
  const Model m = randomNet({37, 50, 29}, 9u);
  for (const ElementDamping& d : {kNone, kViscous}) {
    expectAgree(m, d, "ranges at batch boundaries", {0, 8, 36, 60, 116});
    expectAgree(m, d, "ranges anywhere", {0, 3, 38, 39, 87, 88, 115, 116});
    expectAgree(m, d, "with empty ranges", {0, 0, 50, 50, 116});
  }
}

// Slack cables (compressed by 0.1 % to 20 %) give exactly zero elastic force, taut ones (0.1 % to 5 %) their
// own tension, each cable checked against its own scale, in every lane position and the remainder.
TEST(CableBatch, SlackCablesGiveZeroForce) {
  const Model m = disjointCables(23, [](int e) { return (e % 3 == 0 ? -1.0 : 1.0) * 1e-3 * (1 + 2 * e); });
  const Result r = evaluate(m, kNone, CableKernel::Batched);
  int slack = 0;
  for (int e = 0; e < m.cables.count; ++e) {
    const int i = m.cables.conn[2 * e], j = m.cables.conn[2 * e + 1];
    double L = 0;
    for (int k = 0; k < 3; ++k) L += std::pow(m.nodes.x[3 * j + k] - m.nodes.x[3 * i + k], 2);
    const bool isSlack = std::sqrt(L) < m.cables.restLength[e];
    slack += isSlack;
    for (int k = 0; k < 3; ++k) {
      if (isSlack) {
        EXPECT_EQ(r.f[3 * i + k], 0.0) << "cable " << e;
        EXPECT_EQ(r.f[3 * j + k], 0.0) << "cable " << e;
      } else {
        EXPECT_EQ(r.f[3 * i + k], -r.f[3 * j + k]) << "cable " << e;
      }
    }
  }
  EXPECT_GE(slack, 7);
  expectEachCableAgrees(m, kNone, "slack and taut");
  expectEachCableAgrees(m, kViscous, "slack and taut, viscous");  // viscosity also acts on slack cables
}

// At and across the slack/taut boundary: strains from −1e-3 down to round-off size, exactly zero (the
// reference length), and up again, in every lane position; then one cable's end moved through the boundary
// in 41 steps: the force is zero up to the rest length, grows linearly after it, and both kernels follow the
// reference at every step.
TEST(CableBatch, CablesAtAndAcrossTheSlackTautBoundary) {
  const std::vector<double> strains{-1e-3, -1e-6, -1e-9, -1e-12, -1e-15, 0.0, 1e-15, 1e-12, 1e-9, 1e-6, 1e-3};
  const Model m = disjointCables(int(strains.size()), [&](int e) { return strains[std::size_t(e)]; });
  expectEachCableAgrees(m, kNone, "boundary");
  expectEachCableAgrees(m, kViscous, "boundary, viscous");
  const Result r = evaluate(m, kNone, CableKernel::Batched);
  for (int e = 0; e < m.cables.count; ++e) {
    const int i = m.cables.conn[2 * e], j = m.cables.conn[2 * e + 1];
    double L = 0;
    for (int k = 0; k < 3; ++k) L += std::pow(m.nodes.x[3 * j + k] - m.nodes.x[3 * i + k], 2);
    if (!(std::sqrt(L) > m.cables.restLength[e])) {
      for (int k = 0; k < 3; ++k) EXPECT_EQ(r.f[3 * j + k], 0.0) << "cable " << e;
    }
  }

  // 9 cables (two batches of 4 and a remainder with AVX); cable 5 is moved through its rest length.
  Model sweep = disjointCables(9, [](int e) { return 2e-3 * (e % 2 ? 1 : -1); });
  const int moved = 5;
  const int i = sweep.cables.conn[2 * moved], j = sweep.cables.conn[2 * moved + 1];
  const double ea = sweep.cables.blocks[0].axialStiffness;
  for (int step = -20; step <= 20; ++step) {
    const double s = 1.0 + 1e-4 * step;
    for (int k = 0; k < 3; ++k)
      sweep.nodes.x[3 * j + k] =
          sweep.nodes.X[3 * i + k] + s * (sweep.nodes.X[3 * j + k] - sweep.nodes.X[3 * i + k]);
    const std::string what = "sweep step " + std::to_string(step);
    expectEachCableAgrees(sweep, kNone, what);
    const Result b = evaluate(sweep, kNone, CableKernel::Batched);
    const double f = std::sqrt(b.f[3 * j] * b.f[3 * j] + b.f[3 * j + 1] * b.f[3 * j + 1] +
                               b.f[3 * j + 2] * b.f[3 * j + 2]);
    if (step <= 0) {
      EXPECT_EQ(f, 0.0) << what;
    } else {
      EXPECT_NEAR(f, ea * 1e-4 * step, 1e-9 * ea * 1e-4 * step) << what;  // EA ε, ε = 1e-4 step
    }
  }
}

// The comparison can fail: one cable's rest length changed by 1e-9 in the reference (in any lane position
// or the remainder) is far above the tolerance in the forces and the energy.
TEST(CableBatch, ComparisonDetectsOneMishandledLane) {
  const Model m = disjointCables(11, [](int e) { return 1e-3 * (1 + e); });
  const Result bat = evaluate(m, kNone, CableKernel::Batched);
  for (int e = 0; e < m.cables.count; ++e) {
    Model changed = m;
    changed.cables.restLength[e] *= 1.0 + 1e-9;
    const Result ref = reference(changed, kNone);
    EXPECT_GT(forceError(bat, ref), 1e2 * kTol) << "cable " << e;
    EXPECT_GT(std::abs(bat.energy - ref.energy), 1e2 * kTol * ref.energy) << "cable " << e;
  }
}

// The cables' connectivity: 2 nodes each, scattered, so that below kMinParallelItems cables the assembler
// does not split them for threads (they run whole on the first one); the batched kernel's ranges start on
// whole batches (tests/unit/test_threads.cpp: a net above it).
TEST(CableBatch, SmallNetDoesNotSplit) {
  const Model small = randomNet({40}, 3u);
  const CableForces batched(small.cables, kNone);
  const Connectivity c = batched.connectivity();
  EXPECT_EQ(c.items, small.cables.count);
  EXPECT_EQ(c.nodesPerItem, 2);
  EXPECT_EQ(c.nodes, small.cables.conn.data());
  EXPECT_TRUE(c.scattered);
  EXPECT_EQ(c.batch % 2, 0);
  EXPECT_EQ(CableForces(small.cables, kNone, CableKernel::PerElement).connectivity().batch, 1);
  EXPECT_EQ(ThreadedForces({&batched}, 2, small.nodes.count).splitElements(), 0);
}
