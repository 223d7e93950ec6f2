// The axis-aligned bounding box of a point set (tolerances relative to a mesh's size, the mirror
// plane through its centre).
#pragma once

#include <array>
#include <cstddef>

namespace meshik::edit {

struct BoundingBox {
  std::array<double, 3> low{0.0, 0.0, 0.0};
  std::array<double, 3> high{0.0, 0.0, 0.0};
  double diagonal() const;  // the length of high - low
};

// The bounding box of `count` points (#count by 3 row-major); all zeros when count is 0.
BoundingBox boundingBox(const double* points, std::size_t count);

}  // namespace meshik::edit
