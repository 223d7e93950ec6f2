#include "screen_projection.h"

#include <Eigen/Dense>

#include <algorithm>
#include <cmath>

namespace meshik::edit {
namespace {

using Matrix4 = Eigen::Matrix4d;  // column-major, as OpenGL stores matrices

std::array<double, 16> toArray(const Matrix4& m) {
  std::array<double, 16> a;
  Eigen::Map<Matrix4>(a.data()) = m;
  return a;
}

std::array<double, 16> inverseOf(const std::array<double, 16>& matrix) {
  Matrix4 inverse;
  bool invertible = false;
  Eigen::Map<const Matrix4>(matrix.data()).computeInverseWithCheck(inverse, invertible, 0.0);
  return invertible ? toArray(inverse) : std::array<double, 16>{};
}

}  // namespace

ScreenProjection::ScreenProjection() : viewport_{0.0, 0.0, 2.0, 2.0} {
  matrix_ = toArray(Matrix4::Identity());
  modelview_ = matrix_;
  inverse_ = matrix_;
}

ScreenProjection::ScreenProjection(const double* projection, const double* modelview, const int* viewport)
    : viewport_{double(viewport[0]), double(viewport[1]), double(viewport[2]), double(viewport[3])} {
  std::copy(modelview, modelview + 16, modelview_.begin());
  matrix_ = toArray(Eigen::Map<const Matrix4>(projection) * Eigen::Map<const Matrix4>(modelview));
  inverse_ = inverseOf(matrix_);
}

WindowPoint ScreenProjection::project(const double* p) const {
  const Eigen::Vector4d clip = Eigen::Map<const Matrix4>(matrix_.data()) * Eigen::Vector4d(p[0], p[1], p[2], 1.0);
  const Eigen::Vector3d ndc = clip.head<3>() / clip[3];
  return {viewport_[0] + viewport_[2] * (ndc[0] + 1.0) / 2.0, viewport_[1] + viewport_[3] * (ndc[1] + 1.0) / 2.0,
          (ndc[2] + 1.0) / 2.0};
}

bool ScreenProjection::unproject(const WindowPoint& w, double* out) const {
  if (viewport_[2] <= 0.0 || viewport_[3] <= 0.0) return false;
  const Eigen::Vector4d ndc(2.0 * (w.x - viewport_[0]) / viewport_[2] - 1.0,
                            2.0 * (w.y - viewport_[1]) / viewport_[3] - 1.0, 2.0 * w.depth - 1.0, 1.0);
  const Eigen::Vector4d point = Eigen::Map<const Matrix4>(inverse_.data()) * ndc;
  if (!(std::abs(point[3]) > 0.0) || !point.allFinite()) return false;
  for (int k = 0; k < 3; ++k) out[k] = point[k] / point[3];
  return true;
}

}  // namespace meshik::edit
