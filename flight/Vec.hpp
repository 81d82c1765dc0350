#pragma once
// The small fixed-size algebra of the flight model (Eigen's 3-vectors, 3x3 matrices and quaternions).
//
// Frames: the world frame is North-East-Down (x north, y east, z down; altitude h = -z); the body frame is
// fixed to the rigid parafoil-payload system at its mass centre: x forward along the canopy's chord line
// projected to the symmetry plane, y right, z down (towards the payload). The attitude q rotates body
// vectors into world vectors: a_world = q * a_body.

#include <Eigen/Dense>
#include <Eigen/Geometry>

namespace fsi::flight {

using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;
using Quat = Eigen::Quaterniond;

}  // namespace fsi::flight
