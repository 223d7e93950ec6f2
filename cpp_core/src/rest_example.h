// The rest pose as one more example of the free blend (the paper's feature space holds the rest
// pose when it is one of the examples: T = I, so log R = 0 and S = I). With it the free stretch
// w_0 I + sum_i w_i S_ij contains today's affine one (w_0 = 1 - sum_i w_i).
#pragma once

#include "feature_space.h"

namespace meshik {

// features with an example 0 prepended whose values are all zero (log R = 0, (S - I) U = 0,
// (T - I) U = 0: the rest pose); the others follow as examples 1 .. #E. Returns #E + 1 examples.
ExampleFeatures with_rest_example(const ExampleFeatures& features);

}  // namespace meshik
