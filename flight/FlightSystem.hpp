#pragma once
// FlightSystem: the parafoil and its payload as one rigid body (6 degrees of freedom), the model the flight
// command integrates. Origin and body axes at the system's mass centre (flight/Vec.hpp for the frames).
//
// Forces: gravity on the mass m; the canopy's aerodynamics from the AeroTable at the canopy's reference point
// (lift, drag and side force along the wind axes of the air's velocity there, moments about it); the
// payload's drag (C_D A) at the payload point; the lines' drag lumped as a drag area at the canopy point (0:
// the table's CD includes them). Every aerodynamic velocity is relative to the air: the body's velocity at
// that point minus the wind there.
//
// Apparent mass: the air the canopy carries with it adds a diagonal mass A (body axes) and inertia A_r. They
// act on the velocity relative to the air, v_a (Kirchhoff's equations for a body in a fluid at rest, in a
// steady wind by a Galilean shift):
//   (m I + A) v̇ = F − m ω × v − A (ω × Rᵀw) − ω × (A v_a)
//   (J + A_r) ω̇ = τ − ω × ((J + A_r) ω) − v_a × (A v_a)
// with the Munk moment v_a × A v_a; without wind and aerodynamics they conserve ½ v·(mI + A)v + ½ ω·(J +
// A_r)ω
// + m g h. Lissaman & Brown (1993) estimate A and A_r from the canopy's span, chord, thickness and arc; the
// flight file gives them (docs/FLIGHT.md).

#include <array>

#include "flight/AeroTable.hpp"
#include "flight/Vec.hpp"
#include "flight/Wind.hpp"

namespace fsi::flight {

struct FlightSystem {
  double mass = 1;                   ///< m [kg]: canopy, lines and payload
  Mat3 inertia = Mat3::Identity();   ///< J about the mass centre, body axes [kg m²]
  Vec3 addedMass = Vec3::Zero();     ///< A, diagonal, body axes [kg]
  Vec3 addedInertia = Vec3::Zero();  ///< A_r, diagonal, body axes [kg m²]
  AeroTable aero;
  Vec3 canopyPoint = Vec3::Zero();   ///< the canopy's reference point from the mass centre [m]
  Vec3 payloadPoint = Vec3::Zero();  ///< the payload from the mass centre [m]
  double payloadDragArea = 0;        ///< C_D A of the payload [m²]
  double lineDragArea = 0;           ///< C_D A of the lines, at the canopy point [m²]
  double airDensity = 1.225;         ///< ρ [kg/m³]
  double gravity = 9.80665;          ///< g [m/s²]
  bool aerodynamics = true;          ///< false: gravity and inertia only (checks)
  /// false: the Munk moment −v_a × A v_a is left out, for tables whose moments come from steady flow
  /// solutions (they contain the steady moment of the air's momentum, of which the Munk moment is the
  /// potential-flow part; with both it would count twice). The unsteady apparent-mass terms stay.
  bool munkMoment = true;
};

struct FlightState {
  Vec3 position = Vec3::Zero();      ///< mass centre, NED [m]
  Quat attitude = Quat::Identity();  ///< body -> world
  Vec3 velocity = Vec3::Zero();      ///< mass centre's velocity over the ground, body axes [m/s]
  Vec3 rates = Vec3::Zero();         ///< ω = (p, q, r), body axes [rad/s]
};

struct Controls {
  double brakeLeft = 0, brakeRight = 0;  ///< fraction of the full brake travel, 0 … 1
  /// The rigging's change [rad]: the canopy point turned by this angle about the body's y axis through the
  /// mass centre (positive: the canopy moves back over the payload, the lines tilt back, the trim angle of
  /// attack falls and the glide steepens, as the coupled runs' rigging angle does; docs/FLIGHT.md).
  double incidence = 0;
};

/// What the model sees at one instant (for output and guidance).
struct FlightReading {
  double airspeed = 0;         ///< at the canopy point [m/s]
  double alpha = 0, beta = 0;  ///< [rad]
  AeroCoefficients coefficients;
  Vec3 force = Vec3::Zero(), moment = Vec3::Zero();  ///< external, body axes, about the mass centre
  Vec3 aeroForce = Vec3::Zero();  ///< canopy, lines and payload (the force without gravity), body axes
};

/// Time derivative of the state: d(position)/dt (world), d(attitude)/dt (as a quaternion's 4 numbers w, x, y,
/// z), d(velocity)/dt and d(rates)/dt (body). `reading` (optional) receives the aerodynamic state.
struct StateRate {
  Vec3 position, velocity, rates;
  std::array<double, 4> attitude;
};
StateRate stateRate(const FlightSystem& system, const Wind& wind, const Controls& controls, double time,
                    const FlightState& state, FlightReading* reading = nullptr);

/// One classical Runge–Kutta step of length dt (4th order; the attitude renormalised after the step).
FlightState rungeKuttaStep(const FlightSystem& system, const Wind& wind, const Controls& controls,
                           double time, double dt, const FlightState& state);

/// Total mechanical energy ½ v·(mI + A)v + ½ ω·(J + A_r)ω + m g h, without wind [J].
double mechanicalEnergy(const FlightSystem& system, const FlightState& state);

}  // namespace fsi::flight
