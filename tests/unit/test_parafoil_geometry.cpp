// The parafoil's section and design shape against independent references: the NACA definitions (thickness,
// camber, the area integral of the thickness polynomial), Pappus' theorem for the volume enclosed by the
// skins, watertightness and orientation of the outer surface, exact line geometry, and mirror symmetry.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>
#include <tuple>

#include "structure/elements/BuildModel.hpp"
#include "structure/elements/CableForces.hpp"
#include "structure/model/Error.hpp"
#include "structure/model/Model.hpp"
#include "structure/parafoil/AirfoilSection.hpp"
#include "structure/parafoil/ParafoilGeometry.hpp"
#include "structure/scene/Scene.hpp"

using fsi::InputError;
using fsi::structure::MeshData;
using namespace fsi::structure::parafoil;
using namespace fsi::structure;

namespace {

const double kPi = std::acos(-1.0);

// Area and centroid height of the section polygon sampled finely (independent of the generator's stations).
std::pair<double, double> areaCentroid(const AirfoilSection& s, int n = 20000) {
  std::vector<Point2> poly;
  for (int i = n; i >= 0; --i) poly.push_back(s.upper(0.5 * (1 - std::cos(kPi * i / n))));
  for (int i = 1; i < n; ++i) poly.push_back(s.lower(0.5 * (1 - std::cos(kPi * i / n))));
  double a2 = 0, cy = 0;
  for (std::size_t i = 0; i < poly.size(); ++i) {
    const Point2& p = poly[i];
    const Point2& q = poly[(i + 1) % poly.size()];
    const double c = p[0] * q[1] - q[0] * p[1];
    a2 += c;
    cy += (p[1] + q[1]) * c;
  }
  return {std::abs(0.5 * a2), cy / (3.0 * a2)};
}

double enclosedVolume(const MeshData& m, const std::vector<int>& tris) {
  double v = 0;
  for (int t : tris) {
    const auto& a = m.points[m.triangles[t][0]];
    const auto& b = m.points[m.triangles[t][1]];
    const auto& c = m.points[m.triangles[t][2]];
    v += (a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0]) +
          a[2] * (b[0] * c[1] - b[1] * c[0])) /
         6.0;
  }
  return v;
}

ParafoilParams untwisted(int points, int divisions) {
  ParafoilParams q;
  q.span = 3.0;
  q.rootChord = 1.0;
  q.cells = 8;
  q.arcRadius = 3.0;  // R/b = 1, as in Kalro & Tezduyar
  q.section = AirfoilSection::naca("4415", "test");
  q.chordwisePoints = points;
  q.spanDivisions = divisions;
  return q;
}

}  // namespace

TEST(AirfoilSection, Naca4DigitThicknessAndCamberAsDefined) {
  const AirfoilSection s = AirfoilSection::naca("NACA 2412", "test");
  // Max camber m = 0.02 at p = 0.4: the mid-point of the two surface points of one station is on the mean
  // line.
  const Point2 u = s.upper(0.4), l = s.lower(0.4);
  EXPECT_NEAR(0.5 * (u[0] + l[0]), 0.4, 1e-14);
  EXPECT_NEAR(0.5 * (u[1] + l[1]), 0.02, 1e-14);
  // Thickness ratio t = 0.12 (the 4-digit thickness is largest near 30 % chord, where 2 y_t = 1.0003 t).
  EXPECT_NEAR(s.thickness(), 0.12, 0.12 * 1e-3);
  EXPECT_NEAR(s.upper(0)[0], 0.0, 1e-15);
  EXPECT_NEAR(s.upper(1)[1], s.lower(1)[1], 1e-15);  // closed trailing edge
}

TEST(AirfoilSection, SymmetricAreaEqualsTheThicknessIntegral) {
  // ∫ 2 y_t dx over the chord = 10 t (0.2969·2/3 − 0.1260/2 − 0.3516/3 + 0.2843/4 − 0.1036/5).
  const double t = 0.15;
  const double exact = 10 * t * (0.2969 * 2.0 / 3.0 - 0.1260 / 2 - 0.3516 / 3 + 0.2843 / 4 - 0.1036 / 5);
  const AirfoilSection s = AirfoilSection::naca("0015", "test");
  EXPECT_NEAR(s.area(4000), exact, exact * 1e-5);
  EXPECT_NEAR(s.scaledThickness(2.0).area(4000), 2 * exact, 2 * exact * 1e-5);
}

