// The batched membrane kernel (MembraneBatch.hpp, 4 lanes with AVX, 2 without) against the per-element kernel
// it replaces, on randomised meshes with taut, wrinkled and slack triangles: forces, strain energy and stable
// step must agree to round-off for every element count (whole batches and remainders) and block layout.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "ForceDifference.hpp"
#include "MembraneEvaluation.hpp"
#include "structure/elements/BuildModel.hpp"
#include "structure/elements/MembraneForces.hpp"
#include "structure/material/WrinklingMembrane.hpp"
#include "structure/model/Model.hpp"

using namespace fsi::structure;

namespace {

// `count` triangles of a jittered grid (3D reference), randomly displaced so that their principal strains
// scatter around zero by about ±2 %: some stretched both ways (taut), some one way (wrinkled), some neither
// (slack). Random velocities for the viscous stresses.
MeshInput randomSheet(int count, unsigned seed, int material, double xOffset) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> jitter(-0.15, 0.15);
  const int cols = 6, rows = (count + 2 * cols - 1) / (2 * cols) + 1;
  MeshInput in;
  in.mesh.name = "sheet" + std::to_string(material);
  for (int j = 0; j <= rows; ++j)
    for (int i = 0; i <= cols; ++i) {
      in.mesh.points.push_back({xOffset + i + jitter(rng), j + jitter(rng), 0.3 * jitter(rng)});
      in.mesh.pointTags.push_back(long(in.mesh.points.size()));
    }
  auto node = [&](int i, int j) { return j * (cols + 1) + i; };
  for (int j = 0; j < rows && int(in.mesh.triangles.size()) < count; ++j)
    for (int i = 0; i < cols && int(in.mesh.triangles.size()) < count; ++i) {
      in.mesh.triangles.push_back({node(i, j), node(i + 1, j), node(i + 1, j + 1)});
      if (int(in.mesh.triangles.size()) < count)
        in.mesh.triangles.push_back({node(i, j), node(i + 1, j + 1), node(i, j + 1)});
    }
  // Keep only the grid points the triangles use (a node without an element has no mass).
  std::vector<int> used(in.mesh.points.size(), -1);
  MeshData kept;
  kept.name = in.mesh.name;
  for (auto& t : in.mesh.triangles)
    for (int& k : t) {
      if (used[k] < 0) {
        used[k] = int(kept.points.size());
        kept.points.push_back(in.mesh.points[k]);
        kept.pointTags.push_back(long(kept.points.size()));
      }
      k = used[k];
    }
  kept.triangles = in.mesh.triangles;
  in.mesh = kept;
  in.membraneMaterial = material;
  return in;
}

Model randomModel(const std::vector<int>& counts, const std::vector<bool>& wrinkling, unsigned seed) {
  std::vector<MeshInput> meshes;
  std::vector<MembraneMaterial> materials;
  for (std::size_t b = 0; b < counts.size(); ++b) {
    meshes.push_back(randomSheet(counts[b], seed + unsigned(b), int(b), 20.0 * double(b)));
    // Different constants per block, so a lane reading another block's material would show.
    materials.push_back({"m" + std::to_string(b), 1.0e9 * (1.0 + double(b)), 0.3 + 0.05 * double(b), 1e-3,
                         1000, wrinkling[b]});
  }
  Model m = buildModel(meshes, materials, {});
  std::mt19937 rng(seed * 7 + 1);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  for (int i = 0; i < m.nodes.count; ++i)
    for (int k = 0; k < 3; ++k) {
      m.nodes.x[3 * i + k] = m.nodes.X[3 * i + k] * 1.005 + 0.02 * u(rng);
      m.nodes.v[3 * i + k] = 3.0 * u(rng);
    }
  return m;
}

using Result = test::MembraneEvaluation;

Result evaluate(const Model& m, const ElementDamping& damping, MembraneKernel kernel, double dtStart) {
  return test::evaluateMembranes(m, MembraneForces(m.membranes, damping, kernel), 1, dtStart);
}

// Largest force difference relative to the largest reference force (the nodal sums of neighbouring
// triangles are added in another order, so a node's own small resultant is no scale).
double forceError(const Result& a, const Result& ref) {
  return test::largestRelativeDifference(a.f, ref.f);
}

