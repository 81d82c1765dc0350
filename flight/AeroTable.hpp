#pragma once
// AeroTable: the aerodynamic coefficients of the parafoil canopy, the form in which the coupled runs deliver
// them. Longitudinal coefficients are tables in the angle of attack α (piecewise linear, constant beyond the
// ends) at zero brake; the controls and the lateral motion enter as derivatives (per radian, per unit brake):
//
//   CL = CL(α) + CL_δs δs          CD = CD(α) + CD_δs δs          Cm = Cm(α) + Cm_δs δs + Cm_q q̂
//   CY = CY_β β + CY_δa δa         Cl = Cl_β β + Cl_p p̂ + Cl_δa δa      Cn = Cn_β β + Cn_r r̂ + Cn_δa δa
//
// with the symmetric brake δs = (δl + δr)/2 and the differential brake δa = δr − δl (0 … 1 each: a fraction
// of the full brake travel), the non-dimensional rates p̂ = p b/(2V), q̂ = q c/(2V), r̂ = r b/(2V). Reference:
// area S, span b, chord c; forces and moments about the canopy's reference point. Sign conventions of
// flight mechanics: Cm > 0 nose up, Cl > 0 right wing down, Cn > 0 nose right; a right brake (δa > 0) makes
// drag on the right: Cn_δa > 0 turns right.

#include <string>
#include <vector>

namespace fsi::flight {

struct AeroCoefficients {
  double CL = 0, CD = 0, CY = 0, Cl = 0, Cm = 0, Cn = 0;
};

struct AeroTable {
  // Longitudinal tables at zero brake.
  std::vector<double> alpha;  ///< [rad], strictly increasing, at least one point
  std::vector<double> CL, CD, Cm;
  // Control and rate derivatives.
  double CL_ds = 0, CD_ds = 0, Cm_ds = 0;        ///< per unit symmetric brake
  double Cm_q = 0;                               ///< per q̂
  double CY_beta = 0, Cl_beta = 0, Cn_beta = 0;  ///< per radian of sideslip
  double Cl_p = 0, Cn_r = 0;                     // per p̂, r̂
  double CY_da = 0, Cl_da = 0, Cn_da = 0;        ///< per unit differential brake
  // Reference geometry.
  double area = 1, span = 1, chord = 1;  ///< S [m²], b [m], c [m]

  /// Throws fsi::InputError (naming `where` and the entry) for tables that are not usable.
  void check(const std::string& where) const;
  /// The coefficients at angle of attack α and sideslip β [rad], brakes, rates [rad/s] and airspeed V [m/s].
  AeroCoefficients at(double alpha, double beta, double symmetricBrake, double differentialBrake, double p,
                      double q, double r, double airspeed) const;
};

}  // namespace fsi::flight
