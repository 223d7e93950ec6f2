// The pool of freed large arrays' pages (page_pool.h): what is taken holds the pages given back
// last (their contents moved, not copied), whole arrays and parts of them, within the capacity,
// from several threads at once; PageArrays from kPooledArrayBytes use it; an ExampleSet's
// destruction empties it; and a pose whose arrays get pages full of NaN is the same bits as one on
// fresh pages.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <limits>
#include <memory>
#include <thread>
#include <vector>

#include <Eigen/Core>

#include "page_arrays.h"
#include "page_pool.h"
#include "test_meshik_support.h"

namespace {

using meshik::kPoolCapacityBytes;
using meshik::kPooledArrayBytes;
using meshik::pooled_bytes;

constexpr size_t kMiB = size_t{1} << 20;

// Takes `bytes` from the pool and writes entry e of its 64-bit words as first + e. Returns it.
std::uint64_t* take_counting(size_t bytes, std::uint64_t first) {
  auto* words = static_cast<std::uint64_t*>(meshik::take_pages(bytes));
  for (size_t e = 0; e < bytes / 8; ++e) words[e] = first + e;
  return words;
}

// The number of 64-bit words from `from` to `to` (exclusive) of words that differ from first + e.
size_t count_not_counting(const std::uint64_t* words, size_t from, size_t to, std::uint64_t first) {
  size_t wrong = 0;
  for (size_t e = from; e < to; ++e) wrong += words[e] != first + e;
  return wrong;
}

// The number of nonzero 64-bit words from `from` to `to` (exclusive) of words.
size_t count_nonzero(const std::uint64_t* words, size_t from, size_t to) {
  size_t nonzero = 0;
  for (size_t e = from; e < to; ++e) nonzero += words[e] != 0;
  return nonzero;
}

TEST(PagePool, TakesThePagesOfTheArrayGivenBackLast) {
  meshik::release_pooled_pages();
  const size_t bytes = 40 * kMiB;
  std::uint64_t* first = take_counting(bytes, 7);
  meshik::give_pages(first, bytes);
  EXPECT_EQ(pooled_bytes(), bytes);
  auto* second = static_cast<std::uint64_t*>(meshik::take_pages(bytes));
  EXPECT_EQ(pooled_bytes(), 0u);
  EXPECT_EQ(count_not_counting(second, 0, bytes / 8, 7), 0u) << "the pages were not moved";
  meshik::give_pages(second, bytes);
  meshik::release_pooled_pages();
  EXPECT_EQ(pooled_bytes(), 0u);
}

TEST(PagePool, SplitsAKeptArrayAndAppendsFreshPages) {
  meshik::release_pooled_pages();
  const size_t bytes = 40 * kMiB, head = 16 * kMiB, longer = 100 * kMiB;
  meshik::give_pages(take_counting(bytes, 1), bytes);
  // A smaller array takes the kept array's head; its tail stays kept.
  auto* part = static_cast<std::uint64_t*>(meshik::take_pages(head));
  EXPECT_EQ(count_not_counting(part, 0, head / 8, 1), 0u);
  EXPECT_EQ(pooled_bytes(), bytes - head);
  // A longer one takes the tail, then fresh (zero) pages.
  auto* whole = static_cast<std::uint64_t*>(meshik::take_pages(longer));
  EXPECT_EQ(pooled_bytes(), 0u);
  EXPECT_EQ(count_not_counting(whole, 0, (bytes - head) / 8, 1 + head / 8), 0u);
  EXPECT_EQ(count_nonzero(whole, (bytes - head) / 8, longer / 8), 0u);
  // Given back, the longer array (two mappings) is taken again whole, in order.
  for (size_t e = 0; e < longer / 8; ++e) whole[e] = 3 * e;
  meshik::give_pages(whole, longer);
  meshik::give_pages(part, head);
  EXPECT_EQ(pooled_bytes(), longer + head);
  auto* again = static_cast<std::uint64_t*>(meshik::take_pages(head + longer));
  EXPECT_EQ(count_not_counting(again, 0, head / 8, 1), 0u);
  size_t wrong = 0;
  for (size_t e = 0; e < longer / 8; ++e) wrong += again[head / 8 + e] != 3 * e;
  EXPECT_EQ(wrong, 0u);
  meshik::give_pages(again, head + longer);
  meshik::release_pooled_pages();
}

TEST(PagePool, KeepsAtMostItsCapacityTheLatestFirst) {
  meshik::release_pooled_pages();
  const size_t bytes = 100 * kMiB;
  const std::uint64_t count = kPoolCapacityBytes / bytes + 2;
  std::vector<std::uint64_t*> arrays;
  for (std::uint64_t a = 0; a < count; ++a) arrays.push_back(take_counting(bytes, a << 40));
  for (std::uint64_t* array : arrays) meshik::give_pages(array, bytes);
  EXPECT_EQ(pooled_bytes(), kPoolCapacityBytes);
  auto* latest = static_cast<std::uint64_t*>(meshik::take_pages(bytes));
  EXPECT_EQ(count_not_counting(latest, 0, bytes / 8, (count - 1) << 40), 0u);
  meshik::give_pages(latest, bytes);
  meshik::release_pooled_pages();
  EXPECT_EQ(pooled_bytes(), 0u);
}

TEST(PagePool, ThreadsTakeAndGiveBackAtOnce) {
  meshik::release_pooled_pages();
  const size_t bytes = 33 * kMiB;
  std::vector<size_t> wrong(4, 0);
  std::vector<std::thread> threads;
  for (int t = 0; t < 4; ++t)
    threads.emplace_back([t, bytes, &wrong] {
      for (int round = 0; round < 6; ++round) {
        const std::uint64_t first = (std::uint64_t{1} + t) << 48 | std::uint64_t(round) << 32;
        std::uint64_t* words = take_counting(bytes, first);
        wrong[t] += count_not_counting(words, 0, bytes / 8, first);
        meshik::give_pages(words, bytes);
      }
    });
  for (std::thread& thread : threads) thread.join();
  for (int t = 0; t < 4; ++t) EXPECT_EQ(wrong[t], 0u) << "thread " << t;
  EXPECT_LE(pooled_bytes(), kPoolCapacityBytes);
  meshik::release_pooled_pages();
}

TEST(PagePool, PageArraysFromThePooledSizeUseIt) {
  meshik::release_pooled_pages();
  const size_t large = kPooledArrayBytes / sizeof(double), small = large / 8;
  { meshik::PageArray<double> array(small, 1.0); }
  EXPECT_EQ(pooled_bytes(), 0u);
  { meshik::PageArray<double> array(large, 1.0); }
  EXPECT_EQ(pooled_bytes(), kPooledArrayBytes);
  meshik::PageArray<double> reused;
  meshik::size_unwritten(reused, large);
  EXPECT_EQ(reused[large / 2], 1.0) << "the array did not take the kept pages";
  EXPECT_EQ(pooled_bytes(), 0u);
  reused = meshik::PageArray<double>();
  EXPECT_EQ(pooled_bytes(), kPooledArrayBytes);
  meshik::release_pooled_pages();
}

TEST(PagePool, AnExampleSetsDestructionEmptiesIt) {
  meshik::release_pooled_pages();
  const meshik_test::ExampleMeshes meshes = meshik_test::make_tube_examples();
  auto set = std::make_unique<meshik::ExampleSet>(meshes.view(), meshes.example_pointers());
  meshik::give_pages(take_counting(kPooledArrayBytes, 0), kPooledArrayBytes);
  EXPECT_EQ(pooled_bytes(), kPooledArrayBytes);
  set.reset();
  EXPECT_EQ(pooled_bytes(), 0u);
}

// The vertices of a pose of `meshes` on `threads` threads: 8 farthest-point handles at their
// places in the first example.
std::vector<double> pose(const meshik_test::ExampleMeshes& meshes, int threads) {
  auto set = std::make_shared<meshik::ExampleSet>(meshes.view(), meshes.example_pointers(),
                                                  meshik::ProgressCallback{}, threads);
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes.rest, 8);
  const std::vector<double> targets = meshik_test::gather_rows(meshes.examples[0], handles);
  meshik::SolverOptions options;
  options.threads = threads;
  return meshik::Solver(set, handles, options).solve(targets.data()).vertices;
}

