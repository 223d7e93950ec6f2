#include "rigid_fit.h"

#include <Eigen/Dense>

namespace meshik::edit {

std::optional<RigidMotion> fitRigidMotion(const double* from, const double* to, std::size_t count, double tolerance) {
  if (count == 0) return std::nullopt;
  using Points = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;
  const Eigen::Map<const Points> a(from, static_cast<Eigen::Index>(count), 3), b(to, static_cast<Eigen::Index>(count), 3);
  const Eigen::RowVector3d centre_a = a.colwise().mean(), centre_b = b.colwise().mean();
  const Points da = a.rowwise() - centre_a, db = b.rowwise() - centre_b;
  const Eigen::JacobiSVD<Eigen::Matrix3d> svd(db.transpose() * da, Eigen::ComputeFullU | Eigen::ComputeFullV);
  Eigen::Matrix3d correction = Eigen::Matrix3d::Identity();
  correction(2, 2) = (svd.matrixU() * svd.matrixV().transpose()).determinant() < 0.0 ? -1.0 : 1.0;
  const Eigen::Matrix3d rotation = svd.matrixU() * correction * svd.matrixV().transpose();
  const Points moved = (da * rotation.transpose()).rowwise() + centre_b;
  if (!((moved - b).rowwise().norm().array() <= tolerance).all()) return std::nullopt;
  RigidMotion motion;
  for (int row = 0; row < 3; ++row)
    for (int column = 0; column < 3; ++column) motion.rotation[3 * row + column] = rotation(row, column);
  for (int k = 0; k < 3; ++k) {
    motion.center[k] = centre_a[k];
    motion.translation[k] = centre_b[k] - centre_a[k];
  }
  return motion;
}

}  // namespace meshik::edit
