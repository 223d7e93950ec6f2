// meshik._meshopt: the meshoptimizer library's vertex and index codecs (Debian libmeshoptimizer-dev)
// for EXT_meshopt_compression in meshik/export_gltf_quantized.py: vertex codec version 0, index codec
// version 1 (the versions the extension specifies), plus the vertex-cache triangle order and a
// vertex order (surface_walk.h) that make the streams compress well. Errors are raised as ValueError naming the stream.
#include <nanobind/nanobind.h>
#include <nanobind/ndarray.h>

#include <cstdint>
#include <string>
#include <vector>

#include <meshoptimizer.h>

#include "owned_array.h"
#include "surface_walk.h"

namespace nb = nanobind;
using namespace nb::literals;

namespace {

using ByteRows = nb::ndarray<const std::uint8_t, nb::ndim<2>, nb::c_contig, nb::device::cpu>;
using Indices = nb::ndarray<const std::uint32_t, nb::ndim<1>, nb::c_contig, nb::device::cpu>;
using Positions = nb::ndarray<const double, nb::shape<-1, 3>, nb::c_contig, nb::device::cpu>;

// A numpy array of the given shape that owns `values` (moved to the heap).
template <typename T>
nb::object owning_array(std::vector<T>&& values, std::initializer_list<size_t> shape) {
  return nb::cast(meshik_bindings::owned_array(std::move(values), shape));
}

// ValueError unless every index addresses one of vertex_count vertices and the list is whole triangles.
void check_triangles(const Indices& indices, size_t vertex_count) {
  if (indices.size() % 3 != 0)
    throw nb::value_error(("index list of " + std::to_string(indices.size()) + " entries is not whole triangles").c_str());
  for (size_t i = 0; i < indices.size(); ++i)
    if (indices.data()[i] >= vertex_count)
      throw nb::value_error(("index " + std::to_string(i) + " is " + std::to_string(indices.data()[i]) + ", past the " +
                             std::to_string(vertex_count) + " vertices").c_str());
}

// Encoded bytes of a #vertices by vertex_size byte array (vertex_size a multiple of 4, at most 256).
nb::bytes encode_vertex_buffer(ByteRows rows) {
  const size_t count = rows.shape(0), size = rows.shape(1);
  if (size == 0 || size % 4 != 0 || size > 256)
    throw nb::value_error(("vertex size " + std::to_string(size) + " is not a multiple of 4 up to 256").c_str());
  std::vector<unsigned char> encoded(meshopt_encodeVertexBufferBound(count, size));
  {
    nb::gil_scoped_release release;
    meshopt_encodeVertexVersion(0);
    encoded.resize(meshopt_encodeVertexBuffer(encoded.data(), encoded.size(), rows.data(), count, size));
  }
  return nb::bytes(reinterpret_cast<const char*>(encoded.data()), encoded.size());
}

// The most bytes one decode may produce (meshoptimizer asserts, and would abort the process, on
// sizes it does not support; a count from a hostile file must not allocate without bound).
constexpr size_t kMaxDecodedBytes = size_t{1} << 31;

// ValueError unless count elements of `size` bytes fit in kMaxDecodedBytes.
void check_decoded_size(size_t count, size_t size) {
  if (size != 0 && count > kMaxDecodedBytes / size)
    throw nb::value_error(("decoding " + std::to_string(count) + " elements of " + std::to_string(size) +
                           " bytes would take more than " + std::to_string(kMaxDecodedBytes) + " bytes").c_str());
}

// count by size bytes decoded from encode_vertex_buffer's output; ValueError when malformed
// (size: a multiple of 4 up to 256, as meshoptimizer requires).
nb::object decode_vertex_buffer(nb::bytes data, size_t count, size_t size) {
  if (size == 0 || size % 4 != 0 || size > 256)
    throw nb::value_error(("vertex size " + std::to_string(size) + " is not a multiple of 4 up to 256").c_str());
  check_decoded_size(count, size);
  std::vector<std::uint8_t> rows(count * size);
  const int status = meshopt_decodeVertexBuffer(rows.data(), count, size,
                                                reinterpret_cast<const unsigned char*>(data.c_str()), data.size());
  if (status != 0) throw nb::value_error(("malformed meshopt vertex stream (code " + std::to_string(status) + ")").c_str());
  return owning_array(std::move(rows), {count, size});
}

// Encoded bytes of a triangle list (3 #F uint32 indices into vertex_count vertices).
nb::bytes encode_index_buffer(Indices indices, size_t vertex_count) {
  check_triangles(indices, vertex_count);
  std::vector<unsigned char> encoded(meshopt_encodeIndexBufferBound(indices.size(), vertex_count));
  {
    nb::gil_scoped_release release;
    meshopt_encodeIndexVersion(1);
    encoded.resize(meshopt_encodeIndexBuffer(encoded.data(), encoded.size(), indices.data(), indices.size()));
  }
  return nb::bytes(reinterpret_cast<const char*>(encoded.data()), encoded.size());
}

// count uint32 indices decoded from encode_index_buffer's output; ValueError when malformed.
nb::object decode_index_buffer(nb::bytes data, size_t count) {
  if (count % 3 != 0)
    throw nb::value_error(("index count " + std::to_string(count) + " is not whole triangles").c_str());
  check_decoded_size(count, 4);
  std::vector<std::uint32_t> indices(count);
  const int status = meshopt_decodeIndexBuffer(indices.data(), count, 4,
                                               reinterpret_cast<const unsigned char*>(data.c_str()), data.size());
  if (status != 0) throw nb::value_error(("malformed meshopt index stream (code " + std::to_string(status) + ")").c_str());
  return owning_array(std::move(indices), {count});
}

// The same triangles (3 #F uint32) reordered for the GPU's vertex cache.
nb::object optimize_vertex_cache(Indices indices, size_t vertex_count) {
  check_triangles(indices, vertex_count);
  std::vector<std::uint32_t> reordered(indices.size());
  {
    nb::gil_scoped_release release;
    meshopt_optimizeVertexCache(reordered.data(), indices.data(), indices.size(), vertex_count);
  }
  return owning_array(std::move(reordered), {reordered.size()});
}

// #V uint32 old vertex index at each new position (surface_walk.h) of the triangles (3 #F uint32)
// over #V by 3 positions.
nb::object surface_walk(Indices indices, Positions positions) {
  const size_t vertex_count = positions.shape(0);
  check_triangles(indices, vertex_count);
  std::vector<std::uint32_t> order;
  {
    nb::gil_scoped_release release;
    order = meshik_bindings::surface_walk_order(indices.data(), indices.size(), positions.data(), vertex_count);
  }
  return owning_array(std::move(order), {vertex_count});
}

}  // namespace

NB_MODULE(_meshopt, m) {
  m.doc() = "meshoptimizer's codecs (EXT_meshopt_compression) and vertex orders";
  m.attr("LIBRARY_VERSION") = MESHOPTIMIZER_VERSION;
  m.def("encode_vertex_buffer", &encode_vertex_buffer, "rows"_a);
  m.def("decode_vertex_buffer", &decode_vertex_buffer, "data"_a, "count"_a, "size"_a);
  m.def("encode_index_buffer", &encode_index_buffer, "indices"_a, "vertex_count"_a);
  m.def("decode_index_buffer", &decode_index_buffer, "data"_a, "count"_a);
  m.def("optimize_vertex_cache", &optimize_vertex_cache, "indices"_a, "vertex_count"_a);
  m.def("surface_walk", &surface_walk, "indices"_a, "positions"_a);
}