// Whether a and b are the same bits.
bool same_bits(const std::vector<double>& a, const std::vector<double>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(double)) == 0;
}

TEST(PagePool, PoseOnPagesOfNotANumberIsTheSameBits) {
  // 321,602 triangles (the last batch of 8 padded) and 5 examples, two of them twisted past a half
  // turn (their logs take other branches): the features' values (55 MiB), the factor's, and on 5
  // threads the principal logs and edge distances of the group of 5 (37 MiB each) are pooled arrays.
  meshik_test::ExampleMeshes meshes = meshik_test::make_tube_examples(401, 401);
  for (double twist : {4.0, -3.5})
    meshes.examples.push_back(meshik_test::make_tube_examples(401, 401, twist).examples[1]);
  const size_t group = meshes.examples.size();
  ASSERT_GE(9 * sizeof(float) * group * meshes.num_triangles(), kPooledArrayBytes);
  ASSERT_GE(sizeof(Eigen::Vector3d) * group * meshes.num_triangles(), kPooledArrayBytes);
  meshik::release_pooled_pages();
  const std::vector<double> fresh = pose(meshes, 1);
  // The pool full of quiet NaNs before the set is built; the pose on as many threads as examples
  // (the same bits as on 1).
  auto* poison = static_cast<double*>(meshik::take_pages(kPoolCapacityBytes));
  for (size_t e = 0; e < kPoolCapacityBytes / sizeof(double); ++e)
    poison[e] = std::numeric_limits<double>::quiet_NaN();
  meshik::give_pages(poison, kPoolCapacityBytes);
  ASSERT_EQ(pooled_bytes(), kPoolCapacityBytes);
  EXPECT_TRUE(same_bits(pose(meshes, static_cast<int>(group)), fresh));
}

}  // namespace
