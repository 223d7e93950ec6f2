// Soft handles (SolverOptions::handle_stiffness > 0): a handle vertex stays an unknown of the pose
// system, pulled towards its target by the penalty sigma_h |x_h - t_h|^2 instead of fixed there.
// The system becomes K' + P^T Sigma P and the right-hand side gains Sigma t; written as a coupling
// of value -sigma_h on the handle's own row, PoseSystem::subtract_handle_coupling adds that pull
// without a second code path.
#pragma once

#include <vector>

#include "meshik/sparse_cholesky.h"

namespace meshik {

// lower: the lower triangle of K on the system's rows, its values in `values` (changed in place:
// each handle row's diagonal gains sigma_h = stiffness * its diagonal entry, so the stiffness is
// relative to how strongly the vertex is held by its own triangles and does not depend on the
// mesh's scale). handle_of_row: the handle at each row, or -1; num_handles: #H.
// Fills row / value with one coupling entry (the handle's row, -sigma_h) per handle that has a
// row, and pull with sigma_h per handle (0 for a handle used by no triangle); returns #H + 1
// offsets into row / value.
std::vector<int> pull_handles_softly(const CscMatrix& lower, std::vector<double>& values,
                                     const std::vector<int>& handle_of_row, int num_handles, double stiffness,
                                     std::vector<int>& row, std::vector<double>& value, std::vector<double>& pull);

// sum_h pull[h] |x_h - t_h|^2 for vertices (#V by 3, internal order), the handles' vertex
// indices (#H, same order) and targets (#H by 3); 0 when pull is empty.
double soft_handle_energy(const double* vertices, const std::vector<int>& handles, const double* targets,
                          const std::vector<double>& pull);

}  // namespace meshik
