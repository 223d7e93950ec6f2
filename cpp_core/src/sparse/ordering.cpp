#include "sparse/ordering.h"

#include <amd.h>

#include <stdexcept>

namespace meshik::sparse {

std::vector<int> minimum_degree_ordering(const Pattern& lower) {
  std::vector<int> perm(lower.n);
  if (lower.n == 0) return perm;
  double control[AMD_CONTROL];
  amd_defaults(control);
  const int status = amd_order(lower.n, lower.col_start.data(), lower.row_index.data(),
                               perm.data(), control, nullptr);
  if (status != AMD_OK && status != AMD_OK_BUT_JUMBLED)
    throw std::runtime_error("SparseCholesky: AMD ordering failed with status " +
                             std::to_string(status));
  return perm;
}

std::vector<int> invert_permutation(const std::vector<int>& perm) {
  std::vector<int> inverse(perm.size());
  for (size_t k = 0; k < perm.size(); ++k) inverse[perm[k]] = static_cast<int>(k);
  return inverse;
}

}  // namespace meshik::sparse
