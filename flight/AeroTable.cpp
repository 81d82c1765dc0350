#include "flight/AeroTable.hpp"

#include <fmt/format.h>

#include <cmath>

#include "structure/model/Error.hpp"

namespace fsi::flight {

namespace {

double interpolate(const std::vector<double>& x, const std::vector<double>& y, double at) {
  if (at <= x.front()) return y.front();
  if (at >= x.back()) return y.back();
  std::size_t i = 1;
  while (x[i] < at) ++i;
  const double t = (at - x[i - 1]) / (x[i] - x[i - 1]);
  return (1 - t) * y[i - 1] + t * y[i];
}

}  // namespace

void AeroTable::check(const std::string& where) const {
  if (alpha.empty()) throw InputError(fmt::format("{}: the table 'alpha' is empty", where));
  for (const auto& [name, column] : {std::pair{"CL", &CL}, std::pair{"CD", &CD}, std::pair{"Cm", &Cm}}) {
    if (column->size() != alpha.size())
      throw InputError(
          fmt::format("{}: '{}' has {} values, 'alpha' {}", where, name, column->size(), alpha.size()));
    for (double v : *column)
      if (!std::isfinite(v))
        throw InputError(fmt::format("{}: '{}' has a value that is not a number", where, name));
  }
  for (std::size_t i = 0; i < alpha.size(); ++i) {
    if (!std::isfinite(alpha[i]))
      throw InputError(fmt::format("{}: 'alpha' has a value that is not a number", where));
    if (i > 0 && !(alpha[i] > alpha[i - 1]))
      throw InputError(fmt::format("{}: 'alpha' must increase strictly (entry {})", where, i + 1));
  }
  for (std::size_t i = 0; i < CD.size(); ++i)
    if (CD[i] < 0) throw InputError(fmt::format("{}: 'CD' entry {} is negative", where, i + 1));
  if (!(area > 0 && span > 0 && chord > 0))
    throw InputError(fmt::format("{}: the reference area, span and chord must be positive", where));
}

AeroCoefficients AeroTable::at(double a, double beta, double ds, double da, double p, double q, double r,
                               double v) const {
  AeroCoefficients c;
  const double hb = v > 0 ? span / (2 * v) : 0.0, hc = v > 0 ? chord / (2 * v) : 0.0;
  c.CL = interpolate(alpha, CL, a) + CL_ds * ds;
  c.CD = interpolate(alpha, CD, a) + CD_ds * ds;
  c.Cm = interpolate(alpha, Cm, a) + Cm_ds * ds + Cm_q * q * hc;
  c.CY = CY_beta * beta + CY_da * da;
  c.Cl = Cl_beta * beta + Cl_p * p * hb + Cl_da * da;
  c.Cn = Cn_beta * beta + Cn_r * r * hb + Cn_da * da;
  return c;
}

}  // namespace fsi::flight
