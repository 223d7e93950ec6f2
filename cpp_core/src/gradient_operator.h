// The deformation-gradient operator G and the normal matrix of the pose least-squares problem
// with the fourth-vertex unknowns eliminated.
//
// For one coordinate c (the same G serves x, y and z), G maps the #V vertex values followed by the
// #F fourth-vertex values to the 3 #F values T_j[c][r] (row 3 j + r). The fourth vertex of
// triangle j appears only in triangle j's rows, so the fourth-vertex block of G^T G is diagonal
// and eliminating it exactly leaves K = sum_j (corner Gram matrix of g_j) on the #V vertices,
// with the sparsity of the mesh's vertex graph. The matching right-hand side uses T_j U_j only
// (see triangle_frames.h).
#pragma once

#include <vector>

#include "meshik/sparse_cholesky.h"
#include "triangle_frames.h"

namespace meshik {

struct MatrixEntry {
  int row;
  int col;
  double value;
};

// G with the fourth vertices kept: 3 #F by (#V + #F) entries (12 per triangle), unsorted.
// frames / triangles: the rest mesh's (#F by 3 indices); num_vertices: #V.
std::vector<MatrixEntry> kept_gradient_operator(const TriangleFrames& frames, const int* triangles,
                                                int num_vertices);

// K = G^T G with the fourth vertices eliminated is #V by #V with the sparsity of the mesh's vertex
// graph. Only its lower triangle on the vertices v with row_of_vertex[v] >= 0 is built (every
// vertex of a triangle has one; they number the rows 0..num_rows-1 in increasing vertex order, so
// row >= column there as in K): the pattern first, from the triangles alone (#F by 3 indices), then
// the values on it.
// Returns that pattern: num_rows square, rows sorted in each column, the diagonal always present,
// values empty.
CscMatrix eliminated_lower_pattern(const int* triangles, int num_triangles, const std::vector<int>& row_of_vertex,
                                   int num_rows);

// frames / triangles: the rest mesh's; row_of_vertex: as above; pattern: eliminated_lower_pattern's;
// team: the threads to use. Returns K's values on the pattern (one per entry, in its order), the same
// bits for any team: each entry sums its triangles' terms in increasing triangle order.
std::vector<double> eliminated_lower_values(const TriangleFrames& frames, const int* triangles,
                                            const std::vector<int>& row_of_vertex, const CscMatrix& pattern,
                                            int team = 1);

}  // namespace meshik
