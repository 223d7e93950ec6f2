// The examples' features with the rest pose prepended (rest_example.h).
#include "rest_example.h"

#include <algorithm>
#include <cstddef>

namespace meshik {

namespace {

// values: #batches by #E examples by `rows` rows of kLanes; returns #batches by #E + 1 by `rows`,
// example 0 zero in every batch.
template <typename Value>
PageArray<Value> prepend_zero_example(const PageArray<Value>& values, int batches, int examples, int rows) {
  if (values.empty()) return {};
  const size_t block = static_cast<size_t>(rows) * kLanes;
  PageArray<Value> out(static_cast<size_t>(batches) * (examples + 1) * block, Value(0));
  for (int b = 0; b < batches; ++b) {
    const Value* from = values.data() + static_cast<size_t>(b) * examples * block;
    std::copy(from, from + examples * block, out.data() + (static_cast<size_t>(b) * (examples + 1) + 1) * block);
  }
  return out;
}

// The FeatureValues of `values` with the zero example prepended.
template <typename Stored>
FeatureValues<Stored> prepend_zero_example(const FeatureValues<Stored>& values, int batches, int examples) {
  FeatureValues<Stored> out;
  out.nonlinear = prepend_zero_example(values.nonlinear, batches, examples, 9);
  return out;
}

}  // namespace

ExampleFeatures with_rest_example(const ExampleFeatures& features) {
  ExampleFeatures out;
  out.num_examples = features.num_examples + 1;
  out.num_triangles = features.num_triangles;
  out.num_batches = features.num_batches;
  out.precision = features.precision;
  out.single = prepend_zero_example(features.single, features.num_batches, features.num_examples);
  out.full = prepend_zero_example(features.full, features.num_batches, features.num_examples);
  out.plane_basis = features.plane_basis;
  return out;
}

}  // namespace meshik
