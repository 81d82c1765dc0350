#pragma once
// AirfoilSection: the cross-section of a ram-air canopy in chord units (leading edge at x = 0, trailing edge
// at x = 1, y up), as two surfaces that can be sampled at any chord fraction.
//
// Sources: the NACA 4-digit and 5-digit families from their defining formulas (thickness about a mean camber
// line, offset perpendicular to it), or a coordinate file in Selig's format (name line, then x y pairs from
// the trailing edge over the upper surface and the leading edge back along the lower surface). The trailing
// edge is closed (upper and lower surfaces meet in one point): a canopy's skins are sewn together there, so
// the NACA thickness uses the closed-trailing-edge coefficient −0.1036 instead of −0.1015.
//
// Surfaces are sampled at a chord PARAMETER ξ in [0, 1] (the station along the chord line the point belongs
// to). For a cambered NACA section the point of parameter ξ lies at x = ξ ∓ y_t sin θ, not at x = ξ;
// xOnSurface() finds the parameter of a given x (line attachments sit at chord fractions of x).

#include <array>
#include <filesystem>
#include <string>
#include <vector>

namespace fsi::structure::parafoil {

using Point2 = std::array<double, 2>;

class AirfoilSection {
 public:
  /// "NACA 2412", "naca23012", "0012": 4 or 5 digits. Throws fsi::InputError naming `where` and the
  /// designation when it is not a supported NACA section.
  static AirfoilSection naca(const std::string& designation, const std::string& where);
  /// Selig-format coordinate file. Throws fsi::InputError naming the file and line when a line is not two
  /// numbers, when the curve does not start and end at the trailing edge, does not pass x = 0, or is not a
  /// simple closed curve with the upper surface above the lower one.
  static AirfoilSection seligFile(const std::filesystem::path& file);
  /// The same from text (for tests); `name` stands in for the file name in messages.
  static AirfoilSection seligText(const std::string& text, const std::string& name);

  const std::string& name() const { return name_; }
  /// Point of the upper (lower) surface at chord parameter xi in [0, 1], in chord units.
  Point2 upper(double xi) const { return surface(xi, true); }
  Point2 lower(double xi) const { return surface(xi, false); }
  /// Chord parameter of the point of the upper (lower) surface whose x equals `x` (in [0, 1]).
  double xOnSurface(double x, bool upperSurface) const;
  /// Area enclosed by the section in chord² units (trapezoidal on `samples` points per surface, which
  /// converges to the exact area as samples grow).
  double area(int samples = 2000) const;
  /// Largest distance between the surfaces at one chord parameter (the thickness ratio t/c).
  double thickness() const { return thickness_; }
  /// Multiplies the thickness (distance of each surface from the mean line) by `factor` > 0.
  AirfoilSection scaledThickness(double factor) const;

 private:
  Point2 surface(double xi, bool upperSurface) const;

  enum class Kind { Naca4, Naca5, Table };
  Kind kind_ = Kind::Naca4;
  std::string name_;
  double scale_ = 1.0;  ///< thickness factor
  // NACA 4: max camber m at p, thickness t. NACA 5: camber constants r, k1, k2/k1, design-lift factor.
  double m_ = 0, p_ = 0, t_ = 0, r_ = 0, k1_ = 0, k21_ = 0, lift_ = 1;
  bool reflex_ = false;
  // Table: each surface as x ascending from the leading edge (0) to the trailing edge (1).
  std::vector<Point2> up_, lo_;
  double thickness_ = 0;
};

}  // namespace fsi::structure::parafoil
