// Symmetry for the tool's "Mirror" option: the mirror plane (normal to X, Y or Z, through the rest
// mesh's bounding-box centre), the mirror image of a point, and the rest vertex that pairs with a
// handle (the one nearest its mirror image, within a tolerance).
#pragma once

#include <vector>

namespace meshik::edit {

struct MirrorPlane {
  int axis = 0;         // 0, 1, 2: the plane x = offset, y = offset or z = offset
  double offset = 0.0;

  // The plane normal to `axis` through the bounding-box centre of #V by 3 row-major `vertices`.
  static MirrorPlane throughCentre(const std::vector<double>& vertices, int axis);
  // The mirror image of p (3 doubles) written to out (3 doubles; may be p).
  void reflect(const double* p, double* out) const;
};

// The rest vertex nearest the mirror image of rest vertex `vertex` (#V by 3 row-major `rest`), when
// it lies within `tolerance` of that image; else -1. A vertex on the plane pairs with itself.
int mirrorPartner(const std::vector<double>& rest, int vertex, const MirrorPlane& plane, double tolerance);

}  // namespace meshik::edit