constexpr double kTol = 1e-12;

void expectAgree(const Model& m, const ElementDamping& damping, double dtStart, const std::string& what) {
  const Result ref = evaluate(m, damping, MembraneKernel::PerElement, dtStart);
  const Result bat = evaluate(m, damping, MembraneKernel::Batched, dtStart);
  EXPECT_LE(forceError(bat, ref), kTol) << what;
  EXPECT_LE(std::abs(bat.energy - ref.energy), kTol * ref.energy) << what;
  EXPECT_LE(std::abs(bat.dt - ref.dt), kTol * ref.dt) << what;
  EXPECT_TRUE(std::isfinite(ref.dt)) << what;
}

std::array<int, 3> stateCounts(const Model& m) {
  MembraneStressField s;
  membraneStresses(m.membranes, m.nodes.x.data(), s);
  std::array<int, 3> n{0, 0, 0};
  for (double st : s.state) ++n[int(st)];
  return n;
}

const ElementDamping kNone{}, kViscous{2.0e-6, 0.06};

}  // namespace

// Every element count from 1 to 13 (no whole batch, whole batches, every remainder) and two larger ones, with
// and without wrinkling and viscosity, from an infinite and from a finite starting step.
TEST(MembraneBatch, MatchesPerElementKernelForEveryRemainder) {
  for (int count : {1, 2, 3, 4, 5, 6, 7, 8, 9, 10, 11, 12, 13, 201, 402})
    for (bool wrinkling : {true, false}) {
      const Model m = randomModel({count}, {wrinkling}, 11u + unsigned(count));
      for (const ElementDamping& d : {kNone, kViscous})
        for (double dtStart : {std::numeric_limits<double>::infinity(), 1.0})
          expectAgree(m, d, dtStart,
                      "count " + std::to_string(count) + (wrinkling ? " wrinkling" : " elastic") +
                          (d.enabled() ? " viscous" : "") + " dt0 " + std::to_string(dtStart));
    }
}

// The random displacements give all three states of the law (so every blend is exercised).
TEST(MembraneBatch, RandomMeshHasTautWrinkledAndSlackTriangles) {
  const auto n = stateCounts(randomModel({402}, {true}, 11u + 402u));
  EXPECT_GE(n[int(WrinkleState::Taut)], 20);
  EXPECT_GE(n[int(WrinkleState::Wrinkled)], 20);
  EXPECT_GE(n[int(WrinkleState::Slack)], 20);
}

// Several material blocks, each with a remainder (7, 10 and 5 triangles: the batches must restart at each
// block's first element and use its constants).
TEST(MembraneBatch, MatchesPerElementKernelOverSeveralBlocks) {
  const Model m = randomModel({7, 10, 5}, {true, false, true}, 5u);
  ASSERT_EQ(m.membranes.blocks.size(), 3u);
  for (const ElementDamping& d : {kNone, kViscous}) expectAgree(m, d, 1.0, d.enabled() ? "viscous" : "plain");
}

// The comparison can fail: one triangle's contribution changed by 1e-6 (its t·A0, in any lane position or
// the remainder) is far above the tolerance, in the forces (every loaded triangle) and in the energy.
TEST(MembraneBatch, ComparisonDetectsOneMishandledLane) {
  const Model m = randomModel({13}, {true}, 11u + 13u);
  MembraneStressField s;
  membraneStresses(m.membranes, m.nodes.x.data(), s);
  const Result bat = evaluate(m, kNone, MembraneKernel::Batched, 1.0);
  int checked = 0;
  for (int e = 0; e < m.membranes.count; ++e) {
    if (s.state[e] == double(int(WrinkleState::Slack))) continue;  // no force to change
    Model changed = m;
    changed.membranes.geo[MembraneTriangles::kGeo * e + 3] *= 1.0 + 1e-6;
    const Result ref = evaluate(changed, kNone, MembraneKernel::PerElement, 1.0);
    EXPECT_GT(forceError(bat, ref), 1e3 * kTol) << "element " << e;
    EXPECT_GT(std::abs(bat.energy - ref.energy), 1e3 * kTol * ref.energy) << "element " << e;
    ++checked;
  }
  EXPECT_GE(checked, 6);
}