TEST(AirfoilSection, Naca5DigitMeanLinePeaksAtItsDesignPosition) {
  // 230xx: design lift 0.3, maximum camber at 15 % chord, about 1.8 % high (the family's defining table).
  const AirfoilSection s = AirfoilSection::naca("23012", "test");
  double best = -1, at = 0;
  for (int i = 1; i < 4000; ++i) {
    const double xi = i / 4000.0;
    const double yc = 0.5 * (s.upper(xi)[1] + s.lower(xi)[1]);
    if (yc > best) best = yc, at = xi;
  }
  EXPECT_NEAR(at, 0.15, 2e-3);
  EXPECT_NEAR(best, 0.0183, 5e-4);
  // A reflexed mean line (Q = 1) turns up again before the trailing edge: its slope there is positive.
  const AirfoilSection r = AirfoilSection::naca("23112", "test");
  const double y1 = 0.5 * (r.upper(0.95)[1] + r.lower(0.95)[1]),
               y2 = 0.5 * (r.upper(0.99)[1] + r.lower(0.99)[1]);
  EXPECT_LT(std::abs(y2 - y1), std::abs(0.5 * (s.upper(0.95)[1] + s.lower(0.95)[1]) -
                                        0.5 * (s.upper(0.99)[1] + s.lower(0.99)[1])));
}

TEST(AirfoilSection, XOnSurfaceInvertsTheOffset) {
  const AirfoilSection s = AirfoilSection::naca("4415", "test");
  for (double x : {0.1, 0.3, 0.6, 0.8}) {
    EXPECT_NEAR(s.lower(s.xOnSurface(x, false))[0], x, 1e-12);
    EXPECT_NEAR(s.upper(s.xOnSurface(x, true))[0], x, 1e-12);
  }
}

TEST(AirfoilSection, SeligFileGivesTheSameSection) {
  const AirfoilSection n = AirfoilSection::naca("0012", "test");
  std::string text = "NACA 0012 written out\n";
  const int k = 200;
  for (int i = k; i >= 0; --i) {
    const Point2 p = n.upper(0.5 * (1 - std::cos(kPi * i / k)));
    text += std::to_string(p[0]) + " " + std::to_string(p[1]) + "\n";
  }
  for (int i = 1; i <= k; ++i) {
    const Point2 p = n.lower(0.5 * (1 - std::cos(kPi * i / k)));
    text += std::to_string(p[0]) + " " + std::to_string(p[1]) + "\r\n";
  }
  const AirfoilSection s = AirfoilSection::seligText(text, "n0012.dat");
  EXPECT_NEAR(s.area(), n.area(), n.area() * 2e-3);
  EXPECT_NEAR(s.thickness(), 0.12, 1e-3);
  EXPECT_NEAR(s.upper(0.3)[1], n.upper(0.3)[1], 1e-3);
}

TEST(AirfoilSection, BadSectionFilesAreLocated) {
  auto message = [](const std::string& text) {
    try {
      AirfoilSection::seligText(text, "wing.dat");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message("s\n1 0\n0.5 0.05\n0 0\n0.5 -0.05\n0.6 x\n1 0\n").find("wing.dat:6"), std::string::npos);
  // Not closed: the last point is far from the first.
  EXPECT_NE(message("s\n1 0\n0.5 0.05\n0 0\n0.5 -0.05\n0.6 -0.04\n").find("not a closed curve"),
            std::string::npos);
  // The surfaces cross.
  EXPECT_NE(message("s\n1 0\n0.5 -0.05\n0.2 0.03\n0 0\n0.2 -0.03\n0.5 0.05\n1 0\n").find("cross"),
            std::string::npos);
  // Lednicer's format (counts first).
  EXPECT_NE(message("s\n3. 3.\n\n0 0\n0.5 0.05\n1 0\n\n0 0\n0.5 -0.05\n1 0\n").find("Lednicer"),
            std::string::npos);
  try {
    AirfoilSection::naca("NACA 2x12", "scene.yaml:4");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("scene.yaml:4"), std::string::npos);
  }
  EXPECT_THROW(AirfoilSection::naca("26012", "w"), InputError);  // position digit 6 does not exist
}

TEST(ParafoilGeometry, ClosedSkinIsWatertightAndOutward) {
  ParafoilParams q = untwisted(16, 2);
  q.bulge = 0.1;
  const MeshData m = buildParafoil(q);
  const auto& skin = m.triangleGroups.at("skin");
  // Every directed edge of a closed, consistently oriented surface appears once, its reverse once.
  std::map<std::pair<int, int>, int> directed;
  for (int t : skin)
    for (int e = 0; e < 3; ++e) ++directed[{m.triangles[t][e], m.triangles[t][(e + 1) % 3]}];
  for (const auto& [edge, count] : directed) {
    ASSERT_EQ(count, 1) << "edge " << edge.first << "-" << edge.second;
    ASSERT_EQ(directed.count({edge.second, edge.first}), 1u)
        << "open edge " << edge.first << "-" << edge.second;
  }
  EXPECT_GT(enclosedVolume(m, skin), 0.0);  // outward
}

