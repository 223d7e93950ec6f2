// The soft handles' pull on the pose system and their penalty energy.
#include "soft_handles.h"

#include <cstddef>

namespace meshik {

std::vector<int> pull_handles_softly(const CscMatrix& lower, std::vector<double>& values,
                                     const std::vector<int>& handle_of_row, int num_handles, double stiffness,
                                     std::vector<int>& row, std::vector<double>& value, std::vector<double>& pull) {
  std::vector<int> row_of_handle(num_handles, -1);
  pull.assign(num_handles, 0.0);
  for (int col = 0; col < lower.cols; ++col) {
    const int h = handle_of_row[col];
    if (h < 0) continue;
    for (int s = lower.col_start[col]; s < lower.col_start[col + 1]; ++s)
      if (lower.row_index[s] == col) {
        pull[h] = stiffness * values[s];
        values[s] += pull[h];
        row_of_handle[h] = col;
      }
  }
  std::vector<int> start(1, 0);
  for (int h = 0; h < num_handles; ++h) {
    if (row_of_handle[h] >= 0) {
      row.push_back(row_of_handle[h]);
      value.push_back(-pull[h]);
    }
    start.push_back(static_cast<int>(row.size()));
  }
  return start;
}

double soft_handle_energy(const double* vertices, const std::vector<int>& handles, const double* targets,
                          const std::vector<double>& pull) {
  double energy = 0.0;
  for (size_t h = 0; h < pull.size(); ++h) {
    const double* x = vertices + 3 * static_cast<size_t>(handles[h]);
    const double* t = targets + 3 * h;
    const double dx = x[0] - t[0], dy = x[1] - t[1], dz = x[2] - t[2];
    energy += pull[h] * (dx * dx + dy * dy + dz * dz);
  }
  return energy;
}

}  // namespace meshik
