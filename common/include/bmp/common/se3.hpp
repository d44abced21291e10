#pragma once
// SE(3) helpers on Eigen. Frames are named in variables as T_a_b: maps points from frame b into frame a.
#include <Eigen/Geometry>

namespace bmp {

using SE3 = Eigen::Isometry3d;

// Builds a transform from a translation and a quaternion (normalised here).
SE3 makeSE3(const Eigen::Vector3d& t, const Eigen::Quaterniond& q);
// Rotation angle of a transform, radians, in [0, pi]; robust near 0 and pi.
double rotationAngle(const SE3& T);
// Exponential and logarithm maps; the tangent vector is (rho, phi): translation part first.
SE3 expSE3(const Eigen::Matrix<double, 6, 1>& xi);
Eigen::Matrix<double, 6, 1> logSE3(const SE3& T);
Eigen::Matrix3d skew(const Eigen::Vector3d& v);
// Orthonormalises the rotation block (guards against drift after many compositions).
SE3 normalized(const SE3& T);

}  // namespace bmp