TEST(ParafoilGeometry, EnclosedVolumeConvergesToPappus) {
  // Volume swept by the section along the arc: area × c² × the path of its centroid, b (1 + ȳ c / R).
  ParafoilParams q = untwisted(12, 1);
  const auto [area, ybar] = areaCentroid(q.section);
  const double exact = area * q.rootChord * q.rootChord * q.span * (1.0 + ybar * q.rootChord / q.arcRadius);
  const MeshData coarse = buildParafoil(q);
  const double errCoarse = std::abs(enclosedVolume(coarse, coarse.triangleGroups.at("skin")) / exact - 1.0);
  q.chordwisePoints = 24;
  q.spanDivisions = 2;
  const MeshData fine = buildParafoil(q);
  const double errFine = std::abs(enclosedVolume(fine, fine.triangleGroups.at("skin")) / exact - 1.0);
  EXPECT_LT(errFine, 0.01);
  EXPECT_LT(errFine, errCoarse / 3.0);  // second order: halving both spacings quarters the error
}

// The root rib's section (y = 0) sorted by x: the trailing-edge panel is the gap between the two largest x.
double trailingEdgePanel(const MeshData& m) {
  std::vector<double> xs;
  for (const auto& p : m.points)
    if (std::abs(p[1]) < 1e-12 && p[2] > -0.5) xs.push_back(p[0]);  // not the lines below the wing
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end(), [](double a, double b) { return std::abs(a - b) < 1e-12; }),
           xs.end());
  return xs.back() - xs[xs.size() - 2];
}

TEST(ParafoilGeometry, HalfCosineSpacingGivesTheTrailingEdgeLongPanels) {
  // n = 20 stations. Cosine: the last chord gap is (1 + cos(π·18/19))/2 = 0.0068; half-cosine:
  // cos(π/2·18/19) = 0.0826 (x on the surface differs from the chord parameter by the slope's offset, a few
  // per cent of the gap near the trailing edge).
  ParafoilParams q = untwisted(20, 2);
  const double cosine = trailingEdgePanel(buildParafoil(q));
  q.chordSpacing = ParafoilParams::ChordSpacing::halfCosine;
  const MeshData half = buildParafoil(q);
  EXPECT_NEAR(cosine, 0.5 * (1 + std::cos(kPi * 18 / 19)), 0.1 * 0.0068);
  EXPECT_NEAR(trailingEdgePanel(half), std::cos(0.5 * kPi * 18 / 19), 0.05 * 0.0826);
  // Still a closed, outward skin enclosing the section's volume (Pappus) within the coarse mesh's error,
  // with the attachment rows on their stations.
  const auto [area, ybar] = areaCentroid(q.section);
  const double exact = area * q.span * (1.0 + ybar / q.arcRadius);
  EXPECT_NEAR(enclosedVolume(half, half.triangleGroups.at("skin")) / exact, 1.0, 0.02);
  std::multiset<double> xs;
  for (int a : half.nodeGroups.at("attachments")) xs.insert(std::round(half.points[a][0] * 1e9) / 1e9);
  for (double row : q.rows) EXPECT_EQ(xs.count(std::round(row * 1e9) / 1e9), std::size_t(q.cells + 1));
}

TEST(ParafoilGeometry, LinesAndAttachmentsAsSpecified) {
  ParafoilParams q = untwisted(24, 2);
  q.riserLength = 0.5;
  const MeshData m = buildParafoil(q);
  const auto& c = m.points[m.nodeGroups.at("confluence")[0]];
  const double L = std::hypot(c[0] - 0.25 * q.rootChord, c[1], c[2]);
  EXPECT_NEAR(L, q.lineLength * q.span, 1e-12);
  EXPECT_NEAR(std::atan2(-(c[0] - 0.25), -c[2]), q.riggingDeg * kPi / 180.0, 1e-12);
  // Attachments: on the lower surface at the row's x/c (no taper, twist or incidence: x = (x/c)·c).
  std::multiset<double> xs;
  for (int a : m.nodeGroups.at("attachments")) xs.insert(std::round(m.points[a][0] * 1e9) / 1e9);
  for (double row : q.rows) EXPECT_EQ(xs.count(std::round(row * 1e9) / 1e9), std::size_t(q.cells + 1));
  // Each row: cascade 2 on 4 ribs per half + the centre rib = 2 + 2 + 1 main lines.
  EXPECT_EQ(m.lineGroups.at("main_lines").size(), q.rows.size() * 5 * std::size_t(q.lineElements));
  const auto& p = m.points[m.nodeGroups.at("payload")[0]];
  EXPECT_NEAR(c[2] - p[2], 0.5, 1e-12);
  // Line nodes of one segment are equally spaced on a straight line: total length of a chain = end distance.
  double chainLength = 0;
  for (int e : m.lineGroups.at("riser")) {
    const auto& a = m.points[m.lines[e][0]];
    const auto& b = m.points[m.lines[e][1]];
    chainLength += std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
  }
  EXPECT_NEAR(chainLength, 0.5, 1e-12);
}

