#include "structure/effects/AerodynamicDrag.hpp"

#include <cmath>

namespace fsi::structure {

LineDrag::LineDrag(std::string label, std::vector<int> lineConn, double diameter, double dragCoefficient,
                   AirStream air)
    : label_(std::move(label)),
      conn_(std::move(lineConn)),
      halfRhoCdD_(0.5 * air.density * dragCoefficient * diameter),
      air_(std::move(air)) {}

void LineDrag::addForces(ForceContext& ctx) const {
  // The load factor (incremental loading) scales the force, not the wind: drag goes with U².
  const double s = air_.function(ctx.time);
  const double U[3] = {s * air_.wind[0], s * air_.wind[1], s * air_.wind[2]};
  const double* __restrict x = ctx.x;
  const double* __restrict v = ctx.v;
  double* __restrict f = ctx.fext;
  const int ne = int(conn_.size() / 2);
  for (int e = 0; e < ne; ++e) {
    const int i = conn_[2 * e], j = conn_[2 * e + 1];
    double d[3], w[3];
    for (int k = 0; k < 3; ++k) {
      d[k] = x[3 * j + k] - x[3 * i + k];
      w[k] = U[k] - (v ? 0.5 * (v[3 * i + k] + v[3 * j + k]) : 0.0);  // relative wind at the mid-point
    }
    const double L2 = d[0] * d[0] + d[1] * d[1] + d[2] * d[2];
    if (!(L2 > 0)) continue;
    const double L = std::sqrt(L2);
    const double wt = (w[0] * d[0] + w[1] * d[1] + w[2] * d[2]) / L2;  // axial part, per unit of d
    double wn[3];
    for (int k = 0; k < 3; ++k) wn[k] = w[k] - wt * d[k];
    const double un = std::sqrt(wn[0] * wn[0] + wn[1] * wn[1] + wn[2] * wn[2]);
    const double c = 0.5 * ctx.loadFactor * halfRhoCdD_ * un * L;  // half of the element's force to each node
    for (int k = 0; k < 3; ++k) {
      f[3 * i + k] += c * wn[k];
      f[3 * j + k] += c * wn[k];
    }
  }
}

BodyDrag::BodyDrag(std::string label, std::vector<int> nodes, double dragArea, AirStream air)
    : label_(std::move(label)),
      nodes_(std::move(nodes)),
      halfRhoCdA_(0.5 * air.density * dragArea),
      air_(std::move(air)) {}

void BodyDrag::addForces(ForceContext& ctx) const {
  const double s = air_.function(ctx.time);
  for (int n : nodes_) {
    double w[3];
    for (int k = 0; k < 3; ++k) w[k] = s * air_.wind[k] - (ctx.v ? ctx.v[3 * n + k] : 0.0);
    const double speed = std::sqrt(w[0] * w[0] + w[1] * w[1] + w[2] * w[2]);
    for (int k = 0; k < 3; ++k) ctx.fext[3 * n + k] += ctx.loadFactor * halfRhoCdA_ * speed * w[k];
  }
}

}  // namespace fsi::structure
