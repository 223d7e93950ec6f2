// Symmetry for the tool's "Mirror" option: the mirror plane (normal to X, Y or Z, through the rest
// mesh's bounding-box centre or through a picked vertex), the mirror image of a point, the rest
// vertex that pairs with a handle (the one nearest its mirror image, within a tolerance), and the
// group a new partner joins.
#pragma once

#include <vector>

namespace meshik::edit {

struct MirrorPlane {
  int axis = 0;         // 0, 1, 2: the plane x = offset, y = offset or z = offset
  double offset = 0.0;

  // The plane normal to `axis` through the bounding-box centre of #V by 3 row-major `vertices`.
  static MirrorPlane throughCentre(const std::vector<double>& vertices, int axis);
  // The plane normal to `axis` through `point` (3 doubles).
  static MirrorPlane throughPoint(const double* point, int axis);
  // The mirror image of p (3 doubles) written to out (3 doubles; may be p).
  void reflect(const double* p, double* out) const;
};

// The rest vertex nearest the mirror image of rest vertex `vertex` (#V by 3 row-major `rest`), when
// it lies within `tolerance` of that image; else -1. A vertex on the plane pairs with itself.
int mirrorPartner(const std::vector<double>& rest, int vertex, const MirrorPlane& plane, double tolerance);

// The group the mirror partner of handle `handle` (an index into the #H groups and mirrors, the
// latter the vertex mirroring each handle or -1; handles: the #H vertices) joins: the group of the
// partner of another handle of the same group, when that group is not the handle's own (so a group
// grown by ctrl+click has one mirrored group); else -1 (a new group).
int partnerGroup(const std::vector<int>& handles, const std::vector<int>& groups, const std::vector<int>& mirrors,
                 int handle);

}  // namespace meshik::edit