TEST(ParafoilGeometry, TrailingEdgeTapeJoinsTheTrailingEdgeFromTipToTip) {
  ParafoilParams q = untwisted(24, 2);
  EXPECT_EQ(buildParafoil(q).lineGroups.count("tapes"), 0u);  // off unless asked for
  q.trailingEdgeTape = true;
  const MeshData m = buildParafoil(q);
  const auto& tapes = m.lineGroups.at("tapes");
  const auto& te = m.nodeGroups.at("trailing_edge");  // one node per spanwise station, tip to tip
  ASSERT_EQ(tapes.size(), te.size() - 1);
  ASSERT_EQ(te.size(), std::size_t(q.cells * q.spanDivisions + 1));
  // Cable k joins stations k and k + 1: the skin's own trailing-edge nodes, no new points, and its length is
  // the chord of the arc between them (untwisted, untapered: the edge lies on a circle of the arc's radius
  // about the arc's centre, so the stations are equally spaced along it).
  double total = 0;
  for (std::size_t k = 0; k < tapes.size(); ++k) {
    const auto& line = m.lines[tapes[k]];
    EXPECT_EQ(std::min(line[0], line[1]), std::min(te[k], te[k + 1])) << k;
    EXPECT_EQ(std::max(line[0], line[1]), std::max(te[k], te[k + 1])) << k;
    const auto& a = m.points[line[0]];
    const auto& b = m.points[line[1]];
    total += std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
  }
  const auto& first = m.points[te.front()];
  const auto& last = m.points[te.back()];
  EXPECT_NEAR(first[1], -last[1], 1e-12);  // mirror symmetric ends
  EXPECT_GT(total, std::hypot(first[0] - last[0], first[1] - last[1], first[2] - last[2]));  // a curve
  EXPECT_LT(total, q.span * (1 + 1e-12));  // the polygon inscribed in the span's arc
  EXPECT_EQ(m.points.size(), buildParafoil(untwisted(24, 2)).points.size());
}

// Brake lines rigged with slack: each line's rest length is the distance from its trailing-edge point to the
// toggle plus brake_slack (every cable of it longer in proportion), the other lines keep the distance of
// their ends. In the model, a line pulled straight from its trailing-edge point to a toggle moved by d
// carries nothing while the stretch is within the slack and EA (s - s0 - slack) / (s0 + slack) beyond it (the
// tension-only law on the rest length; s the new span, s0 the design one): the slack is in the model, not
// just in the mesh.
TEST(ParafoilGeometry, BrakeSlackLengthensEachBrakeLineByTheSlack) {
  ParafoilParams q = untwisted(24, 2);
  EXPECT_TRUE(buildParafoil(q).lineRestLength.empty());  // no slack: the reference distances
  q.brakeSlack = 0.05;
  const MeshData m = buildParafoil(q);
  ASSERT_EQ(m.lineRestLength.size(), m.lines.size());
  auto length = [&](int a, int b) {
    const auto &u = m.points[std::size_t(a)], &v = m.points[std::size_t(b)];
    return std::hypot(u[0] - v[0], u[1] - v[1], u[2] - v[2]);
  };
  std::set<int> brakes(m.lineGroups.at("brakes").begin(), m.lineGroups.at("brakes").end());
  for (std::size_t e = 0; e < m.lines.size(); ++e) {
    if (!brakes.count(int(e))) {
      EXPECT_EQ(m.lineRestLength[e], 0.0) << e;
    }
  }
  // The brake group lists each line's cables in order, from its trailing-edge point to the toggle.
  const auto& g = m.lineGroups.at("brakes");
  ASSERT_EQ(g.size(), std::size_t(2 * q.brakePoints * q.lineElements));
  const MembraneMaterial fabric{"fabric", 1.3e9, 0.3, 7.6e-5, 530, true};
  const CableMaterial line{"line", 4.3e10, 3.0e-6, 906};
  MeshInput in;
  in.mesh = m;
  in.membraneMaterial = 0;
  in.cableMaterial = 0;
  const Model model = buildModel({in}, {fabric}, {line});
  const double EA = line.young * line.area;
  for (std::size_t k = 0; k < g.size(); k += std::size_t(q.lineElements)) {
    const int te = m.lines[std::size_t(g[k])][0];
    const int toggle = m.lines[std::size_t(g[k + std::size_t(q.lineElements) - 1])][1];
    const double s0 = length(te, toggle);
    double rest = 0, modelRest = 0;
    for (int j = 0; j < q.lineElements; ++j) {
      rest += m.lineRestLength[std::size_t(g[k + std::size_t(j)])];
      modelRest +=
          model.cables.restLength[std::size_t(model.meshes[0].line[std::size_t(g[k + std::size_t(j)])])];
    }
    EXPECT_NEAR(rest, s0 + q.brakeSlack, 1e-12) << "brake line " << k / q.lineElements;
    EXPECT_NEAR(modelRest, s0 + q.brakeSlack, 1e-12) << "brake line " << k / q.lineElements;
    // The line pulled straight to the toggle moved away along it by d: slack at d = 0.03, taut at 0.08.
    for (const double d : {0.03, 0.08}) {
      std::vector<double> x = model.nodes.X;
      const auto& a = m.points[std::size_t(te)];
      const auto& b = m.points[std::size_t(toggle)];
      const double s = s0 + d;
      for (int j = 1; j <= q.lineElements; ++j) {
        const int node = j == q.lineElements ? toggle : m.lines[std::size_t(g[k + std::size_t(j)])][0];
        const int i = model.meshes[0].node[std::size_t(node)];
        for (int c = 0; c < 3; ++c)
          x[std::size_t(3 * i + c)] =
              a[std::size_t(c)] + (b[std::size_t(c)] - a[std::size_t(c)]) * s / s0 * j / q.lineElements;
      }
      std::vector<double> T;
      cableTensions(model.cables, x.data(), T);
      const double expected = EA * std::max(0.0, s - s0 - q.brakeSlack) / (s0 + q.brakeSlack);
      for (int j = 0; j < q.lineElements; ++j)
        EXPECT_NEAR(T[std::size_t(model.meshes[0].line[std::size_t(g[k + std::size_t(j)])])], expected,
                    1e-6 * EA)
            << "brake line " << k / q.lineElements << ", d " << d << ", cable " << j;
    }
  }
  q.brakeSlack = -0.01;
  EXPECT_THROW(buildParafoil(q), InputError);
}

