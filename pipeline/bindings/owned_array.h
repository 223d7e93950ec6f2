// owned_array: hand a std::vector to Python as a numpy array without copying it.
#pragma once

#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstddef>
#include <initializer_list>
#include <utility>
#include <vector>

namespace meshik_bindings {

// A numpy array of the given shape (e.g. {rows, 3}; the product of its sizes is values.size())
// that owns `values`: the vector moves to the heap and is freed when the array is collected.
template <typename T>
nanobind::ndarray<nanobind::numpy, T> owned_array(std::vector<T>&& values, std::initializer_list<std::size_t> shape) {
  auto* owned = new std::vector<T>(std::move(values));
  nanobind::capsule owner(owned, [](void* p) noexcept { delete static_cast<std::vector<T>*>(p); });
  return nanobind::ndarray<nanobind::numpy, T>(owned->data(), shape.size(), shape.begin(), owner);
}

}  // namespace meshik_bindings
