#include "bounding_box.h"

#include <algorithm>
#include <cmath>

namespace meshik::edit {

double BoundingBox::diagonal() const { return std::hypot(high[0] - low[0], high[1] - low[1], high[2] - low[2]); }

BoundingBox boundingBox(const double* points, std::size_t count) {
  BoundingBox box;
  if (count == 0) return box;
  for (int k = 0; k < 3; ++k) box.low[k] = box.high[k] = points[k];
  for (std::size_t p = 1; p < count; ++p)
    for (int k = 0; k < 3; ++k) {
      box.low[k] = std::min(box.low[k], points[3 * p + k]);
      box.high[k] = std::max(box.high[k], points[3 * p + k]);
    }
  return box;
}

}  // namespace meshik::edit
