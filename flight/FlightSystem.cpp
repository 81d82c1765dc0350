#include "flight/FlightSystem.hpp"

#include <cmath>

namespace fsi::flight {

namespace {

/// Aerodynamic force and moment (about the mass centre) of the canopy at the air velocity `va` [body] there.
void canopyLoads(const FlightSystem& s, const Controls& c, const Vec3& canopyPoint, const Vec3& va,
                 const Vec3& rates, Vec3& force, Vec3& moment, FlightReading* reading) {
  const double v = va.norm();
  if (!(v > 1e-9)) return;
  const Vec3 dir = va / v;  // the air's velocity relative to the canopy is −va: the body moves along va
  const double alpha = std::atan2(va.z(), va.x());
  const double beta = std::asin(std::clamp(va.y() / v, -1.0, 1.0));
  const double ds = 0.5 * (c.brakeLeft + c.brakeRight), da = c.brakeRight - c.brakeLeft;
  const AeroCoefficients k = s.aero.at(alpha, beta, ds, da, rates.x(), rates.y(), rates.z(), v);
  const double qS = 0.5 * s.airDensity * v * v * s.aero.area;
  // Wind axes: drag against the motion, lift perpendicular to it in the plane of the motion and the body's
  // y axis (up for level flight), side force completing them.
  const Vec3 lift = Vec3::UnitY().cross(dir).normalized();
  const Vec3 side = dir.cross(lift);
  const Vec3 f =
      qS * (-k.CD * dir + k.CL * lift + k.CY * side) - 0.5 * s.airDensity * s.lineDragArea * v * va;
  const Vec3 m(qS * s.aero.span * k.Cl, qS * s.aero.chord * k.Cm, qS * s.aero.span * k.Cn);
  force += f;
  moment += m + canopyPoint.cross(f);
  if (reading) {
    reading->airspeed = v;
    reading->alpha = alpha;
    reading->beta = beta;
    reading->coefficients = k;
  }
}

}  // namespace

StateRate stateRate(const FlightSystem& s, const Wind& wind, const Controls& c, double time,
                    const FlightState& x, FlightReading* reading) {
  const Mat3 rot = x.attitude.toRotationMatrix();  // body -> world
  const Vec3& v = x.velocity;
  const Vec3& w = x.rates;
  const Vec3 windBody = rot.transpose() * wind.at(x.position, time);
  Vec3 force = rot.transpose() * Vec3(0, 0, s.mass * s.gravity);
  Vec3 moment = Vec3::Zero();
  if (s.aerodynamics) {
    const Vec3 canopy = c.incidence == 0
                            ? s.canopyPoint
                            : Vec3(Eigen::AngleAxisd(c.incidence, Vec3::UnitY()) * s.canopyPoint);
    canopyLoads(s, c, canopy, v + w.cross(canopy) - windBody, w, force, moment, reading);
    const Vec3 vp = v + w.cross(s.payloadPoint) - windBody;
    const Vec3 fp = -0.5 * s.airDensity * s.payloadDragArea * vp.norm() * vp;
    force += fp;
    moment += s.payloadPoint.cross(fp);
  }
  if (reading) {
    reading->aeroForce = force - rot.transpose() * Vec3(0, 0, s.mass * s.gravity);
    reading->force = force;
    reading->moment = moment;
  }
  const Vec3 va = v - windBody;
  const Vec3 A = s.addedMass;
  const Vec3 Ava = A.cwiseProduct(va);
  const Vec3 trans = force - s.mass * w.cross(v) - A.cwiseProduct(w.cross(windBody)) - w.cross(Ava);
  const Mat3 J = s.inertia + Mat3(s.addedInertia.asDiagonal());
  const Vec3 rot_rhs = moment - w.cross(J * w) - (s.munkMoment ? Vec3(va.cross(Ava)) : Vec3::Zero());
  StateRate r;
  r.velocity = (Vec3::Constant(s.mass) + A).cwiseInverse().cwiseProduct(trans);
  r.rates = J.ldlt().solve(rot_rhs);
  r.position = rot * v;
  const Quat dq = x.attitude * Quat(0, w.x(), w.y(), w.z());
  r.attitude = {0.5 * dq.w(), 0.5 * dq.x(), 0.5 * dq.y(), 0.5 * dq.z()};
  return r;
}

namespace {

FlightState advance(const FlightState& x, const StateRate& r, double h) {
  FlightState y;
  y.position = x.position + h * r.position;
  y.velocity = x.velocity + h * r.velocity;
  y.rates = x.rates + h * r.rates;
  y.attitude = Quat(x.attitude.w() + h * r.attitude[0], x.attitude.x() + h * r.attitude[1],
                    x.attitude.y() + h * r.attitude[2], x.attitude.z() + h * r.attitude[3]);
  return y;
}

}  // namespace

FlightState rungeKuttaStep(const FlightSystem& s, const Wind& wind, const Controls& c, double t, double dt,
                           const FlightState& x) {
  const StateRate k1 = stateRate(s, wind, c, t, x);
  const StateRate k2 = stateRate(s, wind, c, t + 0.5 * dt, advance(x, k1, 0.5 * dt));
  const StateRate k3 = stateRate(s, wind, c, t + 0.5 * dt, advance(x, k2, 0.5 * dt));
  const StateRate k4 = stateRate(s, wind, c, t + dt, advance(x, k3, dt));
  StateRate sum;
  sum.position = (k1.position + 2 * k2.position + 2 * k3.position + k4.position) / 6;
  sum.velocity = (k1.velocity + 2 * k2.velocity + 2 * k3.velocity + k4.velocity) / 6;
  sum.rates = (k1.rates + 2 * k2.rates + 2 * k3.rates + k4.rates) / 6;
  for (int i = 0; i < 4; ++i)
    sum.attitude[i] = (k1.attitude[i] + 2 * k2.attitude[i] + 2 * k3.attitude[i] + k4.attitude[i]) / 6;
  FlightState y = advance(x, sum, dt);
  y.attitude.normalize();
  return y;
}

double mechanicalEnergy(const FlightSystem& s, const FlightState& x) {
  const Vec3 m = Vec3::Constant(s.mass) + s.addedMass;
  const Mat3 J = s.inertia + Mat3(s.addedInertia.asDiagonal());
  return 0.5 * x.velocity.dot(m.cwiseProduct(x.velocity)) + 0.5 * x.rates.dot(J * x.rates) -
         s.mass * s.gravity * x.position.z();
}

}  // namespace fsi::flight
