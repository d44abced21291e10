#include "bmp/common/se3.hpp"

#include <algorithm>
#include <cmath>

namespace bmp {

SE3 makeSE3(const Eigen::Vector3d& t, const Eigen::Quaterniond& q) {
  SE3 T = SE3::Identity();
  T.linear() = q.normalized().toRotationMatrix();
  T.translation() = t;
  return T;
}

double rotationAngle(const SE3& T) {
  // atan2 form: accurate near 0 where acos((trace-1)/2) loses half its digits.
  const Eigen::AngleAxisd aa(T.linear());
  return std::abs(aa.angle());
}

Eigen::Matrix3d skew(const Eigen::Vector3d& v) {
  Eigen::Matrix3d m;
  m << 0, -v.z(), v.y(), v.z(), 0, -v.x(), -v.y(), v.x(), 0;
  return m;
}

namespace {
// Left Jacobian of SO(3) and its inverse, with series expansions for small angles.
Eigen::Matrix3d leftJacobian(const Eigen::Vector3d& phi) {
  const double theta = phi.norm();
  const Eigen::Matrix3d K = skew(phi);
  if (theta < 1e-8) return Eigen::Matrix3d::Identity() + 0.5 * K;
  const double t2 = theta * theta;
  return Eigen::Matrix3d::Identity() + (1 - std::cos(theta)) / t2 * K +
         (theta - std::sin(theta)) / (t2 * theta) * K * K;
}
}  // namespace

SE3 expSE3(const Eigen::Matrix<double, 6, 1>& xi) {
  const Eigen::Vector3d rho = xi.head<3>();
  const Eigen::Vector3d phi = xi.tail<3>();
  const double theta = phi.norm();
  SE3 T = SE3::Identity();
  T.linear() = theta < 1e-12 ? Eigen::Matrix3d(Eigen::Matrix3d::Identity() + skew(phi))
                             : Eigen::AngleAxisd(theta, phi / theta).toRotationMatrix();
  T.translation() = leftJacobian(phi) * rho;
  return normalized(T);
}

Eigen::Matrix<double, 6, 1> logSE3(const SE3& T) {
  const Eigen::AngleAxisd aa(T.linear());
  const Eigen::Vector3d phi = aa.angle() * aa.axis();
  Eigen::Matrix<double, 6, 1> xi;
  xi.head<3>() = leftJacobian(phi).inverse() * T.translation();
  xi.tail<3>() = phi;
  return xi;
}

SE3 normalized(const SE3& T) {
  SE3 out = T;
  out.linear() = Eigen::Quaterniond(T.linear()).normalized().toRotationMatrix();
  return out;
}

}  // namespace bmp