// row_trim: each row's line into the confluence point (with cascades its main line) is longer by the row's
// trim than the design distance, every cable of it in proportion; the other lines keep their design length; a
// trim per row or none, and one that takes half the line or more, are refused.
TEST(ParafoilGeometry, RowTrimLengthensEachRowsLineIntoTheConfluenceByItsTrim) {
  for (const int cascade : {1, 2}) {
    ParafoilParams q = untwisted(24, 2);
    q.cascade = cascade;
    q.rowTrim = {-0.02, 0.0, 0.01, 0.03};
    const MeshData m = buildParafoil(q);
    ASSERT_EQ(m.lineRestLength.size(), m.lines.size());
    const int confluence = m.nodeGroups.at("confluence")[0];
    auto length = [&](int a, int b) {
      const auto &u = m.points[std::size_t(a)], &v = m.points[std::size_t(b)];
      return std::hypot(u[0] - v[0], u[1] - v[1], u[2] - v[2]);
    };
    // the lines into the confluence, by row: walk each row's cables ending at the confluence back to their
    // start
    std::set<int> trimmed;
    for (std::size_t r = 0; r < q.rows.size(); ++r) {
      const auto& row = m.lineGroups.at(std::string("lines_") + char('A' + r));
      const std::set<int> rowSet(row.begin(), row.end());
      const auto& candidates = cascade == 1 ? row : m.lineGroups.at("main_lines");
      int lines = 0;
      for (std::size_t k = 0; k < candidates.size(); ++k) {
        const int e = candidates[k];
        if (m.lines[std::size_t(e)][1] != confluence) continue;
        // the line's cables are consecutive, the last one ending at the confluence
        const int first = e - q.lineElements + 1;
        const int start = m.lines[std::size_t(first)][0];
        if (cascade == 2) {
          // a main line belongs to row r when its junction is where row r's upper lines end
          bool ofRow = false;
          for (const int u : row) ofRow = ofRow || m.lines[std::size_t(u)][1] == start;
          if (!ofRow) continue;
        } else if (!rowSet.count(e)) {
          continue;
        }
        double rest = 0;  // a rest length of 0 stands for the design distance of the cable's ends
        for (int j = first; j <= e; ++j) {
          const double r0 = m.lineRestLength[std::size_t(j)];
          rest += r0 > 0 ? r0 : length(m.lines[std::size_t(j)][0], m.lines[std::size_t(j)][1]);
          if ((*q.rowTrim)[r] != 0.0) trimmed.insert(j);
        }
        EXPECT_NEAR(rest, length(start, confluence) + (*q.rowTrim)[r], 1e-12)
            << "row " << char('A' + r) << ", cascade " << cascade;
        ++lines;
      }
      EXPECT_GT(lines, 0) << "row " << char('A' + r);
    }
    for (std::size_t e = 0; e < m.lines.size(); ++e)
      if (!trimmed.count(int(e))) {
        EXPECT_EQ(m.lineRestLength[e], 0.0) << "cable " << e << " is not a trimmed line's";
      }
  }
  ParafoilParams q = untwisted(24, 2);
  q.rowTrim = {0.01, 0.02};  // four rows
  EXPECT_THROW(buildParafoil(q), InputError);
  q.rowTrim = {-2.0, 0, 0, 0};  // more than half of a 2 m line
  EXPECT_THROW(buildParafoil(q), InputError);
}

