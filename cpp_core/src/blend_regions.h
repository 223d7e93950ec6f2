// Regions of spatially varying blend weights: each triangle's shares of the regions (a partition
// of unity with soft borders), the regions each batch of triangles touches, and the smoothness
// term that pulls neighbouring regions' weights together.
//
// Triangle j blends the examples with w_j = sum_r alpha_jr W_r, W_r the #E weights of region r.
// The smoothness energy is W^T (M kron I_#E) W with M = lambda sum over triangle edges (j, j') of
// (alpha_j - alpha_j')(alpha_j - alpha_j')^T, i.e. lambda sum over edges of |w_j - w_j'|^2.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "example_set_impl.h"

namespace meshik {

struct BlendRegions {
  int num_regions = 0;
  int num_triangles = 0;
  std::vector<double> share;  // #F (internal order) by #regions: alpha_jr >= 0, rows sum to one
  // Per batch of kLanes triangles: the regions with a share in any of its triangles, ascending,
  // at active[active_start[b] .. active_start[b + 1]).
  std::vector<int> active_start;  // #batches + 1
  std::vector<int> active;
  // Per batch: the region r when every triangle of the batch has alpha_jr = 1 exactly, else -1.
  std::vector<int> whole_region;
  Eigen::MatrixXd smoothness;  // #regions by #regions: M (lambda included)

  int batch_region_count(int batch) const { return active_start[batch + 1] - active_start[batch]; }
  const int* batch_regions(int batch) const { return active.data() + active_start[batch]; }
};

// The user's region per vertex -> shares: a triangle takes each of its corners' regions by a third
// (vertices in no group, -1, form one more region), then the borders are softened.
// vertex_regions: #V in the user's vertex order. Throws InputError for an id below -1.
BlendRegions regions_from_vertex_groups(const ExampleSet::Impl& set, const std::vector<int>& vertex_regions,
                                        double smoothness);

// count regions (>= 1, or kAutomaticRegions) clustered from the examples: k-means of how the
// triangles move (each example's displacement of the triangle's centroid from the rest),
// farthest-point seeded, then softened borders. One region gives every triangle alpha = 1.
BlendRegions regions_from_examples(const ExampleSet& examples, int count, double smoothness);

}  // namespace meshik
