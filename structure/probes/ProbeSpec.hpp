#pragma once
// One probe of the scene's `probes:` section, as resolved at load time: which kind, on which nodes or
// triangles, which component and how the values of several nodes/triangles reduce to one number.

#include <array>
#include <string>
#include <vector>

namespace fsi::structure {

struct ProbeKind;

/// Which component of a vector quantity a probe reports.
enum class ProbeComponent {
  X,
  Y,
  Z,
  Magnitude,
  Radial,  ///< distance from `center` (displacement: its change)
};

/// How the values of several nodes or triangles become the probe's one number.
enum class ProbeReduce { Value, Mean, Max, Min, Sum };

/// Which principal membrane stress a stress probe reports.
enum class StressQuantity { MaxPrincipal, MinPrincipal };

/// What a laplace probe reports (LaplaceProbe.cpp).
enum class LaplaceQuantity { Ratio, SimpleRatio, Radius, Tension, Pressure };

struct ProbeSpec {
  std::string name;
  const ProbeKind* kind = nullptr;  ///< its entry in probeKinds()
  ProbeReduce reduce = ProbeReduce::Value;
  std::vector<int> nodes;      ///< model node indices
  std::vector<int> triangles;  ///< model membrane element indices
  std::vector<int> lines;      ///< model cable element indices
  std::vector<int> nodesTo;    ///< a second node set (pitch_angle: the trailing edge)
  ProbeComponent component = ProbeComponent::X;
  std::array<double, 3> center{0, 0, 0};
  StressQuantity quantity = StressQuantity::MaxPrincipal;
  LaplaceQuantity laplace = LaplaceQuantity::Ratio;
  std::array<double, 3> direction{0, 0, 0};  ///< laplace: the tangent direction of radius and tension
  int rings = 2;                             ///< laplace: the rings of neighbours the fit and average use
  bool areaWeighted = false;                 ///< stress: the values are σ·A/ΣA, summed (an area mean)
  double angle = 0;                          ///< folds: the turn [deg] that counts as a fold
};

}  // namespace fsi::structure
