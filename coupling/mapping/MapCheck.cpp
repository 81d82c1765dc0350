#include "coupling/mapping/MapCheck.hpp"

#include <fmt/format.h>
#include <fmt/ranges.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <functional>
#include <limits>
#include <random>
#include <utility>
#include <vector>

#include "coupling/interface/SurfaceSearch.hpp"
#include "structure/model/Error.hpp"

namespace fsi::coupling {

namespace {

using Vec3 = std::array<double, 3>;
using Clock = std::chrono::steady_clock;
constexpr double kPi = 3.14159265358979323846;

// The test fields, in coordinates centred on and scaled by the bounding box of both meshes so that their
// size does not depend on the units or the position of the meshes.
struct TestFields {
  Vec3 centre{};
  double scale = 1.0;
  Vec3 local(const Vec3& x) const {
    return {(x[0] - centre[0]) / scale, (x[1] - centre[1]) / scale, (x[2] - centre[2]) / scale};
  }
  double linear(const Vec3& x) const {
    const Vec3 y = local(x);
    return 0.8 * y[0] - 0.5 * y[1] + 0.33 * y[2];
  }
  double quadratic(const Vec3& x) const {
    const Vec3 y = local(x);
    return y[0] * y[0] + 0.5 * y[0] * y[1] - y[1] * y[2] + 0.7 * y[1] * y[1] - 0.4 * y[2] * y[2] + linear(x);
  }
  // Plane waves (in the scaled coordinates) of random direction and phase: 3 of wavelength 1/3 (the
  // interface's size) and 3 of 8 coarse edges (its mesh's scale).
  std::array<Vec3, 6> k{};
  std::array<double, 6> phase{};
  double wave(const Vec3& x) const {
    const Vec3 y = local(x);
    double s = 0.0;
    for (std::size_t m = 0; m < k.size(); ++m)
      s += std::sin(k[m][0] * y[0] + k[m][1] * y[1] + k[m][2] * y[2] + phase[m]);
    return s / double(k.size());
  }
};

TestFields makeFields(const InterfaceMesh& a, const InterfaceMesh& b) {
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const InterfaceMesh* m : {&a, &b})
    for (const Vec3& p : m->points)
      for (std::size_t k = 0; k < 3; ++k) {
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
  TestFields f;
  double extent = 0.0;
  for (std::size_t k = 0; k < 3; ++k) {
    f.centre[k] = 0.5 * (lo[k] + hi[k]);
    extent = std::max(extent, hi[k] - lo[k]);
  }
  f.scale = extent > 0.0 ? extent : 1.0;
  const double coarse = std::max(a.meanEdgeLength(), b.meanEdgeLength()) / f.scale;
  std::mt19937 rng(3939);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> ph(0.0, 2.0 * kPi);
  for (std::size_t m = 0; m < f.k.size(); ++m) {
    const double lambda = m < 3 || !(coarse > 0.0) ? 1.0 / 3.0 : 8.0 * coarse;
    Vec3 d{g(rng), g(rng), g(rng)};
    const double n = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
    for (std::size_t c = 0; c < 3; ++c) f.k[m][c] = 2.0 * kPi / lambda * d[c] / n;
    f.phase[m] = ph(rng);
  }
  return f;
}

// Nodal error of `map` (source values → target values) for field f, over the target nodes h mapped.
FieldError fieldError(const L2Projection& h, const InterfaceMesh& src, const InterfaceMesh& dst,
                      const std::function<double(const Vec3&)>& f,
                      const std::function<void(const double*, double*)>& map) {
  std::vector<double> us, ut(std::size_t(dst.numPoints()));
  us.reserve(std::size_t(src.numPoints()));
  for (const Vec3& p : src.points) us.push_back(f(p));
  map(us.data(), ut.data());
  double lo = HUGE_VAL, hi = -HUGE_VAL, maxErr = 0.0, sum2 = 0.0;
  long n = 0;
  for (int i = 0; i < dst.numPoints(); ++i) {
    if (!h.targetNodeMapped()[std::size_t(i)]) continue;
    const double exact = f(dst.points[std::size_t(i)]);
    const double e = std::abs(ut[std::size_t(i)] - exact);
    lo = std::min(lo, exact);
    hi = std::max(hi, exact);
    maxErr = std::max(maxErr, e);
    sum2 += e * e;
    ++n;
  }
  if (n == 0) return {};
  const double range = hi > lo ? hi - lo : 1.0;
  return {maxErr / range, std::sqrt(sum2 / double(n)) / range};
}

void balance(const InterfaceMesh& m, const std::vector<double>& f, const Vec3& origin, Vec3& force,
             Vec3& moment, double& forceScale, double& momentScale) {
  force = moment = Vec3{0.0, 0.0, 0.0};
  forceScale = momentScale = 0.0;
  for (int i = 0; i < m.numPoints(); ++i) {
    const Vec3& x = m.points[std::size_t(i)];
    const Vec3 r{x[0] - origin[0], x[1] - origin[1], x[2] - origin[2]};
    const double* fi = &f[3 * std::size_t(i)];
    for (std::size_t k = 0; k < 3; ++k) force[k] += fi[k];
    moment[0] += r[1] * fi[2] - r[2] * fi[1];
    moment[1] += r[2] * fi[0] - r[0] * fi[2];
    moment[2] += r[0] * fi[1] - r[1] * fi[0];
    const double fn = std::sqrt(fi[0] * fi[0] + fi[1] * fi[1] + fi[2] * fi[2]);
    forceScale += fn;
    momentScale += fn * std::sqrt(r[0] * r[0] + r[1] * r[1] + r[2] * r[2]);
  }
}

template <class Fn>
double meanSeconds(int repeats, Fn&& fn) {
  const auto t0 = Clock::now();
  for (int r = 0; r < repeats; ++r) fn();
  return std::chrono::duration<double>(Clock::now() - t0).count() / std::max(1, repeats);
}

DirectionCheck check(const InterfaceMesh& src, const InterfaceMesh& dst, const TestFields& fields,
                     const ProjectionOptions& po, const MapCheckOptions& options) {
  const L2Projection h(src, dst, po);
  DirectionCheck d;
  d.report = h.report();
  d.mass = h.mass();
  const auto linear = [&](const Vec3& x) { return fields.linear(x); };
  const auto quadratic = [&](const Vec3& x) { return fields.quadratic(x); };
  const auto wave = [&](const Vec3& x) { return fields.wave(x); };
  const auto project = [&](const double* us, double* ut) { h.apply(us, ut); };
  d.linear = fieldError(h, src, dst, linear, project);
  d.quadratic = fieldError(h, src, dst, quadratic, project);
  d.wave = fieldError(h, src, dst, wave, project);
  // Nearest-point interpolation, from the same search as the projection's.
  const SurfaceSearch search(src);
  std::vector<int> tri;
  std::vector<std::array<double, 3>> bary;
  int hint = -1;
  for (const Vec3& x : dst.points) {
    const SurfacePoint p = search.closest(x, hint);
    hint = p.triangle;
    tri.push_back(p.triangle);
    bary.push_back(p.bary);
  }
  const auto nearest = [&](const double* us, double* ut) {
    for (std::size_t i = 0; i < tri.size(); ++i) ut[i] = search.fan().interpolate(tri[i], bary[i], us);
  };
  d.linearNearest = fieldError(h, src, dst, linear, nearest);
  d.quadraticNearest = fieldError(h, src, dst, quadratic, nearest);
  d.waveNearest = fieldError(h, src, dst, wave, nearest);

  // Smoothness: the nodal share of a unit pressure on the target, carried back by Hᵀ, against the source's
  // own shares ∫φ_j (a third of each fan triangle's area per corner, a centre's split over its face).
  {
    const FanTriangulation& sf = search.fan();
    std::vector<double> share(std::size_t(src.numPoints()), 0.0);
    for (int t = 0; t < sf.numTriangles(); ++t)
      for (std::size_t k = 0; k < 3; ++k) {
        std::array<double, 3> corner{0.0, 0.0, 0.0};
        corner[k] = 1.0;
        sf.forEachWeight(t, corner, [&](int j, double w) { share[std::size_t(j)] += w * sf.area(t) / 3.0; });
      }
    std::vector<double> pt(h.lumpedMass().data(), h.lumpedMass().data() + dst.numPoints()),
        ps(std::size_t(src.numPoints()));
    h.applyTranspose(pt.data(), ps.data());
    double sum2 = 0.0;
    long n = 0;
    for (std::size_t j = 0; j < ps.size(); ++j) {
      if (!(share[j] > 0.0)) continue;  // a node of no face
      const double e = ps[j] / share[j] - 1.0;
      sum2 += e * e;
      d.pressureMax = std::max(d.pressureMax, std::abs(e));
      if (std::abs(ps[j]) < 1e-9 * share[j]) ++d.zeroForceNodes;
      ++n;
    }
    d.pressureRms = n > 0 ? std::sqrt(sum2 / double(n)) : 0.0;
  }

  // A random force field with a non-zero resultant, so the relative force error is meaningful.
  std::mt19937 rng(options.seed);
  std::uniform_real_distribution<double> u(-1.0, 1.0);
  std::vector<double> ft(3 * std::size_t(dst.numPoints())), fs(3 * std::size_t(src.numPoints()));
  for (std::size_t i = 0; i < ft.size(); ++i) ft[i] = u(rng) + (i % 3 == 2 ? 0.5 : 0.1);
  h.applyTranspose(ft.data(), fs.data(), 3);
  Vec3 origin{0.0, 0.0, 0.0};
  for (const Vec3& p : dst.points)
    for (std::size_t k = 0; k < 3; ++k) origin[k] += p[k] / dst.numPoints();
  Vec3 forceT, momentT, forceS, momentS;
  double forceScale, momentScale, unusedF, unusedM;
  balance(dst, ft, origin, forceT, momentT, forceScale, momentScale);
  balance(src, fs, origin, forceS, momentS, unusedF, unusedM);
  for (std::size_t k = 0; k < 3; ++k) {
    d.forceError = std::max(d.forceError, std::abs(forceS[k] - forceT[k]) / forceScale);
    d.momentError = std::max(d.momentError, std::abs(momentS[k] - momentT[k]) / momentScale);
  }

  std::vector<double> us(3 * std::size_t(src.numPoints()), 1.0), ut(3 * std::size_t(dst.numPoints()));
  d.applySecondsScalar = meanSeconds(options.applyRepeats, [&] { h.apply(us.data(), ut.data(), 1); });
  d.applySecondsVector = meanSeconds(options.applyRepeats, [&] { h.apply(us.data(), ut.data(), 3); });
  d.applyTransposeSecondsVector =
      meanSeconds(options.applyRepeats, [&] { h.applyTranspose(ft.data(), fs.data(), 3); });
  return d;
}

nlohmann::json reportJson(const ProjectionReport& r) {
  nlohmann::json points = nlohmann::json::array();
  for (const UnmappedPoint& p : r.firstUnmappedPoints)
    points.push_back({{"id", p.id}, {"x", p.x}, {"distance", p.distance}});
  return {{"source", r.source},
          {"target", r.target},
          {"source_nodes", r.sourceNodes},
          {"target_nodes", r.targetNodes},
          {"target_triangles", r.targetTriangles},
          {"quadrature_level", r.quadratureLevel},
          {"gap_correction", r.gapCorrection},
          {"defect_correction", r.defectCorrection},
          {"quadrature_points", r.quadraturePoints},
          {"unmapped_quadrature_points", r.unmappedQuadraturePoints},
          {"first_unmapped_quadrature_points", points},
          {"unmapped_target_nodes", r.unmappedTargetNodes},
          {"first_unmapped_target_nodes", r.firstUnmappedNodes},
          {"max_gap", r.maxGap},
          {"facing_share", r.facingShare},
          {"one_sided", r.oneSided},
          {"points_moved_to_own_side", r.residedPoints},
          {"max_gap_of_moved_points", r.maxResidedGap},
          {"points_facing_the_other_way_left", r.turnedPoints},
          {"setup_seconds", r.setupSeconds},
          {"search_seconds", r.searchSeconds},
          {"assembly_seconds", r.assemblySeconds},
          {"factor_seconds", r.factorSeconds}};
}

// Coordinates near the limits of double (1e308) pass the readers but overflow the extents, squared distances
// and areas the check computes: refuse them, and never report a check as passed beside a NaN.
void checkCoordinates(const InterfaceMesh& a, const InterfaceMesh& b) {
  // Squared areas are fourth powers of lengths: they must stay finite.
  const double limit = std::sqrt(std::sqrt(std::numeric_limits<double>::max()));
  Vec3 lo{HUGE_VAL, HUGE_VAL, HUGE_VAL}, hi{-HUGE_VAL, -HUGE_VAL, -HUGE_VAL};
  for (const InterfaceMesh* m : {&a, &b})
    for (std::size_t i = 0; i < m->points.size(); ++i) {
      const Vec3& p = m->points[i];
      for (std::size_t k = 0; k < 3; ++k) {
        if (!std::isfinite(p[k]))
          throw InputError(
              fmt::format("{}: point {} ({}, {}, {}) is not finite", m->name, i, p[0], p[1], p[2]));
        lo[k] = std::min(lo[k], p[k]);
        hi[k] = std::max(hi[k], p[k]);
      }
    }
  for (std::size_t k = 0; k < 3; ++k)
    if (lo[k] <= hi[k] && std::max(std::abs(lo[k]), std::abs(hi[k])) > limit)  // lo > hi: no points
      throw InputError(
          fmt::format("{} and {}: coordinate {} spans [{:.6g}, {:.6g}]: beyond {:.3g}, squared "
                      "areas overflow; rescale the meshes",
                      a.name, b.name, "xyz"[k], lo[k], hi[k], limit));
}

void checkFinite(const MapCheckResult& r) {
  for (const DirectionCheck& d : r.directions) {
    const std::pair<const char*, double> values[] = {{"largest gap", d.report.maxGap},
                                                     {"linear field max error", d.linear.max},
                                                     {"linear field rms error", d.linear.rms},
                                                     {"quadratic field max error", d.quadratic.max},
                                                     {"quadratic field rms error", d.quadratic.rms},
                                                     {"force error", d.forceError},
                                                     {"pressure transfer deviation", d.pressureRms},
                                                     {"moment error", d.momentError}};
    for (const auto& [what, value] : values)
      if (!std::isfinite(value))
        throw InputError(fmt::format("map-check {} -> {}: the {} is {} (degenerate or extreme coordinates)",
                                     d.report.source, d.report.target, what, value));
  }
}

// Warnings, each with the setting that would help (issue 39): surfaces far apart against the finer mesh's
// edges (the chord gap), the consistent transfer behind nearest-point interpolation on a field of the
// interface's own length scales, source nodes the conservative transfer leaves without force.
std::vector<std::string> advise(const MapCheckResult& r, const InterfaceMesh& a, const InterfaceMesh& b) {
  std::vector<std::string> out;
  const double finer = std::min(a.meanEdgeLength(), b.meanEdgeLength());
  double gap = 0.0;
  for (const DirectionCheck& d : r.directions) gap = std::max(gap, d.report.maxGap);
  if (gap > kAdviseGapShare * finer)
    out.push_back(fmt::format(
        "the surfaces are up to {:.3g} apart ({:.0f} % of the finer mesh's mean edge {:.3g}; chord gaps "
        "{:.3g} / {:.3g}, tolerance {:.3g}): a field varying across the surface differs by the gap times its "
        "normal derivative, and H^T's moment is off by as much: keep conserveMoment yes; refining the "
        "coarser mesh shrinks the gap as h^2",
        gap, 100.0 * gap / finer, finer, chordGap(a), chordGap(b), r.tolerance));
  for (const DirectionCheck& d : r.directions) {
    const std::string dir = fmt::format("{} -> {}", d.report.source, d.report.target);
    const double rmax = d.wave.max / std::max(d.waveNearest.max, 1e-300);
    const double rrms = d.wave.rms / std::max(d.waveNearest.rms, 1e-300);
    if (rmax > kAdviseBehindNearest || rrms > kAdviseBehindNearest)
      out.push_back(fmt::format(
          "{}: on a field of the interface's own length scales the consistent transfer's error is {:.2f}x "
          "(max) / {:.2f}x (RMS) nearest-point interpolation's: use evaluation pointwise (fsiCoupling "
          "`evaluation pointwise;`, map-check --evaluation pointwise)",
          dir, rmax, rrms));
    if (d.zeroForceNodes > 0) {
      // Explicit level: auto (about half a source edge per sub-triangle); auto already: twice as fine.
      const bool automatic = r.projection.quadratureLevel == kAutoQuadrature;
      const std::string advised = automatic ? std::to_string(2 * d.report.quadratureLevel) : "auto";
      out.push_back(fmt::format(
          "{}: H^T leaves {} of {} source nodes without force (quadrature level {} samples the source too "
          "sparsely): use quadratureLevel {} (fsiCoupling; map-check --quadrature-level {})",
          dir, d.zeroForceNodes, d.report.sourceNodes, d.report.quadratureLevel, advised, advised));
    }
  }
  return out;
}

}  // namespace

MapCheckResult runMapCheck(const InterfaceMesh& a, const InterfaceMesh& b, const MapCheckOptions& options) {
  checkCoordinates(a, b);
  MapCheckResult r;
  r.meshA = a.name;
  r.meshB = b.name;
  r.mass = options.projection.mass;
  r.tolerance = options.tolerance >= 0.0 ? options.tolerance : mappingTolerance(a, b);
  const TestFields fields = makeFields(a, b);
  ProjectionOptions po = options.projection;
  po.tolerance = r.tolerance;
  r.projection = po;
  r.directions[0] = check(a, b, fields, po, options);
  r.directions[1] = check(b, a, fields, po, options);
  checkFinite(r);
  r.advice = advise(r, a, b);
  return r;
}

nlohmann::json MapCheckResult::toJson() const {
  nlohmann::json dirs = nlohmann::json::array();
  for (const DirectionCheck& d : directions) {
    nlohmann::json j = reportJson(d.report);
    j["variant"] = toString(d.mass);
    j["linear_error"] = {{"max", d.linear.max}, {"rms", d.linear.rms}};
    j["quadratic_error"] = {{"max", d.quadratic.max}, {"rms", d.quadratic.rms}};
    j["linear_error_nearest_point"] = {{"max", d.linearNearest.max}, {"rms", d.linearNearest.rms}};
    j["quadratic_error_nearest_point"] = {{"max", d.quadraticNearest.max}, {"rms", d.quadraticNearest.rms}};
    j["wave_error"] = {{"max", d.wave.max}, {"rms", d.wave.rms}};
    j["wave_error_nearest_point"] = {{"max", d.waveNearest.max}, {"rms", d.waveNearest.rms}};
    j["evaluation"] = d.report.pointwise ? "pointwise" : "l2";
    j["uniform_pressure_transfer"] = {{"rms_deviation", d.pressureRms},
                                      {"max_deviation", d.pressureMax},
                                      {"zero_force_nodes", d.zeroForceNodes}};
    j["conservative_force_error"] = d.forceError;
    j["conservative_moment_error"] = d.momentError;
    j["apply_seconds_scalar"] = d.applySecondsScalar;
    j["apply_seconds_vector"] = d.applySecondsVector;
    j["apply_transpose_seconds_vector"] = d.applyTransposeSecondsVector;
    dirs.push_back(j);
  }
  return {{"mesh_a", meshA},
          {"mesh_b", meshB},
          {"tolerance", tolerance},
          {"variant", toString(mass)},
          {"settings", describe(projection)},
          {"differs_from_run_defaults", differencesFromRunDefaults(projection)},
          {"advice", advice},
          {"errors_relative_to", "range of the exact field over the mapped target nodes"},
          {"directions", dirs},
          {"all_mapped", allMapped()}};
}

namespace {
// The summary's end: the warnings, then whether every point mapped (and the first that did not).
std::string closingLines(const MapCheckResult& result) {
  std::string s;
  for (const std::string& a : result.advice) s += "warning: " + a + "\n";
  if (result.allMapped()) {
    s += "all points mapped\n";
    return s;
  }
  for (const DirectionCheck& d : result.directions) {
    const ProjectionReport& r = d.report;
    if (r.allMapped()) continue;
    s += fmt::format(
        "{} -> {}: {} target quadrature points were not mapped (farther than {:.4g} from the source); "
        "{} target nodes affected",
        r.source, r.target, r.unmappedQuadraturePoints, result.tolerance, r.unmappedTargetNodes);
    if (!r.firstUnmappedNodes.empty()) s += fmt::format(", first: {}", fmt::join(r.firstUnmappedNodes, " "));
    s += "\n";
    for (const UnmappedPoint& p : r.firstUnmappedPoints)
      s += fmt::format("    point ({:.6g}, {:.6g}, {:.6g}) at distance {:.4g}\n", p.x[0], p.x[1], p.x[2],
                       p.distance);
  }
  return s;
}
}  // namespace

std::string MapCheckResult::settingsLines() const {
  const std::vector<std::string> differ = differencesFromRunDefaults(projection);
  return fmt::format("settings: {}\n          {}\n\n", describe(projection),
                     differ.empty()
                         ? std::string("(the coupled run's defaults, coupledRunProjection())")
                         : fmt::format("(not the coupled run's defaults: {})", fmt::join(differ, ", ")));
}

std::string MapCheckResult::summary() const {
  const DirectionCheck& ab = directions[0];
  const DirectionCheck& ba = directions[1];
  std::string s = fmt::format("map-check  A = {} ({} nodes)\n           B = {} ({} nodes)\n", meshA,
                              ab.report.sourceNodes, meshB, ab.report.targetNodes);
  s += settingsLines();
  auto row = [&](const std::string& label, const std::string& x, const std::string& y) {
    s += fmt::format("  {:<44} {:>22} {:>22}\n", label, x, y);
  };
  auto both = [&](const std::string& label, auto get, const char* format) {
    row(label, fmt::format(fmt::runtime(format), get(ab)), fmt::format(fmt::runtime(format), get(ba)));
  };
  row("", "A -> B", "B -> A");
  both(
      "projection variant", [](const DirectionCheck& d) { return toString(d.mass); }, "{}");
  both(
      "quadrature level (target triangle split L x L)",
      [](const DirectionCheck& d) { return d.report.quadratureLevel; }, "{}");
  both(
      "gap / defect correction",
      [](const DirectionCheck& d) {
        return fmt::format("{} / {}", d.report.gapCorrection ? "yes" : "no",
                           d.report.defectCorrection ? "yes" : "no");
      },
      "{}");
  both(
      "target quadrature points", [](const DirectionCheck& d) { return d.report.quadraturePoints; }, "{}");
  both(
      "  not mapped", [](const DirectionCheck& d) { return d.report.unmappedQuadraturePoints; }, "{}");
  both(
      "target nodes not (fully) mapped", [](const DirectionCheck& d) { return d.report.unmappedTargetNodes; },
      "{}");
  both(
      "largest gap between the surfaces", [](const DirectionCheck& d) { return d.report.maxGap; }, "{:.3g}");
  both(
      "area facing one way (one-sided: keep sides)",
      [](const DirectionCheck& d) {
        return fmt::format("{:.4f} ({})", d.report.facingShare, d.report.oneSided ? "yes" : "no");
      },
      "{}");
  both(
      "  moved to their own side (gap) / left",
      [](const DirectionCheck& d) {
        return fmt::format("{} ({:.3g}) / {}", d.report.residedPoints, d.report.maxResidedGap,
                           d.report.turnedPoints);
      },
      "{}");
  both(
      "linear field, max error (rel. to range)", [](const DirectionCheck& d) { return d.linear.max; },
      "{:.3e}");
  both(
      "linear field, rms error", [](const DirectionCheck& d) { return d.linear.rms; }, "{:.3e}");
  both(
      "quadratic field, max error", [](const DirectionCheck& d) { return d.quadratic.max; }, "{:.3e}");
  both(
      "quadratic field, rms error", [](const DirectionCheck& d) { return d.quadratic.rms; }, "{:.3e}");
  both(
      "  nearest-point interpolation: linear, max",
      [](const DirectionCheck& d) { return d.linearNearest.max; }, "{:.3e}");
  both(
      "  nearest-point interpolation: quadratic, max",
      [](const DirectionCheck& d) { return d.quadraticNearest.max; }, "{:.3e}");
  both(
      "  nearest-point interpolation: quadratic, rms",
      [](const DirectionCheck& d) { return d.quadraticNearest.rms; }, "{:.3e}");
  both(
      "own-scale wave field, max / rms error",
      [](const DirectionCheck& d) { return fmt::format("{:.2e}/{:.2e}", d.wave.max, d.wave.rms); }, "{}");
  both(
      "  nearest-point interpolation: wave, max / rms",
      [](const DirectionCheck& d) {
        return fmt::format("{:.2e}/{:.2e}", d.waveNearest.max, d.waveNearest.rms);
      },
      "{}");
  both(
      "uniform pressure by H^T: rms deviation", [](const DirectionCheck& d) { return d.pressureRms; },
      "{:.3e}");
  both(
      "  max deviation", [](const DirectionCheck& d) { return d.pressureMax; }, "{:.3e}");
  both(
      "  source nodes with zero force", [](const DirectionCheck& d) { return d.zeroForceNodes; }, "{}");
  both(
      "conservative (H^T) force error", [](const DirectionCheck& d) { return d.forceError; }, "{:.3e}");
  both(
      "conservative (H^T) moment error", [](const DirectionCheck& d) { return d.momentError; }, "{:.3e}");
  both(
      "setup [s]", [](const DirectionCheck& d) { return d.report.setupSeconds; }, "{:.4f}");
  both(
      "  search / assembly / factorisation [s]",
      [](const DirectionCheck& d) {
        return fmt::format("{:.3f}/{:.3f}/{:.3f}", d.report.searchSeconds, d.report.assemblySeconds,
                           d.report.factorSeconds);
      },
      "{}");
  both(
      "apply, scalar field [ms]", [](const DirectionCheck& d) { return 1e3 * d.applySecondsScalar; },
      "{:.4f}");
  both(
      "apply, vector field [ms]", [](const DirectionCheck& d) { return 1e3 * d.applySecondsVector; },
      "{:.4f}");
  both(
      "transpose, vector field [ms]",
      [](const DirectionCheck& d) { return 1e3 * d.applyTransposeSecondsVector; }, "{:.4f}");
  s += "\n";
  return s + closingLines(*this);
}

}  // namespace fsi::coupling
