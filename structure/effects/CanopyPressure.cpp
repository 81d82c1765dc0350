#include "structure/effects/CanopyPressure.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>

namespace fsi::structure {

namespace {

using Vec3 = std::array<double, 3>;

double dot(const Vec3& a, const Vec3& b) {
  return a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
}

/// The wind relative to the mean velocity of `nodes`.
Vec3 relativeWind(const Vec3& U, const std::vector<int>& nodes, const double* v) {
  Vec3 w = U;
  if (v == nullptr || nodes.empty()) return w;
  for (int k = 0; k < 3; ++k) {
    double s = 0;
    for (int n : nodes) s += v[3 * n + k];
    w[k] -= s / double(nodes.size());
  }
  return w;
}

}  // namespace

double clothThroughFlow(double dp, double density, const ClothPermeability& cloth) {
  if (!cloth.porous() || !(dp > 0)) return 0.0;
  const double qa = cloth.b * density, qb = cloth.a * cloth.viscosity;
  return 2.0 * dp / (qb + std::sqrt(qb * qb + 4.0 * qa * dp));  // the positive root, without cancellation
}

double insidePressure(const CanopyState& s, double density, const CanopyPressureParams& prm) {
  const double q = 0.5 * density * s.speed * s.speed;
  if (!(q > 0)) return 0.0;
  const double floor = -prm.suctionLimit * q;
  // F(p) = p − ½ρ(W² − u_m|u_m|) increases with p (Q_out does, u_m|u_m| does with u_m): its root by
  // bisection on [floor, ceiling].
  auto residual = [&](double p) {
    const double out = s.clothArea * clothThroughFlow(p, density, prm.cloth) +
                       prm.ventDischarge * s.ventArea * std::sqrt(2.0 * std::max(p, 0.0) / density);
    const double flow = s.volumeRate + out;
    if (!(s.mouthArea > 0)) return flow > 0 ? p + 1e300 : p - q;
    const double um = flow / s.mouthArea;
    return p - (q - 0.5 * density * um * std::abs(um));
  };
  if (residual(floor) >= 0) return floor;
  double hi = std::max(q, 1.0);
  while (residual(hi) < 0) hi *= 2.0;  // air pushed out of a shrinking canopy: p_in above q
  double lo = floor;
  for (int it = 0; it < 200 && hi - lo > 1e-14 * std::max(1.0, std::abs(hi)); ++it) {
    const double mid = 0.5 * (lo + hi);
    (residual(mid) < 0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

double projectedRingArea(const std::vector<double>& points, const Vec3& axis) {
  const std::size_t n = points.size() / 3;
  if (n < 3) return 0.0;
  // An orthonormal pair (e1, e2) in the plane normal to the axis.
  const Vec3 t = std::abs(axis[0]) < 0.9 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
  Vec3 e1{t[1] * axis[2] - t[2] * axis[1], t[2] * axis[0] - t[0] * axis[2], t[0] * axis[1] - t[1] * axis[0]};
  const double l = std::sqrt(dot(e1, e1));
  for (double& c : e1) c /= l;
  const Vec3 e2{axis[1] * e1[2] - axis[2] * e1[1], axis[2] * e1[0] - axis[0] * e1[2],
                axis[0] * e1[1] - axis[1] * e1[0]};
  std::vector<double> a(n), b(n);
  double ca = 0, cb = 0;
  for (std::size_t i = 0; i < n; ++i) {
    const Vec3 p{points[3 * i], points[3 * i + 1], points[3 * i + 2]};
    a[i] = dot(p, e1);
    b[i] = dot(p, e2);
    ca += a[i] / double(n);
    cb += b[i] / double(n);
  }
  std::vector<std::size_t> order(n);
  std::iota(order.begin(), order.end(), 0);
  std::sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) {
    return std::atan2(b[i] - cb, a[i] - ca) < std::atan2(b[j] - cb, a[j] - ca);
  });
  double twice = 0;
  for (std::size_t k = 0; k < n; ++k) {
    const std::size_t i = order[k], j = order[(k + 1) % n];
    twice += (a[i] - ca) * (b[j] - cb) - (a[j] - ca) * (b[i] - cb);
  }
  return 0.5 * std::abs(twice);
}

CanopyPressureLoad::CanopyPressureLoad(std::string label, std::vector<int> triangleConn,
                                       std::vector<int> mouth, std::vector<int> vent, AirStream air,
                                       CanopyPressureParams params)
    : label_(std::move(label)),
      conn_(std::move(triangleConn)),
      mouth_(std::move(mouth)),
      vent_(std::move(vent)),
      air_(std::move(air)),
      prm_(params) {
  canopyNodes_ = conn_;
  std::sort(canopyNodes_.begin(), canopyNodes_.end());
  canopyNodes_.erase(std::unique(canopyNodes_.begin(), canopyNodes_.end()), canopyNodes_.end());
}

CanopyState CanopyPressureLoad::state(const double* x, const double* v, double time) const {
  const double f = air_.function(time);
  const Vec3 U{f * air_.wind[0], f * air_.wind[1], f * air_.wind[2]};
  const Vec3 W = relativeWind(U, canopyNodes_, v);
  CanopyState s;
  s.speed = std::sqrt(dot(W, W));
  const Vec3 axis = s.speed > 0 ? Vec3{W[0] / s.speed, W[1] / s.speed, W[2] / s.speed} : Vec3{0, 0, 1};
  auto ring = [&](const std::vector<int>& nodes) {
    std::vector<double> p;
    for (int n : nodes)
      for (int k = 0; k < 3; ++k) p.push_back(x[3 * n + k]);
    return projectedRingArea(p, axis);
  };
  s.mouthArea = ring(mouth_);
  s.ventArea = vent_.empty() ? 0.0 : ring(vent_);
  const Vec3 V{U[0] - W[0], U[1] - W[1], U[2] - W[2]};  // the canopy's mean velocity
  for (std::size_t e = 0; 3 * e < conn_.size(); ++e) {
    const int a = conn_[3 * e], b = conn_[3 * e + 1], c = conn_[3 * e + 2];
    Vec3 d21, d31, rel{};
    for (int k = 0; k < 3; ++k) {
      d21[k] = x[3 * b + k] - x[3 * a + k];
      d31[k] = x[3 * c + k] - x[3 * a + k];
      if (v) rel[k] = (v[3 * a + k] + v[3 * b + k] + v[3 * c + k]) / 3.0 - V[k];
    }
    const Vec3 an{d21[1] * d31[2] - d21[2] * d31[1], d21[2] * d31[0] - d21[0] * d31[2],
                  d21[0] * d31[1] - d21[1] * d31[0]};  // 2 A n̂
    s.clothArea += 0.5 * std::sqrt(dot(an, an));
    s.volumeRate += 0.5 * dot(rel, an);
  }
  return s;
}

void CanopyPressureLoad::addForces(ForceContext& ctx) const {
  const double* x = ctx.x;
  const double* v = ctx.v;
  const CanopyState s = state(x, v, ctx.time);
  const double q = 0.5 * air_.density * s.speed * s.speed;
  const double pin = insidePressure(s, air_.density, prm_);
  const double f = air_.function(ctx.time);
  const Vec3 U{f * air_.wind[0], f * air_.wind[1], f * air_.wind[2]};
  double* fe = ctx.fext;
  for (std::size_t e = 0; 3 * e < conn_.size(); ++e) {
    const int a = conn_[3 * e], b = conn_[3 * e + 1], c = conn_[3 * e + 2];
    Vec3 d21, d31, w;
    for (int k = 0; k < 3; ++k) {
      d21[k] = x[3 * b + k] - x[3 * a + k];
      d31[k] = x[3 * c + k] - x[3 * a + k];
      w[k] = U[k] - (v ? (v[3 * a + k] + v[3 * b + k] + v[3 * c + k]) / 3.0 : 0.0);
    }
    const Vec3 an{d21[1] * d31[2] - d21[2] * d31[1], d21[2] * d31[0] - d21[0] * d31[2],
                  d21[0] * d31[1] - d21[1] * d31[0]};
    const double twiceArea = std::sqrt(dot(an, an));
    if (!(twiceArea > 0)) continue;
    const Vec3 inward{-an[0] / twiceArea, -an[1] / twiceArea, -an[2] / twiceArea};
    // Outside: the impact law where the wind meets the outer face (its normal −n̂ facing the wind), else the
    // wake's suction.
    const double outside =
        dot(inward, w) > 0
            ? impactPressure(inward, w, air_.density, prm_.cpMax, prm_.exponent, prm_.cloth).pressure
            : -prm_.wakeCp * q;
    const double sixth = ctx.loadFactor * (pin - outside) / 6.0;  // p A n̂ / 3 = p (d21 × d31) / 6
    if (sixth == 0.0) continue;
    for (int k = 0; k < 3; ++k) {
      fe[3 * a + k] += sixth * an[k];
      fe[3 * b + k] += sixth * an[k];
      fe[3 * c + k] += sixth * an[k];
    }
  }
}

}  // namespace fsi::structure