TEST(ParafoilGeometry, BulgedCellsAreCircularArcsBetweenTheRibs) {
  // Flat and bulged designs differ only between the ribs: the rib nodes stay, and at the thickest chord
  // station the skin node at mid-cell stands out by bulge·w (w = b / cells), the others on the circular arc
  // through the two ribs with that height.
  ParafoilParams q = untwisted(24, 4);
  q.arcRadius = 0;  // flat span: the offset is then the distance between the two designs
  const MeshData flat = buildParafoil(q);
  q.bulge = 0.2;
  const MeshData bulged = buildParafoil(q);
  ASSERT_EQ(flat.points.size(), bulged.points.size());
  const int ring = 2 * q.chordwisePoints - 2;
  const double w = q.span / q.cells, h = q.bulge * w, r = (w * w / 4 + h * h) / (2 * h);
  // The thickest station of the upper surface: where flat upper minus lower z is largest.
  int kMax = 1;
  double tMax = 0;
  for (int k = 1; k < q.chordwisePoints - 1; ++k) {
    const double t = flat.points[k][2] - flat.points[2 * q.chordwisePoints - 2 - k][2];
    if (t > tMax) tMax = t, kMax = k;
  }
  for (int j = 0; j <= q.cells * q.spanDivisions; ++j) {
    const auto& a = flat.points[j * ring + kMax];
    const auto& b = bulged.points[j * ring + kMax];
    const double moved = std::hypot(a[0] - b[0], a[1] - b[1], a[2] - b[2]);
    const double d = (double(j % q.spanDivisions) / q.spanDivisions - 0.5) * w;
    const double expected = j % q.spanDivisions == 0 ? 0.0 : std::sqrt(r * r - d * d) - (r - h);
    EXPECT_NEAR(moved, expected, 1e-12) << "station " << j;
    EXPECT_GE(b[2], a[2] - 1e-15) << "the upper skin bulges outward (up)";
  }
  // The leading and trailing edges do not move (the skins meet there).
  for (int j = 0; j <= q.cells * q.spanDivisions; ++j)
    for (int k : {0, q.chordwisePoints - 1})
      for (int c = 0; c < 3; ++c) EXPECT_EQ(flat.points[j * ring + k][c], bulged.points[j * ring + k][c]);
  // Still closed and outward, and larger.
  const auto& skin = bulged.triangleGroups.at("skin");
  EXPECT_GT(enclosedVolume(bulged, skin), enclosedVolume(flat, flat.triangleGroups.at("skin")));
}

TEST(ParafoilGeometry, MirrorSymmetric) {
  ParafoilParams q = untwisted(20, 3);
  q.bulge = 0.15;
  q.twistDeg = 3;
  q.tipChord = 0.7;
  q.intakeOpen = true;
  q.intakeFrom = 0.0;
  q.intakeTo = 0.06;
  const MeshData m = buildParafoil(q);
  auto key = [](const std::array<double, 3>& p, double sign) {
    return std::make_tuple(std::llround(p[0] * 1e9), std::llround(sign * p[1] * 1e9),
                           std::llround(p[2] * 1e9));
  };
  std::map<std::tuple<long long, long long, long long>, int> at;
  for (std::size_t i = 0; i < m.points.size(); ++i) at[key(m.points[i], 1)] = int(i);
  std::vector<int> mirror(m.points.size());
  for (std::size_t i = 0; i < m.points.size(); ++i) {
    const auto it = at.find(key(m.points[i], -1));
    ASSERT_NE(it, at.end()) << "node " << i << " has no mirror image";
    mirror[i] = it->second;
  }
  std::set<std::set<int>> tris, lines;
  for (const auto& t : m.triangles) tris.insert({t[0], t[1], t[2]});
  for (const auto& l : m.lines) lines.insert({l[0], l[1]});
  for (const auto& t : m.triangles) EXPECT_TRUE(tris.count({mirror[t[0]], mirror[t[1]], mirror[t[2]]}));
  for (const auto& l : m.lines) EXPECT_TRUE(lines.count({mirror[l[0]], mirror[l[1]]}));
  EXPECT_EQ(m.lineGroups.at("brakes_left").size(), m.lineGroups.at("brakes_right").size());
  // The left half's suspension lines are the mirror images of the right half's.
  std::set<std::set<int>> right;
  for (int e : m.lineGroups.at("lines_right")) right.insert({m.lines[e][0], m.lines[e][1]});
  ASSERT_EQ(m.lineGroups.at("lines_left").size(), right.size());
  for (int e : m.lineGroups.at("lines_left"))
    EXPECT_TRUE(right.count({mirror[m.lines[e][0]], mirror[m.lines[e][1]]}));
  EXPECT_EQ(mirror[m.nodeGroups.at("toggle_left")[0]], m.nodeGroups.at("toggle_right")[0]);
}

