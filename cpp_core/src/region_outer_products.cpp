// The forward-solved rows' products, region blocks by region blocks (region_outer_products.h).
#include "region_outer_products.h"

#include <cstddef>

namespace meshik {

namespace {

// The regions with a nonzero value in row (ascending) into active; returns their count.
int regions_in_row(const double* row, int regions, int examples, int* active) {
  const int k = regions * examples;
  int n = 0;
  for (int r = 0; r < regions; ++r) {
    bool any = false;
    for (int c = 0; c < 3 && !any; ++c) {
      const double* values = row + 3 + c * k + r * examples;
      for (int a = 0; a < examples; ++a) any = any || values[a] != 0.0;
    }
    if (any) active[n++] = r;
  }
  return n;
}

}  // namespace

void add_region_outer_products(const double* forward, int begin, int end, int regions, int examples, int stride,
                               int* active, double* products) {
  const int k = regions * examples;
  for (int u = begin; u < end; ++u) {
    const double* row = forward + static_cast<size_t>(u) * stride;
    const int n = regions_in_row(row, regions, examples, active);
    for (int c = 0; c < 3; ++c) {
      const double* columns = row + 3 + c * k;
      for (int t = 0; t < n; ++t) {
        const int r = active[t];
        for (int a = r * examples; a < (r + 1) * examples; ++a) {
          const double value = columns[a];
          if (value == 0.0) continue;
          double* __restrict product = products + static_cast<size_t>(a) * (k + 1);
          product[0] += value * row[c];
          for (int q = 0; q <= t; ++q) {
            const int s = active[q] * examples;
            double* __restrict block = product + 1 + s;
            const double* __restrict other = columns + s;
            for (int b = 0; b < examples; ++b) block[b] += value * other[b];
          }
        }
      }
    }
  }
}

}  // namespace meshik
