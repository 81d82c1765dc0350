#include "structure/parafoil/AirfoilSection.hpp"

#include <fmt/format.h>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <fstream>
#include <sstream>

#include "structure/io/TextNumbers.hpp"
#include "structure/model/Error.hpp"

namespace fsi::structure::parafoil {

namespace {

// Half-thickness of the NACA 4/5-digit families for thickness ratio t, closed trailing edge (see header).
double halfThickness(double x, double t) {
  return 5.0 * t *
         (0.2969 * std::sqrt(x) - 0.1260 * x - 0.3516 * x * x + 0.2843 * x * x * x - 0.1036 * x * x * x * x);
}

// Mean-line constants of the 5-digit family for a design lift coefficient of 0.3 (L = 2), by the position
// digit P = 1..5: r (where the cubic front part ends), k1, and for the reflexed lines (Q = 1) k2/k1. From the
// NACA report defining the family (Jacobs, Pinkerton; NACA Report 537 and its later reflexed extension).
struct Camber5 {
  double r, k1, k21;
};
constexpr Camber5 kStandard[5] = {
    {0.0580, 361.400, 0}, {0.1260, 51.640, 0}, {0.2025, 15.957, 0}, {0.2900, 6.643, 0}, {0.3910, 3.230, 0}};
constexpr Camber5 kReflex[5] = {{0, 0, 0},
                                {0.1300, 51.990, 0.000764},
                                {0.2170, 15.793, 0.00677},
                                {0.3180, 6.520, 0.0303},
                                {0.4410, 3.191, 0.1355}};

[[noreturn]] void badNaca(const std::string& where, const std::string& d, const std::string& why) {
  throw InputError(fmt::format("{}: '{}' is not a supported NACA section: {}", where, d, why));
}

double lerpY(const std::vector<Point2>& s, double x) {
  // s is sorted by x ascending (from the leading edge).
  if (x <= s.front()[0]) return s.front()[1];
  if (x >= s.back()[0]) return s.back()[1];
  const auto it = std::upper_bound(s.begin(), s.end(), x, [](double v, const Point2& p) { return v < p[0]; });
  const Point2& b = *it;
  const Point2& a = *(it - 1);
  const double w = (x - a[0]) / (b[0] - a[0]);
  return a[1] + w * (b[1] - a[1]);
}

}  // namespace

AirfoilSection AirfoilSection::naca(const std::string& designation, const std::string& where) {
  // Exactly "NACA" (any case), optional spaces, then 4 or 5 digits in one piece; or the digits alone. Signs,
  // dashes and spaces inside the digits are refused: "NACA -4415" or "NACA 44-15" is not a NACA section.
  std::string rest = designation;
  for (char& c : rest) c = char(std::tolower(static_cast<unsigned char>(c)));
  if (rest.rfind("naca", 0) == 0) rest = rest.substr(4);
  const std::size_t first = rest.find_first_not_of(' ');
  const std::string digits = first == std::string::npos ? std::string() : rest.substr(first);
  const bool allDigits = !digits.empty() && std::all_of(digits.begin(), digits.end(), [](char c) {
    return std::isdigit(static_cast<unsigned char>(c)) != 0;
  });
  if (!allDigits || (digits.size() != 4 && digits.size() != 5))
    badNaca(where, designation,
            "expected 'NACA' and 4 or 5 digits in one piece (NACA 4415, naca23012, 0012), nothing else");
  AirfoilSection s;
  s.name_ = "NACA " + digits;
  auto d = [&](int i) { return digits[i] - '0'; };
  if (digits.size() == 4) {
    s.kind_ = Kind::Naca4;
    s.m_ = d(0) / 100.0;
    s.p_ = d(1) / 10.0;
    s.t_ = (10 * d(2) + d(3)) / 100.0;
    if ((s.m_ > 0) != (s.p_ > 0))
      badNaca(where, designation, "camber and its position must both be zero or both be non-zero");
  } else if (digits.size() == 5) {
    s.kind_ = Kind::Naca5;
    const int L = d(0), P = d(1), Q = d(2);
    if (L < 1) badNaca(where, designation, "the first digit (design lift, 0.15 per unit) must be 1..9");
    if (P < 1 || P > 5) badNaca(where, designation, "the second digit (camber position) must be 1..5");
    if (Q > 1) badNaca(where, designation, "the third digit must be 0 (standard) or 1 (reflexed mean line)");
    if (Q == 1 && P == 1) badNaca(where, designation, "there is no reflexed mean line with position digit 1");
    const Camber5 c = Q == 0 ? kStandard[P - 1] : kReflex[P - 1];
    s.r_ = c.r;
    s.k1_ = c.k1;
    s.k21_ = c.k21;
    s.reflex_ = Q == 1;
    s.lift_ = L / 2.0;
    s.t_ = (10 * d(3) + d(4)) / 100.0;
  } else {
    badNaca(where, designation, "expected 4 or 5 digits");
  }
  if (!(s.t_ > 0)) badNaca(where, designation, "the thickness (last two digits) must not be zero");
  // 2 y_t is largest near x = 0.3, where it equals t to 0.03 %; the sampled maximum is what the part sees.
  double tmax = 0;
  for (int i = 0; i <= 2000; ++i) tmax = std::max(tmax, 2.0 * halfThickness(i / 2000.0, s.t_));
  s.thickness_ = tmax;
  return s;
}

AirfoilSection AirfoilSection::seligFile(const std::filesystem::path& file) {
  std::ifstream in(file, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot open the section file", file.string()));
  std::ostringstream ss;
  ss << in.rdbuf();
  return seligText(ss.str(), file.string());
}

AirfoilSection AirfoilSection::seligText(const std::string& text, const std::string& name) {
  std::vector<Point2> pts;
  std::vector<int> lines;
  std::istringstream in(text);
  std::string line;
  int lineNo = 0;
  bool header = true;
  while (std::getline(in, line)) {
    ++lineNo;
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.find_first_not_of(" \t") == std::string::npos) continue;
    if (header) {  // the first non-blank line names the section
      header = false;
      continue;
    }
    std::istringstream ls(line);
    std::string a, b, extra;
    ls >> a >> b;
    if (ls >> extra)
      throw InputError(
          fmt::format("{}:{}: expected two numbers (x y), found more: '{}'", name, lineNo, line));
    double x = 0, y = 0;
    if (parseReal(a, x) != NumberStatus::Ok || parseReal(b, y) != NumberStatus::Ok)
      throw InputError(
          fmt::format("{}:{}: expected two finite numbers (x y), found '{}'", name, lineNo, line));
    pts.push_back({x, y});
    lines.push_back(lineNo);
  }
  if (pts.size() < 5)
    throw InputError(
        fmt::format("{}: a section needs at least 5 points (Selig format: a name line, then x y pairs from "
                    "the trailing edge over the upper surface to the leading edge and back), found {}",
                    name, pts.size()));
  if (pts[0][0] >= 2 && pts[0][1] >= 2 && pts[0][0] == std::floor(pts[0][0]) &&
      pts[0][1] == std::floor(pts[0][1]))
    throw InputError(
        fmt::format("{}:{}: this looks like Lednicer's format (point counts first); give the "
                    "coordinates in Selig's format",
                    name, lines[0]));
  // Leading edge: the point farthest from the trailing edge (the mid-point of the first and last points).
  const Point2 te{0.5 * (pts.front()[0] + pts.back()[0]), 0.5 * (pts.front()[1] + pts.back()[1])};
  std::size_t le = 0;
  double far = -1;
  for (std::size_t i = 0; i < pts.size(); ++i) {
    const double d = std::hypot(pts[i][0] - te[0], pts[i][1] - te[1]);
    if (d > far) far = d, le = i;
  }
  const double chord = far;
  const double gap = std::hypot(pts.front()[0] - pts.back()[0], pts.front()[1] - pts.back()[1]);
  if (!(chord > 0) || gap > 0.02 * chord)
    throw InputError(
        fmt::format("{}: not a closed curve: the first point (line {}) and the last (line {}) are "
                    "{:.4g} chords apart; they must both be the trailing edge (a gap of at most "
                    "0.02 chord is closed at its mid-point)",
                    name, lines.front(), lines.back(), chord > 0 ? gap / chord : gap));
  if (le == 0 || le == pts.size() - 1)
    throw InputError(
        fmt::format("{}: the points do not go round the section from the trailing edge over the "
                    "leading edge and back",
                    name));
  // Chord axis from the leading edge to the trailing edge: rotate and scale onto (0,0)-(1,0).
  const double cx = (te[0] - pts[le][0]) / chord, cy = (te[1] - pts[le][1]) / chord;
  auto local = [&](const Point2& p) {
    const double dx = p[0] - pts[le][0], dy = p[1] - pts[le][1];
    return Point2{(dx * cx + dy * cy) / chord, (-dx * cy + dy * cx) / chord};
  };
  AirfoilSection s;
  s.kind_ = Kind::Table;
  s.name_ = name;
  std::vector<Point2> a, b;
  for (std::size_t i = le + 1; i-- > 0;) a.push_back(local(pts[i]));  // leading edge -> trailing edge
  for (std::size_t i = le; i < pts.size(); ++i) b.push_back(local(pts[i]));
  a.back() = b.back() = Point2{1.0, 0.0};  // the trailing edge, closed
  // The surface the points reach first from the trailing edge may be either one: the one above is the upper.
  const double ya = lerpY(a, 0.3), yb = lerpY(b, 0.3);
  if (ya < yb) std::swap(a, b);
  auto monotone = [&](const std::vector<Point2>& surf, bool first) {
    for (std::size_t i = 1; i < surf.size(); ++i)
      if (!(surf[i][0] > surf[i - 1][0])) {
        // Map back to the file's line for the message.
        const std::size_t k = first == (ya >= yb) ? le - i : le + i;
        throw InputError(fmt::format(
            "{}:{}: x must grow from the leading edge to the trailing edge along each surface (a simple "
            "closed curve, no loops); this point goes back",
            name, lines[std::min(k, lines.size() - 1)]));
      }
  };
  monotone(a, true);
  monotone(b, false);
  s.up_ = std::move(a);
  s.lo_ = std::move(b);
  for (int i = 1; i < 1000; ++i) {
    const double x = i / 1000.0;
    const double d = lerpY(s.up_, x) - lerpY(s.lo_, x);
    if (!(d > 0))
      throw InputError(
          fmt::format("{}: the upper and lower surfaces cross at x/c = {:.3f}: not a simple "
                      "closed curve",
                      name, x));
    s.thickness_ = std::max(s.thickness_, d);
  }
  return s;
}

Point2 AirfoilSection::surface(double xi, bool up) const {
  xi = std::clamp(xi, 0.0, 1.0);
  if (kind_ == Kind::Table) return {xi, lerpY(up ? up_ : lo_, xi)};
  double yc = 0, dyc = 0;
  if (kind_ == Kind::Naca4) {
    if (m_ > 0) {
      if (xi < p_) {
        yc = m_ / (p_ * p_) * (2 * p_ * xi - xi * xi);
        dyc = 2 * m_ / (p_ * p_) * (p_ - xi);
      } else {
        yc = m_ / ((1 - p_) * (1 - p_)) * ((1 - 2 * p_) + 2 * p_ * xi - xi * xi);
        dyc = 2 * m_ / ((1 - p_) * (1 - p_)) * (p_ - xi);
      }
    }
  } else if (!reflex_) {
    const double r = r_, k = k1_ / 6.0 * lift_;
    if (xi < r) {
      yc = k * (xi * xi * xi - 3 * r * xi * xi + r * r * (3 - r) * xi);
      dyc = k * (3 * xi * xi - 6 * r * xi + r * r * (3 - r));
    } else {
      yc = k * r * r * r * (1 - xi);
      dyc = -k * r * r * r;
    }
  } else {
    const double r = r_, k = k1_ / 6.0 * lift_, q = k21_, c = (1 - r) * (1 - r) * (1 - r);
    if (xi < r) {
      yc = k * ((xi - r) * (xi - r) * (xi - r) - q * c * xi - r * r * r * xi + r * r * r);
      dyc = k * (3 * (xi - r) * (xi - r) - q * c - r * r * r);
    } else {
      yc = k * (q * (xi - r) * (xi - r) * (xi - r) - q * c * xi - r * r * r * xi + r * r * r);
      dyc = k * (3 * q * (xi - r) * (xi - r) - q * c - r * r * r);
    }
  }
  const double yt = scale_ * halfThickness(xi, t_);
  const double th = std::atan(dyc);
  const double sgn = up ? 1.0 : -1.0;
  return {xi - sgn * yt * std::sin(th), yc + sgn * yt * std::cos(th)};
}

double AirfoilSection::xOnSurface(double x, bool up) const {
  if (kind_ == Kind::Table) return std::clamp(x, 0.0, 1.0);
  // x(ξ) is monotone on each surface for the thin cambers of these families; bisection is robust.
  double a = 0, b = 1;
  for (int it = 0; it < 80; ++it) {
    const double m = 0.5 * (a + b);
    (surface(m, up)[0] < x ? a : b) = m;
  }
  return 0.5 * (a + b);
}

double AirfoilSection::area(int samples) const {
  // Shoelace over the closed polygon: upper from the trailing edge to the leading edge, lower back; cosine
  // spacing resolves the leading-edge radius.
  double twice = 0;
  Point2 prev = upper(1.0);
  auto add = [&](const Point2& p) {
    twice += prev[0] * p[1] - p[0] * prev[1];
    prev = p;
  };
  const double pi = std::acos(-1.0);
  for (int i = samples - 1; i >= 0; --i) add(upper(0.5 * (1 - std::cos(pi * i / samples))));
  for (int i = 1; i <= samples; ++i) add(lower(0.5 * (1 - std::cos(pi * i / samples))));
  return 0.5 * std::abs(twice);
}

AirfoilSection AirfoilSection::scaledThickness(double factor) const {
  AirfoilSection s = *this;
  if (kind_ != Kind::Table) {
    s.scale_ *= factor;
    s.thickness_ *= factor;
    return s;
  }
  std::vector<double> xs;
  for (const auto& p : up_) xs.push_back(p[0]);
  for (const auto& p : lo_) xs.push_back(p[0]);
  std::sort(xs.begin(), xs.end());
  xs.erase(std::unique(xs.begin(), xs.end()), xs.end());
  s.up_.clear();
  s.lo_.clear();
  for (double x : xs) {
    const double yu = lerpY(up_, x), yl = lerpY(lo_, x), ym = 0.5 * (yu + yl);
    s.up_.push_back({x, ym + factor * (yu - ym)});
    s.lo_.push_back({x, ym + factor * (yl - ym)});
  }
  s.thickness_ *= factor;
  return s;
}

}  // namespace fsi::structure::parafoil