TEST(ParafoilGeometry, EverySetIsNonEmpty) {
  ParafoilParams q = untwisted(16, 2);
  q.intakeOpen = true;
  q.riserLength = 0.3;
  const MeshData m = buildParafoil(q);
  for (const auto& [name, v] : m.nodeGroups) EXPECT_FALSE(v.empty()) << name;
  for (const auto& [name, v] : m.triangleGroups) EXPECT_FALSE(v.empty()) << name;
  for (const auto& [name, v] : m.lineGroups) EXPECT_FALSE(v.empty()) << name;
  for (const char* g : {"lines_A", "lines_B", "lines_C", "lines_D", "main_lines", "brakes", "riser"})
    EXPECT_TRUE(m.lineGroups.count(g)) << g;
  // An open intake removes the lower skin between its edges: the skin is no longer closed.
  EXPECT_LT(m.triangleGroups.at("lower").size(), m.triangleGroups.at("upper").size());
}

TEST(ParafoilGeometry, ImpossibleDesignsNameTheParameter) {
  auto message = [](auto change) {
    ParafoilParams q = untwisted(16, 1);
    change(q);
    try {
      buildParafoil(q);
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_NE(message([](ParafoilParams& q) { q.cells = 0; }).find("'cells'"), std::string::npos);
  EXPECT_NE(message([](ParafoilParams& q) { q.bulge = 0.6; }).find("'bulge'"), std::string::npos);
  EXPECT_NE(message([](ParafoilParams& q) { q.lineLength = 0.01; }).find("'line_length'"), std::string::npos);
  EXPECT_NE(message([](ParafoilParams& q) {
              q.intakeOpen = true;
              q.intakeFrom = 0.2;
              q.intakeTo = 1.3;
            }).find("'intake.to'"),
            std::string::npos);
  EXPECT_NE(message([](ParafoilParams& q) { q.arcRadius = 0.5; }).find("'arc_radius'"), std::string::npos);
  EXPECT_NE(message([](ParafoilParams& q) { q.rows = {0.3, 0.1}; }).find("'rows[1]'"), std::string::npos);
  EXPECT_NE(message([](ParafoilParams& q) {
              q.cells = 7;
              q.alternateRibs = true;
            }).find("'ribs'"),
            std::string::npos);
  EXPECT_NE(message([](ParafoilParams& q) { q.chordwisePoints = 5; }).find("'chordwise_points'"),
            std::string::npos);
}

namespace {
const char* kParafoilScene = R"(materials:
  fabric: {type: membrane, young: 1.3e9, poisson: 0.3, thickness: 7.6e-5, density: 530}
  line: {type: cable, young: 4.3e10, area: 3.0e-6, density: 906}
meshes:
  wing:
    generator: {type: parafoil, cells: 4, chordwise_points: 12, span_divisions: 1, section: NACA 2412,
                intake: {from: 0.0, to: 0.05}, riser_length: 0.4, brake_points: 2}
    material: fabric
    cable_material: line
constraints:
  - {nodes: wing/confluence, fix: all}
effects:
  pressure: {triangles: wing/skin, value: 60}
time: {end: 1.0e-3}
)";
}  // namespace

TEST(ParafoilScene, GeneratorSetsAreSceneSets) {
  const auto scene = fsi::structure::loadSceneFromString(kParafoilScene, "wing.yaml");
  const auto& m = *scene.model;
  EXPECT_GT(m.membranes.count, 0);
  EXPECT_GT(m.cables.count, 0);
  ASSERT_EQ(scene.constraints.fixedDofs.size(), 3u);  // the confluence point
}

TEST(ParafoilScene, MisspelledKeyAndBadValueAreLocated) {
  std::string text = kParafoilScene;
  auto withChange = [&](const std::string& from, const std::string& to) {
    std::string t = text;
    t.replace(t.find(from), from.size(), to);
    try {
      fsi::structure::loadSceneFromString(t, "wing.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  const std::string typo = withChange("cells: 4", "cels: 4");
  EXPECT_NE(typo.find("wing.yaml:6"), std::string::npos) << typo;
  EXPECT_NE(typo.find("cells"), std::string::npos) << typo;
  const std::string spacing = withChange("span_divisions: 1", "span_divisions: 1, chordwise_spacing: even");
  EXPECT_NE(spacing.find("wing.yaml:6"), std::string::npos) << spacing;
  EXPECT_NE(spacing.find("half_cosine"), std::string::npos) << spacing;  // the valid choices are named
  const std::string section = withChange("NACA 2412", "NACA 2x12");
  EXPECT_NE(section.find("wing.yaml:6"), std::string::npos) << section;
  const std::string rows = withChange("riser_length: 0.4", "rows: [0.5, 0.2]");
  EXPECT_NE(rows.find("'rows[1]'"), std::string::npos) << rows;
  EXPECT_NE(rows.find("wing.yaml"), std::string::npos) << rows;
}

// Issue 35, item 9: unset is never a number, a value that cannot take effect is an error, lengths have
// physical bounds, NACA designations are 4 or 5 digits in one piece. Every case below was accepted before.
TEST(ParafoilScene, UnsetIsNotZeroAndIneffectiveOrAbsurdValuesAreRefused) {
  auto withChange = [](const std::string& from, const std::string& to) {
    std::string t = kParafoilScene;
    t.replace(t.find(from), from.size(), to);
    try {
      fsi::structure::loadSceneFromString(t, "wing.yaml");
    } catch (const InputError& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  struct Case {
    const char *from, *to, *expected;
  };
  const Case cases[] = {
      // tip_chord 0 built the untapered wing (0 was "unset"). Ranges of the schema (ParafoilScene.cpp's
      // parafoilSchema) are refused at the key; those that depend on other keys by the geometry's checks.
      {"riser_length: 0.4", "tip_chord: 0", "meshes.wing.generator.tip_chord: must be > 0"},
      {"riser_length: 0.4", "tip_chord: 4", "parameter 'tip_chord' is 4; valid: (0, 3]"},
      // riser_length 0 meant "no riser"; 1e308 made a node at -1e308.
      {"riser_length: 0.4", "riser_length: 0", "meshes.wing.generator.riser_length: must be > 0"},
      {"riser_length: 0.4", "riser_length: 1e308", "parameter 'riser_length' is 1e+308; valid: (0, 30]"},
      {"riser_length: 0.4", "line_length: 1.0e300",
       "meshes.wing.generator.line_length: is 1.0e300; valid: (0, 10]"},
      {"cells: 4", "cells: 4, span: 1.0e300", "meshes.wing.generator.span: is 1.0e300; valid: (0, 1000]"},
      {"cells: 4", "cells: 4, span: 1.0e-320",
       "meshes.wing.generator.span: is 1.0e-320; valid: (0, 1000] (and "
       "at least 2.2e-308"},
      {"cells: 4", "cells: 4, root_chord: 50", "parameter 'root_chord' is 50; valid: (0, 3]"},
      // bulge with span_divisions 1 gave the same mesh as without.
      {"riser_length: 0.4", "bulge: 0.1", "parameter 'bulge' is 0.1 but has no effect with span_divisions 1"},
      {"riser_length: 0.4", "cascade: 1, cascade_fraction: 0.5",
       "cascade_fraction: has no effect with cascade 1"},
      {"brake_points: 2", "brake_points: 0, toggle_fraction: 0.2",
       "toggle_fraction: has no effect with brake_points 0"},
      {"brake_points: 2", "brake_points: 0, brake_slack: 0.1",
       "parameter 'brake_slack' is 0.1 but has no effect with brake_points 0"},
      // An empty row_trim meant "none" whatever the rows.
      {"riser_length: 0.4", "row_trim: []", "parameter 'row_trim' has 0 entries for 4 rows"},
      // Read as NACA 4415 (2412 here) before.
      {"NACA 2412", "NACA 24-12", "wing.yaml:6:"},
      {"NACA 2412", "NACA -2412", "'NACA -2412' is not a supported NACA section"},
      {"NACA 2412", "NACA 2 412", "'NACA 2 412' is not a supported NACA section"},
      {"NACA 2412", "NACA_2412", "'NACA_2412' is not a supported NACA section"},
  };
  for (const Case& c : cases) {
    const std::string e = withChange(c.from, c.to);
    EXPECT_NE(e.find(c.expected), std::string::npos) << c.to << ": " << e;
    EXPECT_TRUE(e.find("wing.yaml:6:") != std::string::npos || e.find("wing.yaml:7:") != std::string::npos)
        << c.to << ": " << e;  // located: the generator entry or the key
  }
  // The accepted spellings still read, and an unset tip chord is the root chord.
  for (const char* name : {"naca2412", "2412", "NACA  2412", "NACA 23012"})
    EXPECT_EQ(withChange("NACA 2412", name), "no error") << name;
  EXPECT_EQ(withChange("riser_length: 0.4", "tip_chord: 1.0"), "no error");
}

TEST(ParafoilGeometry, UnsetTipChordIsTheRootChordAndZeroIsRefused) {
  ParafoilParams q = untwisted(12, 1);
  const MeshData untapered = buildParafoil(q);
  q.tipChord = q.rootChord;
  EXPECT_EQ(buildParafoil(q).points, untapered.points);
  q.tipChord = 0.0;
  EXPECT_THROW(buildParafoil(q), InputError);
  q.tipChord.reset();
  q.riserLength = 0.0;
  EXPECT_THROW(buildParafoil(q), InputError);
}
