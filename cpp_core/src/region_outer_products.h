// H^T K'^{-1} H and H^T x0 with spatially varying weights (blend_regions.h), from the
// forward-solved right-hand sides: a region's Jacobian columns G'^T J are zero outside the rows of
// its triangles' corners, and the forward solve spreads them only up the elimination tree, so
// most rows carry one or two regions. Each row adds only the products of the regions it carries.
#pragma once

namespace meshik {

// Adds, over the rows u in [begin, end) of forward (rows of `stride` doubles, PoseEvaluator's
// rhs_ layout: the 3 coordinates of L^{-1} G'^T s, then coordinate c's K = regions x examples
// columns of L^{-1} G'^T J at 3 + c K + a, region-major), summed over the coordinates c:
//   products[a (K + 1)]         += row[3 + c K + a] row[c]                 (H^T x0)
//   products[a (K + 1) + 1 + b] += row[3 + c K + a] row[3 + c K + b]       (H^T K'^{-1} H)
// for b in a region s <= a's region r (the lower triangle of region blocks, diagonal blocks
// whole). A row adds nothing for a region whose 3 x examples values are all zero in it.
// products: K by K + 1; active: scratch of `regions` ints.
void add_region_outer_products(const double* forward, int begin, int end, int regions, int examples, int stride,
                               int* active, double* products);

// H^T K'^{-1} H (lower region blocks) and H^T x0 as add_region_outer_products summed them:
// entry (a, b) of the symmetric K by K matrix, a and b in any order.
inline double region_outer_product(const double* products, int regions, int examples, int a, int b) {
  const int k = regions * examples;
  if (b / examples > a / examples) return products[static_cast<long>(b) * (k + 1) + 1 + a];
  return products[static_cast<long>(a) * (k + 1) + 1 + b];
}

}  // namespace meshik
