// The process-wide cache of system analyses by connectivity (analysis_cache.h): a second
// ExampleSet of the same triangles shares the first one's analysis (a hit) and poses to the same
// bits as with an analysis of its own; other triangles miss; the cache keeps its bounds; and
// ExampleSets built on several threads at once agree.
#include <gtest/gtest.h>

#include <memory>
#include <thread>
#include <vector>

#include "analysis_cache.h"
#include "example_set_impl.h"
#include "test_meshik_support.h"

namespace {

using meshik::ExampleSet;
using meshik::Solver;
using meshik_test::ExampleMeshes;

std::shared_ptr<ExampleSet> example_set(const ExampleMeshes& meshes, int threads = 0) {
  return std::make_shared<ExampleSet>(meshes.view(), meshes.example_pointers(), meshik::ProgressCallback{}, threads);
}

// A pose of the set: 8 farthest-point handles moved to their places in the first example.
meshik::SolveResult pose(const std::shared_ptr<ExampleSet>& set, const ExampleMeshes& meshes) {
  const std::vector<int> handles = meshik_test::farthest_point_handles(meshes.rest, 8);
  const std::vector<double> targets = meshik_test::gather_rows(meshes.examples[0], handles);
  return Solver(set, handles).solve(targets.data());
}

TEST(AnalysisCache, SecondExampleSetOfTheSameTrianglesSharesTheAnalysis) {
  meshik::clear_analysis_cache();
  const ExampleMeshes first = meshik_test::make_tube_examples(31, 16, 2.0);
  const ExampleMeshes second = meshik_test::make_tube_examples(31, 16, 1.0);  // other positions
  ASSERT_EQ(first.triangles, second.triangles);
  ASSERT_NE(first.examples[1], second.examples[1]);
  const auto a = example_set(first);
  EXPECT_EQ(meshik::analysis_cache_stats().misses, 1);
  EXPECT_EQ(meshik::analysis_cache_stats().hits, 0);
  EXPECT_EQ(meshik::analysis_cache_stats().entries, 1u);
  const auto b = example_set(second);
  EXPECT_EQ(meshik::analysis_cache_stats().hits, 1);
  EXPECT_EQ(&a->impl().system_analysis.analyzed_pattern(), &b->impl().system_analysis.analyzed_pattern());
  EXPECT_EQ(b->impl().phase_times.back().first, "analysis (cached)");
  // The same bits as an ExampleSet that analysed the pattern itself.
  meshik::clear_analysis_cache();
  const auto fresh = example_set(second);
  EXPECT_EQ(meshik::analysis_cache_stats().misses, 1);
  EXPECT_NE(&fresh->impl().system_analysis.analyzed_pattern(), &b->impl().system_analysis.analyzed_pattern());
  EXPECT_EQ(fresh->impl().system_values, b->impl().system_values);
  const meshik::SolveResult cached = pose(b, second), own = pose(fresh, second);
  ASSERT_GE(own.iterations, 1);
  EXPECT_EQ(cached.vertices, own.vertices);
  EXPECT_EQ(cached.weights, own.weights);
}

TEST(AnalysisCache, OtherTrianglesMiss) {
  meshik::clear_analysis_cache();
  ExampleMeshes meshes = meshik_test::make_tube_examples(9, 10);
  example_set(meshes);
  example_set(meshik_test::make_tube_examples(9, 11));  // another vertex count
  std::swap(meshes.triangles[0], meshes.triangles[1]);  // one triangle turned over
  example_set(meshes);
  const meshik::AnalysisCacheStats stats = meshik::analysis_cache_stats();
  EXPECT_EQ(stats.hits, 0);
  EXPECT_EQ(stats.misses, 3);
  EXPECT_EQ(stats.entries, 3u);
}

TEST(AnalysisCache, KeepsItsBoundsDroppingTheLeastRecentlyUsed) {
  meshik::clear_analysis_cache();
  const int sets = static_cast<int>(meshik::kAnalysisCacheEntries) + 2;
  for (int i = 0; i < sets; ++i) {
    example_set(meshik_test::make_tube_examples(6, 5 + i));
    EXPECT_LE(meshik::analysis_cache_stats().entries, meshik::kAnalysisCacheEntries);
    EXPECT_LE(meshik::analysis_cache_stats().bytes, meshik::kAnalysisCacheBytes);
    EXPECT_GT(meshik::analysis_cache_stats().bytes, 0u);
  }
  EXPECT_EQ(meshik::analysis_cache_stats().entries, meshik::kAnalysisCacheEntries);
  example_set(meshik_test::make_tube_examples(6, 5 + sets - 1));  // the newest: kept
  EXPECT_EQ(meshik::analysis_cache_stats().hits, 1);
  example_set(meshik_test::make_tube_examples(6, 5));  // the oldest: dropped
  EXPECT_EQ(meshik::analysis_cache_stats().hits, 1);
  EXPECT_EQ(meshik::analysis_cache_stats().misses, sets + 1);
}

TEST(AnalysisCache, ExampleSetsBuiltOnSeveralThreadsAtOnceAgree) {
  meshik::clear_analysis_cache();
  const ExampleMeshes meshes = meshik_test::make_tube_examples(31, 16);
  std::vector<std::shared_ptr<ExampleSet>> sets(4);
  std::vector<std::thread> builders;
  for (size_t i = 0; i < sets.size(); ++i)
    builders.emplace_back([&, i] { sets[i] = example_set(meshes, 1); });
  for (std::thread& t : builders) t.join();
  const meshik::AnalysisCacheStats stats = meshik::analysis_cache_stats();
  EXPECT_EQ(stats.hits + stats.misses, 4);
  EXPECT_EQ(stats.entries, 1u);
  const meshik::SolveResult first = pose(sets[0], meshes);
  for (size_t i = 1; i < sets.size(); ++i) {
    EXPECT_EQ(sets[i]->impl().system_values, sets[0]->impl().system_values);
    EXPECT_EQ(pose(sets[i], meshes).vertices, first.vertices) << "set " << i;
  }
}

}  // namespace
