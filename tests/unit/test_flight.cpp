// The flight model (flight/): the rigid parafoil-payload system's equations of motion against closed forms —
// energy of the Kirchhoff equations with apparent mass, the integrator's 4th order, a torque-free spin, the
// analytic steady glide (with payload and line drag) and its drift in a steady wind.

#include <gtest/gtest.h>

#include <cmath>
#include <vector>

#include "flight/FlightSystem.hpp"
#include "flight/GlideSlope.hpp"
#include "structure/model/Error.hpp"

namespace fsi::flight {
namespace {

FlightSystem tumbler() {
  FlightSystem s;
  s.mass = 80;
  s.inertia << 60, 2, -5, 2, 45, 1, -5, 1, 30;
  s.addedMass = Vec3(3, 25, 40);
  s.addedInertia = Vec3(10, 4, 2);
  s.aerodynamics = false;
  return s;
}

FlightState moving() {
  FlightState x;
  x.position = Vec3(0, 0, -500);
  x.velocity = Vec3(10, -2, 3);
  x.rates = Vec3(0.4, -0.7, 0.25);
  x.attitude = Quat(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()));
  return x;
}

FlightState integrate(const FlightSystem& s, const Wind& wind, FlightState x, double end, double dt) {
  const int n = int(std::lround(end / dt));
  for (int i = 0; i < n; ++i) x = rungeKuttaStep(s, wind, Controls{}, i * dt, dt, x);
  return x;
}

TEST(Flight, KirchhoffEquationsConserveEnergyWithApparentMass) {
  // The continuous equations conserve the energy exactly; RK4's error in it falls at 4th order.
  const FlightSystem s = tumbler();
  const FlightState x0 = moving();
  const double e0 = mechanicalEnergy(s, x0);
  std::vector<double> err;
  for (double dt : {2e-3, 1e-3, 5e-4}) {
    const FlightState x = integrate(s, Wind{}, x0, 3.0, dt);
    err.push_back(std::abs(mechanicalEnergy(s, x) / e0 - 1));
    EXPECT_GT(x.position.z(), x0.position.z()) << "it falls (z is down)";
  }
  EXPECT_LT(err.back(), 1e-9);
  EXPECT_NEAR(std::log2(err[0] / err[1]), 4.0, 0.5);
  EXPECT_NEAR(std::log2(err[1] / err[2]), 4.0, 0.5);
  // The apparent mass does something (the Munk moment turns the body).
  FlightSystem plain = s;
  plain.addedMass = Vec3::Zero();
  EXPECT_GT(
      (integrate(plain, Wind{}, x0, 1.0, 1e-3).rates - integrate(s, Wind{}, x0, 1.0, 1e-3).rates).norm(),
      1e-3);
}

TEST(Flight, RungeKuttaIsFourthOrder) {
  const FlightSystem s = tumbler();
  const FlightState ref = integrate(s, Wind{}, moving(), 2.0, 0.02 / 16);
  double last = 0;
  for (double dt : {0.04, 0.02, 0.01}) {
    const FlightState x = integrate(s, Wind{}, moving(), 2.0, dt);
    const double err = (x.rates - ref.rates).norm() + (x.velocity - ref.velocity).norm();
    if (last > 0) {
      EXPECT_NEAR(std::log2(last / err), 4.0, 0.3) << dt;
    }
    last = err;
  }
}

TEST(Flight, TorqueFreeSpinAboutAPrincipalAxisIsARotation) {
  FlightSystem s = tumbler();
  s.inertia = Vec3(60, 45, 30).asDiagonal();
  s.gravity = 0;
  FlightState x;
  x.rates = Vec3(0, 0, 0.8);
  const FlightState y = integrate(s, Wind{}, x, 5.0, 1e-3);
  const Quat expect(Eigen::AngleAxisd(0.8 * 5.0, Vec3::UnitZ()));
  EXPECT_LT(y.attitude.angularDistance(expect), 1e-10);
}

FlightSystem glider() {
  FlightSystem s;
  s.mass = 120;
  s.inertia = Vec3(150, 120, 40).asDiagonal();
  s.aero.alpha = {0.0};
  s.aero.CL = {0.8};
  s.aero.CD = {0.2};
  s.aero.Cm = {0.0};
  s.aero.area = 25;
  s.aero.span = 8;
  s.aero.chord = 3;
  s.payloadDragArea = 0.5;
  s.lineDragArea = 0.3;
  s.addedMass = Vec3::Constant(20);  // isotropic: no Munk moment, so nothing turns the glider
  return s;
}

TEST(Flight, SettlesIntoTheAnalyticSteadyGlide) {
  const FlightSystem s = glider();
  FlightState x;
  x.position = Vec3(0, 0, -1000);
  x.velocity = Vec3(12, 0, 0);
  x = integrate(s, Wind{}, x, 120.0, 0.01);
  // Steady glide: tan(gamma) = CD_system / CL with CD_system = CD + (C_D A)_payload+lines / S, and
  // W = q S sqrt(CL^2 + CD_system^2).
  const double cd = 0.2 + (0.5 + 0.3) / 25, cl = 0.8;
  const Vec3 ground = x.attitude * x.velocity;
  const double gamma = std::atan2(ground.z(), std::hypot(ground.x(), ground.y()));
  EXPECT_NEAR(gamma, std::atan(cd / cl), 1e-8);
  const double v = std::sqrt(2 * s.mass * s.gravity / (s.airDensity * s.aero.area * std::hypot(cl, cd)));
  EXPECT_NEAR(ground.norm(), v, 1e-7 * v);
}

TEST(Flight, SteadyWindCarriesTheGlide) {
  const FlightSystem s = glider();
  Wind wind;
  wind.steady = Vec3(0, -3, 0);  // from the east
  FlightState calm, windy;
  calm.velocity = windy.velocity = Vec3(12, 0, 0);
  calm = integrate(s, Wind{}, calm, 120.0, 0.01);
  windy = integrate(s, wind, windy, 120.0, 0.01);
  const Vec3 gCalm = calm.attitude * calm.velocity, gWindy = windy.attitude * windy.velocity;
  EXPECT_LT((gWindy - gCalm - wind.steady).norm(), 1e-6) << "ground velocity = air velocity + wind";
}

// Pitch period of a glider whose canopy point sits l above the mass centre, after a small pitch-rate kick
// from its steady glide at airspeed V (no apparent mass, constant coefficients: the force does not depend on
// the attitude).
double pitchPeriod(double airspeed) {
  FlightSystem s;
  s.mass = 100;
  s.inertia = Vec3(20, 10, 20).asDiagonal();
  s.aero.alpha = {0.0};
  s.aero.CL = {0.8};
  s.aero.CD = {0.2};
  s.aero.Cm = {0.0};
  s.aero.span = 8;
  s.aero.chord = 3;
  s.aero.area = 2 * s.mass * s.gravity / (s.airDensity * airspeed * airspeed * std::hypot(0.8, 0.2));
  s.canopyPoint = Vec3(0, 0, -1.0);
  FlightState x;
  x.velocity = Vec3(airspeed, 0, 0);
  const double dt = 1e-3;
  x = integrate(s, Wind{}, x, 60.0, dt);
  x.rates.y() += 0.05;
  std::vector<double> downCrossings;
  double prev = x.rates.y(), t = 60.0;
  for (int i = 0; i < 8000; ++i) {
    x = rungeKuttaStep(s, Wind{}, Controls{}, t, dt, x);
    t += dt;
    const double q = x.rates.y();
    if (prev > 0 && q <= 0) downCrossings.push_back(t - dt * q / (q - prev));
    prev = q;
  }
  if (downCrossings.size() < 3) return 0;
  return (downCrossings.back() - downCrossings.front()) / double(downCrossings.size() - 1);
}

TEST(Flight, PendulumModeAboutTheMassCentre) {
  // The aerodynamic force W acts at the canopy point, l above the mass centre; with coefficients that do not
  // depend on the attitude it gives the restoring moment W l sin(theta). When the force does not depend on
  // the canopy point's motion either, the body swings about its mass centre: T = 2 pi sqrt(J / (W l)). The
  // force's dependence on that point's velocity damps the swing by about sqrt(g l) / V of critical: small
  // at 60 m/s (and the pitch period the free limit's to 1 %); at a parafoil's 10-15 m/s the swing is damped
  // within a period and the canopy acts partly as a pivot (T towards 2 pi sqrt((J + m l^2) / (W l))).
  const double J = 10, W = 100 * 9.80665, l = 1.0;
  EXPECT_NEAR(pitchPeriod(60.0) / (2 * M_PI * std::sqrt(J / (W * l))), 1.0, 0.01);
}

TEST(Flight, TablesAreChecked) {
  AeroTable t;
  EXPECT_THROW(t.check("flight.yaml"), InputError);
  t.alpha = {0.0, 0.1, 0.05};
  t.CL = t.CD = t.Cm = {0, 0, 0};
  EXPECT_THROW(t.check("flight.yaml"), InputError);
  t.alpha = {0.0, 0.1, 0.2};
  t.CD = {0.1, -0.1, 0.2};
  EXPECT_THROW(t.check("flight.yaml"), InputError);
  t.CD = {0.1, 0.1, 0.2};
  EXPECT_NO_THROW(t.check("flight.yaml"));
  // Interpolation and clamping.
  t.CL = {0.2, 0.6, 0.8};
  EXPECT_DOUBLE_EQ(t.at(0.05, 0, 0, 0, 0, 0, 0, 10).CL, 0.4);
  EXPECT_DOUBLE_EQ(t.at(-1.0, 0, 0, 0, 0, 0, 0, 10).CL, 0.2);
  EXPECT_DOUBLE_EQ(t.at(1.0, 0, 0, 0, 0, 0, 0, 10).CL, 0.8);
}

// The incidence turns the canopy point about the body's y axis through the mass centre: the state's rate is
// that of the same system with its canopy point turned, and without incidence it is not.
TEST(Flight, IncidenceTurnsTheCanopyPointAboutTheMassCentre) {
  FlightSystem s = glider();
  s.canopyPoint = Vec3(0.3, 0.2, -6);
  s.addedMass = Vec3(1, 2, 8);
  FlightState x = moving();
  const double incidence = 0.07;
  FlightSystem turned = s;
  turned.canopyPoint = Eigen::AngleAxisd(incidence, Vec3::UnitY()) * s.canopyPoint;
  Controls c;
  c.incidence = incidence;
  const StateRate a = stateRate(s, Wind{}, c, 0, x), b = stateRate(turned, Wind{}, Controls{}, 0, x);
  EXPECT_LT((a.rates - b.rates).norm(), 1e-12 * b.rates.norm());
  EXPECT_LT((a.velocity - b.velocity).norm(), 1e-12 * b.velocity.norm());
  EXPECT_GT((stateRate(s, Wind{}, Controls{}, 0, x).rates - b.rates).norm(), 1e-3 * b.rates.norm());
  // Without the Munk moment the rotational rate changes by exactly (J + A_r)^-1 (v_a x A v_a).
  FlightSystem noMunk = turned;
  noMunk.munkMoment = false;
  const Vec3 va = x.velocity, munk = va.cross(Vec3(turned.addedMass.cwiseProduct(va)));
  const Mat3 J = turned.inertia + Mat3(turned.addedInertia.asDiagonal());
  const Vec3 diff = stateRate(noMunk, Wind{}, Controls{}, 0, x).rates - b.rates;
  EXPECT_LT((diff - J.ldlt().solve(munk)).norm(), 1e-10 * diff.norm());
}

// The glide-slope loop: proportional around the trim, clamped, and its integral held while the output sits in
// a limit (anti-windup): after a long saturated stretch a reversed error leaves the limit at once.
TEST(Flight, GlideSlopeLoopIsClampedWithoutWindup) {
  GlideSlopeParams p;
  p.control = "incidence";
  p.gains = {2.0, 0.5, 0.0, 100.0};
  p.trim = 0;
  p.min = -5;
  p.max = 3;
  GlideSlope g(p);
  EXPECT_DOUBLE_EQ(g.update(0.1, 15.0, 14.5), 2.0 * 0.5 + 0.5 * 0.5 * 0.1);
  for (int i = 0; i < 200; ++i) EXPECT_DOUBLE_EQ(g.update(0.1, 20.0, 14.0), 3.0);
  const double back = g.update(0.1, 14.0, 15.0);  // now below the path: shallower at once
  EXPECT_LT(back, 0.0);
}

}  // namespace
}  // namespace fsi::flight
