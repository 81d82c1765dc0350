#include "structure/parafoil/ParafoilGeometry.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

#include "structure/model/Error.hpp"
#include "structure/model/PositiveValue.hpp"

namespace fsi::structure::parafoil {

namespace {

constexpr double kPi = 3.14159265358979323846;
using P3 = std::array<double, 3>;

[[noreturn]] void invalid(const std::string& parameter, const std::string& what) {
  throw InputError(fmt::format("parafoil generator: parameter '{}' {}", parameter, what));
}

void requireRange(const std::string& p, double v, double lo, double hi, bool loOpen, bool hiOpen) {
  // An open bound at 0 means a positive quantity: under the one rule for those, not subnormal.
  const bool above = loOpen ? v > lo && (lo != 0 || isPositiveNormal(v)) : v >= lo;
  const bool ok = std::isfinite(v) && above && (hiOpen ? v < hi : v <= hi);
  if (!ok)
    invalid(p,
            fmt::format("is {}; valid: {}{:g}, {:g}{}", v, loOpen ? "(" : "[", lo, hi, hiOpen ? ")" : "]"));
}

void validate(const ParafoilParams& q) {
  const double inf = std::numeric_limits<double>::infinity();
  requireRange("span", q.span, 0, kMaxSpan, true, false);
  requireRange("root_chord", q.rootChord, 0, q.span, true, false);  // at most the span
  if (q.tipChord) requireRange("tip_chord", *q.tipChord, 0, q.span, true, false);
  if (q.cells < 1) invalid("cells", fmt::format("is {}; valid: at least 1", q.cells));
  requireRange("arc_radius", q.arcRadius, 0, inf, false, true);
  if (q.arcRadius > 0 && q.span / q.arcRadius > kPi)
    invalid("arc_radius", fmt::format("is {} m: the span {} m would bend through more than 180°; valid: at "
                                      "least span/π = {:.4g} m, or 0 for a flat span",
                                      q.arcRadius, q.span, q.span / kPi));
  requireRange("incidence", q.incidenceDeg, -45, 45, true, true);
  requireRange("twist", q.twistDeg, -45, 45, true, true);
  if (q.intakeOpen) {
    requireRange("intake.from", q.intakeFrom, 0, 1, false, true);
    requireRange("intake.to", q.intakeTo, 0, 1, true, true);
    if (!(q.intakeFrom < q.intakeTo))
      invalid("intake.to", fmt::format("is {}; it must lie behind intake.from = {} (both x/c on the lower "
                                       "surface, in [0, 1))",
                                       q.intakeTo, q.intakeFrom));
  }
  if (q.chordwisePoints < 4 || q.chordwisePoints > 10000)
    invalid("chordwise_points", fmt::format("is {}; valid: 4 to 10000", q.chordwisePoints));
  requireRange("bulge", q.bulge, 0, 0.5, false, false);
  if (q.spanDivisions < 1 || q.spanDivisions > 10000)
    invalid("span_divisions", fmt::format("is {}; valid: 1 to 10000", q.spanDivisions));
  // A value that cannot take effect is an error, as everywhere in the scene reader.
  if (q.bulge > 0 && q.spanDivisions < 2)
    invalid("bulge",
            fmt::format("is {} but has no effect with span_divisions 1 (no skin node lies between two "
                        "ribs); give span_divisions >= 2 or leave bulge out",
                        q.bulge));
  if (q.alternateRibs && q.cells % 2 != 0)
    invalid("ribs", fmt::format("'alternate' needs an even number of cells (lines on both tip ribs and "
                                "mirror-symmetric); cells is {}",
                                q.cells));
  for (std::size_t i = 0; i < q.rows.size(); ++i) {
    requireRange(fmt::format("rows[{}]", i), q.rows[i], 0, 1, true, true);
    if (i > 0 && !(q.rows[i] > q.rows[i - 1]))
      invalid(fmt::format("rows[{}]", i), fmt::format("is {}; rows must grow from the leading edge (x/c "
                                                      "increasing), the one before is {}",
                                                      q.rows[i], q.rows[i - 1]));
  }
  if (q.rows.size() > 26) invalid("rows", "has more than 26 rows (A to Z)");
  const std::vector<double> trims = q.rowTrim.value_or(std::vector<double>());
  if (q.rowTrim && trims.size() != q.rows.size())
    invalid("row_trim", fmt::format("has {} entries for {} rows; give one per row (A first) or leave it out",
                                    trims.size(), q.rows.size()));
  for (std::size_t i = 0; i < trims.size(); ++i)
    requireRange(fmt::format("row_trim[{}]", i), trims[i], -kMaxLineLength * q.span, kMaxLineLength * q.span,
                 false, false);
  if (q.cascade < 1) invalid("cascade", fmt::format("is {}; valid: at least 1 (1 = no cascade)", q.cascade));
  requireRange("cascade_fraction", q.cascadeFraction, 0, 1, true, true);
  requireRange("line_length", q.lineLength, 0, kMaxLineLength, true, false);  // in spans
  requireRange("rigging_angle", q.riggingDeg, -45, 45, true, true);
  if (q.lineElements < 1 || q.lineElements > 10000)
    invalid("line_elements", fmt::format("is {}; valid: 1 to 10000", q.lineElements));
  if (q.brakePoints < 0 || q.brakePoints > (q.cells + 1) / 2)
    invalid("brake_points", fmt::format("is {}; valid: 0 to {} (the ribs of one half-span)", q.brakePoints,
                                        (q.cells + 1) / 2));
  requireRange("toggle_fraction", q.toggleFraction, 0, 1, false, true);
  requireRange("brake_slack", q.brakeSlack, 0, q.span, false, true);
  if (q.brakeSlack > 0 && q.brakePoints == 0)
    invalid("brake_slack",
            fmt::format("is {} but has no effect with brake_points 0 (no brakes)", q.brakeSlack));
  if (q.riserLength) requireRange("riser_length", *q.riserLength, 0, kMaxLineLength * q.span, true, false);
  const double count = 2.0 * q.chordwisePoints * (double(q.cells) * q.spanDivisions + 1) * 2.0;
  if (count > 5e7)
    invalid("chordwise_points", fmt::format("with span_divisions and cells gives {:.3g} triangles, more than "
                                            "the limit 5e7",
                                            count));
}

// Chord parameters of the stations of both surfaces: cosine spacing (fine at the leading and trailing edges)
// or half-cosine (fine at the leading edge only), with the stations nearest to each attachment row and intake
// edge moved exactly onto it.
std::vector<double> chordStations(const ParafoilParams& q, std::vector<int>& rowStation, int& intakeFrom,
                                  int& intakeTo) {
  const int n = q.chordwisePoints;
  std::vector<double> xi(n);
  const bool half = q.chordSpacing == ParafoilParams::ChordSpacing::halfCosine;
  for (int i = 0; i < n; ++i)
    xi[i] = half ? 1.0 - std::cos(0.5 * kPi * i / (n - 1)) : 0.5 * (1.0 - std::cos(kPi * i / (n - 1)));
  std::vector<char> taken(n, 0);
  taken[0] = taken[n - 1] = 1;
  auto snap = [&](double xOverC, const std::string& what) {
    if (xOverC <= 0.0) return 0;  // the leading edge itself
    const double t = q.section.xOnSurface(xOverC, false);
    int best = -1;
    for (int i = 1; i < n - 1; ++i)
      if (!taken[i] && (best < 0 || std::abs(xi[i] - t) < std::abs(xi[best] - t))) best = i;
    if (best < 0)
      invalid("chordwise_points", fmt::format("is {}: too few to place {} on its own chordwise station; "
                                              "give more points",
                                              n, what));
    xi[best] = t;
    taken[best] = 1;
    return best;
  };
  rowStation.clear();
  for (std::size_t r = 0; r < q.rows.size(); ++r)
    rowStation.push_back(snap(q.rows[r], fmt::format("row {} (x/c = {})", char('A' + r), q.rows[r])));
  intakeFrom = intakeTo = -1;
  if (q.intakeOpen) {
    intakeFrom = snap(q.intakeFrom, "the intake's front edge");
    intakeTo = snap(q.intakeTo, "the intake's rear edge");
  }
  for (int i = 1; i < n; ++i)
    if (!(xi[i] > xi[i - 1]))
      invalid("chordwise_points", fmt::format("is {}: too few to keep the attachment rows and intake edges "
                                              "on separate stations; give more points",
                                              n));
  return xi;
}

P3 lerp(const P3& a, const P3& b, double t) {
  return {a[0] + t * (b[0] - a[0]), a[1] + t * (b[1] - a[1]), a[2] + t * (b[2] - a[2])};
}

double distance(const P3& a, const P3& b) {
  return std::sqrt((b[0] - a[0]) * (b[0] - a[0]) + (b[1] - a[1]) * (b[1] - a[1]) +
                   (b[2] - a[2]) * (b[2] - a[2]));
}

}  // namespace

MeshData buildParafoil(const ParafoilParams& q, const std::string& name) {
  validate(q);
  MeshData m;
  m.name = name;
  const int n = q.chordwisePoints;  // per surface, edges included
  const int ring = 2 * n - 2;       // nodes around one section
  const int divisions = q.cells * q.spanDivisions;
  const int stations = divisions + 1;
  const double tip = q.tipChord.value_or(q.rootChord);
  std::vector<int> rowStation;
  int intakeFrom = -1, intakeTo = -1;
  const std::vector<double> xi = chordStations(q, rowStation, intakeFrom, intakeTo);

  // Section points in chord units, around the ring: leading edge, upper surface, trailing edge, lower
  // surface.
  std::vector<Point2> sec(ring);
  for (int k = 0; k < ring; ++k) {
    if (k < n) {
      sec[k] = q.section.upper(xi[k]);
    } else {
      sec[k] = q.section.lower(xi[2 * n - 2 - k]);
    }
  }
  sec[0] = q.section.upper(0.0);
  sec[n - 1] = q.section.upper(1.0);
  const double deg = kPi / 180.0;
  auto place = [&](double s, const Point2& p) -> P3 {
    const double frac = std::abs(2.0 * s / q.span);
    const double c = q.rootChord + (tip - q.rootChord) * frac;
    const double a = (q.incidenceDeg + q.twistDeg * frac) * deg;
    const double X = (p[0] - 0.25) * c, Y = p[1] * c;
    const double Xr = X * std::cos(a) + Y * std::sin(a), Yr = -X * std::sin(a) + Y * std::cos(a);
    double ay = s, az = 0, sp = 0, cp = 1;
    if (q.arcRadius > 0) {
      const double phi = s / q.arcRadius;
      sp = std::sin(phi), cp = std::cos(phi);
      ay = q.arcRadius * sp, az = q.arcRadius * (cp - 1.0);
    }
    return {0.25 * q.rootChord + Xr, ay + Yr * sp, az + Yr * cp};
  };
  auto spanAt = [&](int j) {
    // Mirror pairs j, divisions − j get exactly opposite stations.
    const int mirror = divisions - j;
    return j <= mirror ? -0.5 * q.span + q.span * j / divisions : 0.5 * q.span - q.span * mirror / divisions;
  };
  // The bulge: each skin point between two ribs moves along the section's outward normal by the circular
  // arc through the two ribs with height bulge·w at mid-cell (w = the cell width along the span), times the
  // local thickness over the largest (the skins meet at the edges, so the bulge fades there).
  std::vector<Point2> outward(ring, Point2{0, 0});
  std::vector<double> taper(ring, 0.0);
  if (q.bulge > 0) {
    double tmax = 0;
    for (int k = 1; k < n - 1; ++k) tmax = std::max(tmax, sec[k][1] - sec[2 * n - 2 - k][1]);
    for (int k = 1; k < ring; ++k) {
      if (k == n - 1) continue;  // the trailing edge
      const Point2& a = sec[k - 1];
      const Point2& b = sec[(k + 1) % ring];
      const double tx = b[0] - a[0], ty = b[1] - a[1], tl = std::hypot(tx, ty);
      outward[k] = {-ty / tl, tx / tl};  // the ring runs clockwise: outward is to the left
      const int up = k < n ? k : 2 * n - 2 - k;
      taper[k] = std::max(0.0, (sec[up][1] - sec[2 * n - 2 - up][1]) / tmax);
    }
  }
  const double cellWidth = q.span / q.cells;
  for (int j = 0; j < stations; ++j) {
    const double s = spanAt(j);
    const int inCell = j % q.spanDivisions;
    double arc = 0;  // the arc's height at this station, in metres
    if (q.bulge > 0 && inCell != 0) {
      const double h = q.bulge * cellWidth, half = 0.5 * cellWidth;
      const double r = (half * half + h * h) / (2 * h);
      const double d = (double(inCell) / q.spanDivisions - 0.5) * cellWidth;
      arc = std::sqrt(r * r - d * d) - (r - h);
    }
    const double frac = std::abs(2.0 * s / q.span);
    const double chord = q.rootChord + (tip - q.rootChord) * frac;
    for (int k = 0; k < ring; ++k) {
      Point2 p = sec[k];
      if (arc > 0) {
        const double off = arc * taper[k] / chord;  // section coordinates are in chords
        p = {p[0] + off * outward[k][0], p[1] + off * outward[k][1]};
      }
      m.points.push_back(place(s, p));
    }
  }
  auto node = [&](int j, int k) { return j * ring + k; };
  auto lowerIndex = [&](int k) { return k == 0 ? 0 : 2 * n - 2 - k; };  // chord station of a lower ring node

  // Skins.
  std::vector<int> upper, lower;
  for (int j = 0; j + 1 < stations; ++j) {
    const bool left = 2 * j + 1 < divisions;  // the strip's centre is left of the symmetry plane
    for (int k = 0; k < ring; ++k) {
      const int k1 = (k + 1) % ring;
      const bool isUpper = k < n - 1;
      if (!isUpper && intakeFrom >= 0 && lowerIndex(k1) >= intakeFrom && lowerIndex(k) <= intakeTo) continue;
      const int a = node(j, k), b = node(j, k1), c = node(j + 1, k1), d = node(j + 1, k);
      auto& group = isUpper ? upper : lower;
      const int t0 = int(m.triangles.size());
      if (left) {
        m.triangles.push_back({a, b, c});
        m.triangles.push_back({a, c, d});
      } else {
        m.triangles.push_back({a, b, d});
        m.triangles.push_back({b, c, d});
      }
      group.push_back(t0);
      group.push_back(t0 + 1);
    }
  }
  // Ribs: the section's inside, strips between the upper and lower node of each chord station.
  std::vector<int> ribs, tipRibs, innerRibs;
  for (int r = 0; r <= q.cells; ++r) {
    const int j = r * q.spanDivisions;
    auto U = [&](int i) { return node(j, i); };
    auto L = [&](int i) { return node(j, i == 0 ? 0 : (i == n - 1 ? n - 1 : 2 * n - 2 - i)); };
    std::vector<std::array<int, 3>> tris;
    tris.push_back({U(0), U(1), L(1)});
    for (int i = 1; i + 2 < n; ++i) {
      tris.push_back({U(i), U(i + 1), L(i + 1)});
      tris.push_back({U(i), L(i + 1), L(i)});
    }
    tris.push_back({U(n - 2), U(n - 1), L(n - 2)});
    const bool isTip = r == 0 || r == q.cells;
    for (auto t : tris) {
      if (r == 0) std::swap(t[1], t[2]);  // the left tip rib faces −y (outward)
      const int id = int(m.triangles.size());
      m.triangles.push_back(t);
      ribs.push_back(id);
      (isTip ? tipRibs : innerRibs).push_back(id);
    }
  }
  std::vector<int> skin = upper;
  skin.insert(skin.end(), lower.begin(), lower.end());
  skin.insert(skin.end(), tipRibs.begin(), tipRibs.end());
  std::sort(skin.begin(), skin.end());
  m.triangleGroups["upper"] = upper;
  m.triangleGroups["lower"] = lower;
  m.triangleGroups["skin"] = skin;
  m.triangleGroups["ribs"] = ribs;
  m.triangleGroups["tip_ribs"] = tipRibs;
  m.triangleGroups["inner_ribs"] = innerRibs;

  std::vector<int>& le = m.nodeGroups["leading_edge"];
  std::vector<int>& te = m.nodeGroups["trailing_edge"];
  std::vector<int>& intake = m.nodeGroups["intake_edge"];
  for (int j = 0; j < stations; ++j) {
    le.push_back(node(j, 0));
    te.push_back(node(j, n - 1));
    if (intakeFrom >= 0)
      for (int i : {intakeFrom, intakeTo}) intake.push_back(node(j, i == 0 ? 0 : 2 * n - 2 - i));
  }
  std::sort(intake.begin(), intake.end());

  // Lines: a chain of line_elements cables between two points (new interior nodes), tagged into groups.
  auto addPoint = [&](const P3& p) {
    m.points.push_back(p);
    return int(m.points.size()) - 1;
  };
  auto chain = [&](int from, int to, const std::vector<std::string>& groups) {
    const P3 a = m.points[from], b = m.points[to];
    int prev = from;
    for (int e = 1; e <= q.lineElements; ++e) {
      const int next = e == q.lineElements ? to : addPoint(lerp(a, b, double(e) / q.lineElements));
      for (const auto& g : groups) m.lineGroups[g].push_back(int(m.lines.size()));
      m.lines.push_back({prev, next});
      prev = next;
    }
  };
  const double L = q.lineLength * q.span, mu = q.riggingDeg * deg;
  const P3 ref{0.25 * q.rootChord, 0.0, 0.0};
  const P3 conf{ref[0] - L * std::sin(mu), 0.0, ref[2] - L * std::cos(mu)};
  const int confluence = addPoint(conf);
  m.nodeGroups["confluence"] = {confluence};

  std::vector<int> loadRibs;
  for (int r = 0; r <= q.cells; ++r)
    if (!q.alternateRibs || r % 2 == 0) loadRibs.push_back(r);
  std::vector<int>& attachments = m.nodeGroups["attachments"];
  for (std::size_t row = 0; row < q.rows.size(); ++row) {
    const std::string rowGroup = fmt::format("lines_{}", char('A' + row));
    const int i = rowStation[row];
    auto attach = [&](int r) { return node(r * q.spanDivisions, 2 * n - 2 - i); };
    for (int r : loadRibs) {
      const int a = attach(r);
      attachments.push_back(a);
      if (!(m.points[a][2] - conf[2] > 0.05 * L))
        invalid("line_length",
                fmt::format("is {} (× span): the confluence point is not below the attachment "
                            "of row {} on rib {}; valid: long enough that every line hangs down",
                            q.lineLength, char('A' + row), r));
    }
    // Groups of `cascade` load-bearing ribs per half-span from the tip inward; a rib on the symmetry plane
    // gets its own line.
    std::vector<std::vector<int>> groups;
    std::vector<std::string> sides;  // the half-span group a line belongs to ("" on the symmetry plane)
    std::vector<int> leftHalf, rightHalf, centre;
    for (int r : loadRibs) (2 * r < q.cells ? leftHalf : 2 * r > q.cells ? rightHalf : centre).push_back(r);
    std::reverse(rightHalf.begin(), rightHalf.end());  // from the right tip inward
    for (const auto* half : {&leftHalf, &rightHalf})
      for (std::size_t g = 0; g < half->size(); g += std::size_t(q.cascade)) {
        groups.emplace_back(half->begin() + long(g),
                            half->begin() + long(std::min(half->size(), g + std::size_t(q.cascade))));
        sides.push_back(half == &leftHalf ? "lines_left" : "lines_right");
      }
    if (!centre.empty()) {
      groups.push_back(centre);
      sides.emplace_back();
    }
    // row_trim: the line into the confluence (the whole line, or the main line of a cascade) lengthened by
    // the row's trim, every cable of it in proportion; a trim that takes half the line or more is refused
    const double trim = q.rowTrim ? (*q.rowTrim)[row] : 0.0;
    auto trimmed = [&](int from, std::size_t first) {
      if (trim == 0.0) return;
      const double span = distance(m.points[std::size_t(from)], conf);
      if (!(trim > -0.5 * span))
        invalid(fmt::format("row_trim[{}]", row),
                fmt::format(
                    "is {} m: row {}'s line into the confluence is {:.4g} m long; valid: above minus half "
                    "of it",
                    trim, char('A' + row), span));
      m.lineRestLength.resize(m.lines.size(), 0.0);
      for (std::size_t e = first; e < m.lines.size(); ++e)
        m.lineRestLength[e] =
            distance(m.points[m.lines[e][0]], m.points[m.lines[e][1]]) * (span + trim) / span;
    };
    for (std::size_t gi = 0; gi < groups.size(); ++gi) {
      const auto& g = groups[gi];
      std::vector<std::string> tags{"lines", rowGroup};
      if (!sides[gi].empty()) tags.push_back(sides[gi]);
      if (q.cascade == 1) {
        const std::size_t first = m.lines.size();
        chain(attach(g[0]), confluence, tags);
        trimmed(attach(g[0]), first);
        continue;
      }
      P3 mean{0, 0, 0};
      for (int r : g)
        for (int c = 0; c < 3; ++c) mean[c] += m.points[attach(r)][c] / double(g.size());
      const int junction = addPoint(lerp(mean, conf, q.cascadeFraction));
      for (int r : g) chain(attach(r), junction, tags);
      std::vector<std::string> mainTags{"lines", "main_lines"};
      if (!sides[gi].empty()) mainTags.push_back(sides[gi]);
      const std::size_t first = m.lines.size();
      chain(junction, confluence, mainTags);
      trimmed(junction, first);
    }
  }
  std::sort(attachments.begin(), attachments.end());

  // Brakes: fans from the trailing edge of the outermost ribs to a toggle on each side.
  m.nodeGroups["toggle_left"] = {};
  m.nodeGroups["toggle_right"] = {};
  m.lineGroups["brakes_left"];
  m.lineGroups["brakes_right"];
  if (q.brakePoints > 0) {
    for (int side = 0; side < 2; ++side) {
      std::vector<int> tePoints;
      for (int b = 0; b < q.brakePoints; ++b) {
        const int r = side == 0 ? b : q.cells - b;
        tePoints.push_back(node(r * q.spanDivisions, n - 1));
      }
      P3 mean{0, 0, 0};
      for (int p : tePoints)
        for (int c = 0; c < 3; ++c) mean[c] += m.points[p][c] / double(tePoints.size());
      const int toggle = addPoint(lerp(conf, mean, q.toggleFraction));
      const std::string g = side == 0 ? "brakes_left" : "brakes_right";
      m.nodeGroups[side == 0 ? "toggle_left" : "toggle_right"] = {toggle};
      for (int p : tePoints) {
        const std::size_t first = m.lines.size();
        chain(p, toggle, {"brakes", g});
        if (q.brakeSlack > 0) {
          // Each cable of the line longer in proportion, so the line's rest length is its span plus the
          // slack.
          const double span = distance(m.points[p], m.points[toggle]);
          m.lineRestLength.resize(m.lines.size(), 0.0);
          for (std::size_t e = first; e < m.lines.size(); ++e)
            m.lineRestLength[e] =
                distance(m.points[m.lines[e][0]], m.points[m.lines[e][1]]) * (span + q.brakeSlack) / span;
        }
      }
    }
  }
  m.lineGroups["brakes"];
  // Trailing-edge tape: one cable per skin edge along the trailing edge (the skin's own nodes, no new ones);
  // the set `tapes` exists only with it.
  if (q.trailingEdgeTape)
    for (int j = 0; j < q.cells * q.spanDivisions; ++j) {
      m.lineGroups["tapes"].push_back(int(m.lines.size()));
      m.lines.push_back({node(j, n - 1), node(j + 1, n - 1)});
    }
  m.lineGroups["main_lines"];
  m.lineGroups["riser"];
  if (q.riserLength) {
    const int payload = addPoint({conf[0], conf[1], conf[2] - *q.riserLength});
    chain(confluence, payload, {"riser"});
    m.nodeGroups["payload"] = {payload};
  } else {
    m.nodeGroups["payload"] = {confluence};
  }

  m.pointTags.resize(m.points.size());
  std::iota(m.pointTags.begin(), m.pointTags.end(), 1L);
  m.triangleTags.resize(m.triangles.size());
  std::iota(m.triangleTags.begin(), m.triangleTags.end(), 1L);
  m.lineTags.resize(m.lines.size());
  std::iota(m.lineTags.begin(), m.lineTags.end(), 1L);
  if (!m.lineRestLength.empty()) m.lineRestLength.resize(m.lines.size(), 0.0);
  // The bounds above keep the design finite; this is the last guard that nothing else slipped through.
  for (std::size_t i = 0; i < m.points.size(); ++i)
    for (double x : m.points[i])
      if (!std::isfinite(x))
        throw InputError(
            fmt::format("parafoil generator: node {} of the design has a non-finite coordinate; "
                        "check span, chords, arc_radius and the line lengths",
                        i + 1));
  return m;
}

}  // namespace fsi::structure::parafoil
