#pragma once
// Aerodynamic drag of the parts of a parachute system that the flow solver does not resolve: suspension and
// brake lines (slender cylinders, cross-flow principle) and the payload (a bluff body with a drag area).
// The wind U(t) = U·f(t) is uniform; the relative wind is U − v with v the structure's velocity, so a line
// moving with the air feels nothing and drag damps motion across the wind. In dynamic relaxation v is
// fictitious and vanishes at the static state: the static answer sees only U.
//
// Line drag per unit length: ½ ρ C_D d |U_n| U_n, U_n the part of the relative wind normal to the line (the
// axial part causes skin friction only, neglected); the element's force is that times its CURRENT length,
// half to each node, with the relative wind at its mid-point. Body drag at a node: ½ ρ C_D A |U − v| (U − v).

#include <array>
#include <string>
#include <vector>

#include "structure/effects/Effect.hpp"
#include "structure/effects/TimeFunction.hpp"

namespace fsi::structure {

struct AirStream {
  std::array<double, 3> wind{0, 0, 0};  ///< U [m/s]
  double density = 1.225;               ///< ρ of the air [kg/m³]
  TimeFunction function;                ///< scales U
};

class LineDrag final : public Effect {
 public:
  /// lineConn: model node indices, 2 per line element; diameter d [m], drag coefficient C_D of the section.
  LineDrag(std::string label, std::vector<int> lineConn, double diameter, double dragCoefficient,
           AirStream air);
  std::string name() const override { return "line_drag:" + label_; }
  void addForces(ForceContext& ctx) const override;

 private:
  std::string label_;
  std::vector<int> conn_;
  double halfRhoCdD_;  ///< ½ ρ C_D d
  AirStream air_;
};

class BodyDrag final : public Effect {
 public:
  /// Each node of `nodes` carries a body of drag area C_D·A [m²].
  BodyDrag(std::string label, std::vector<int> nodes, double dragArea, AirStream air);
  std::string name() const override { return "body_drag:" + label_; }
  void addForces(ForceContext& ctx) const override;

 private:
  std::string label_;
  std::vector<int> nodes_;
  double halfRhoCdA_;
  AirStream air_;
};

}  // namespace fsi::structure
