// Symmetry for the tool's "Mirror" option: the mirror plane (normal to X, Y or Z, or the view's
// vertical plane; through the rest mesh's bounding-box centre or through a picked vertex), the
// mirror image of a point, the rest vertex that pairs with a handle (the one nearest its mirror
// image, within a tolerance), and the group a new partner joins.
#pragma once

#include <array>
#include <vector>

namespace meshik::edit {

using Direction = std::array<double, 3>;  // a unit vector in mesh coordinates

// The normal of the plane x = c (axis 0), y = c (1) or z = c (2).
Direction axisNormal(int axis);

// The normal of the view's vertical plane: the plane that contains the view direction and the
// view's up vector (the screen's vertical mid-plane when it goes through what the screen centres),
// so that mirroring across it swaps left and right on the screen. `modelview`: 16 doubles,
// column-major, from mesh to eye coordinates (GL's modelview with the mesh transform multiplied
// in). Returns the screen's right direction in mesh coordinates: the normal of the planes of
// constant eye x (row 0 of the matrix's linear part, normalised); (1, 0, 0) when that row is zero.
Direction viewVerticalNormal(const std::array<double, 16>& modelview);

struct MirrorPlane {
  Direction normal{1.0, 0.0, 0.0};  // unit normal n: the plane is n . x = offset
  double offset = 0.0;

  // The plane with unit normal `normal` through the bounding-box centre of #V by 3 row-major `vertices`.
  static MirrorPlane throughCentre(const std::vector<double>& vertices, const Direction& normal);
  // The plane with unit normal `normal` through `point` (3 doubles).
  static MirrorPlane throughPoint(const double* point, const Direction& normal);
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
