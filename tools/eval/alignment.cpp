#include "eval/alignment.hpp"

#include <Eigen/LU>
#include <Eigen/SVD>

namespace bmp::eval {

RigidAlignment alignHorn(const Eigen::Matrix3Xd& model, const Eigen::Matrix3Xd& data) {
  const Eigen::Vector3d model_mean = model.rowwise().mean();
  const Eigen::Vector3d data_mean = data.rowwise().mean();
  const Eigen::Matrix3Xd model_c = model.colwise() - model_mean;
  const Eigen::Matrix3Xd data_c = data.colwise() - data_mean;
  // W = sum_i outer(model_i, data_i); the script decomposes W^T = U diag(d) Vh.
  const Eigen::Matrix3d W = model_c * data_c.transpose();
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(W.transpose(), Eigen::ComputeFullU | Eigen::ComputeFullV);
  const Eigen::Matrix3d U = svd.matrixU();
  const Eigen::Matrix3d Vh = svd.matrixV().transpose();
  Eigen::Matrix3d S = Eigen::Matrix3d::Identity();
  if (U.determinant() * Vh.determinant() < 0) S(2, 2) = -1;  // a reflection is not a rotation
  RigidAlignment out;
  out.rotation = U * S * Vh;
  out.translation = data_mean - out.rotation * model_mean;
  return out;
}

}  // namespace bmp::eval
