// Regions of spatially varying blend weights from vertex groups or from the examples' deformations.
#include "blend_regions.h"

#include <algorithm>
#include <limits>
#include <string>

#include "mesh_topology.h"

namespace meshik {

namespace {

// Rings of neighbouring triangles over which a border is softened: each ring averages a triangle's
// shares with its edge neighbours' (the shares stay a partition of unity; a region's interior keeps
// alpha = 1 exactly).
constexpr int kBorderRings = 3;

// Lloyd iterations of the clustering, and the share of the features' spread that the automatic
// count must explain.
constexpr int kClusterIterations = 25;
constexpr double kExplainedSpread = 0.8;
constexpr int kMaxAutomaticRegions = 8;

// shares: #F by count, each row summing to one; averages each row with its edge neighbours'
// kBorderRings times.
void soften_borders(const TriangleAdjacency& adjacency, int count, std::vector<double>& shares) {
  const int m = static_cast<int>(adjacency.start.size()) - 1;
  std::vector<double> next(shares.size());
  for (int ring = 0; ring < kBorderRings; ++ring) {
    for (int j = 0; j < m; ++j) {
      const int degree = adjacency.start[j + 1] - adjacency.start[j];
      for (int r = 0; r < count; ++r) {
        double sum = shares[static_cast<size_t>(j) * count + r];
        for (int s = adjacency.start[j]; s < adjacency.start[j + 1]; ++s)
          sum += shares[static_cast<size_t>(adjacency.neighbour[s]) * count + r];
        next[static_cast<size_t>(j) * count + r] = sum / (degree + 1);
      }
    }
    shares.swap(next);
  }
}

// Fills everything but share and num_regions from them (share: #F by num_regions).
void finish_regions(const TriangleAdjacency& adjacency, double smoothness, BlendRegions& regions) {
  const int m = regions.num_triangles, count = regions.num_regions;
  const int batches = (m + kLanes - 1) / kLanes;
  regions.active_start.assign(1, 0);
  regions.active.clear();
  regions.whole_region.assign(batches, -1);
  for (int b = 0; b < batches; ++b) {
    const int first = b * kLanes, last = std::min(m, first + kLanes);
    for (int r = 0; r < count; ++r) {
      bool any = false, whole = true;
      for (int j = first; j < last; ++j) {
        const double a = regions.share[static_cast<size_t>(j) * count + r];
        any = any || a > 0.0;
        whole = whole && a == 1.0;
      }
      if (any) regions.active.push_back(r);
      if (whole) regions.whole_region[b] = r;
    }
    regions.active_start.push_back(static_cast<int>(regions.active.size()));
  }
  regions.smoothness = Eigen::MatrixXd::Zero(count, count);
  Eigen::VectorXd difference(count);
  for (int j = 0; j < m; ++j)
    for (int s = adjacency.start[j]; s < adjacency.start[j + 1]; ++s) {
      const int n = adjacency.neighbour[s];
      if (n <= j) continue;  // each edge once
      for (int r = 0; r < count; ++r)
        difference(r) = regions.share[static_cast<size_t>(j) * count + r] - regions.share[static_cast<size_t>(n) * count + r];
      if (difference.squaredNorm() > 0.0) regions.smoothness += smoothness * difference * difference.transpose();
    }
}

// Per triangle (internal order): how it moves across the examples, the displacement of its
// centroid from the rest in each example (3 #E values, one row of a #F by 3 #E matrix). The
// example poses are recovered from the features by the set's own blend at w = e_i (exact up to
// the features' rounding; translation by the examples' centroids).
Eigen::MatrixXd triangle_motion(const ExampleSet& examples) {
  const ExampleSet::Impl& set = examples.impl();
  const int m = set.num_triangles, k = set.num_examples;
  Eigen::MatrixXd motion(m, 3 * k);
  std::vector<double> unit(k, 0.0);
  for (int i = 0; i < k; ++i) {
    unit.assign(k, 0.0);
    unit[i] = 1.0;
    const std::vector<double> pose = set.to_internal(examples.blend(unit.data()).data());
    for (int j = 0; j < m; ++j)
      for (int c = 0; c < 3; ++c) {
        double sum = 0.0;
        for (int q = 0; q < 3; ++q) {
          const size_t v = 3 * static_cast<size_t>(set.triangles[3 * j + q]) + c;
          sum += pose[v] - set.rest[v];
        }
        motion(j, 3 * i + c) = sum / 3.0;
      }
  }
  return motion;
}

// k-means of the rows of features into count clusters (farthest-point seeds from the row farthest
// from the mean, then Lloyd iterations). Returns the label of each row; *spread: the sum of
// squared distances to the cluster means.
std::vector<int> cluster_rows(const Eigen::MatrixXd& features, int count, double* spread) {
  const int m = static_cast<int>(features.rows());
  Eigen::MatrixXd centers(count, features.cols());
  const Eigen::RowVectorXd mean = features.colwise().mean();
  Eigen::VectorXd nearest = (features.rowwise() - mean).rowwise().squaredNorm();
  for (int c = 0; c < count; ++c) {
    int farthest = 0;
    nearest.maxCoeff(&farthest);
    centers.row(c) = features.row(farthest);
    nearest = nearest.cwiseMin((features.rowwise() - centers.row(c)).rowwise().squaredNorm());
  }
  std::vector<int> label(m, 0);
  for (int iteration = 0; iteration <= kClusterIterations; ++iteration) {
    *spread = 0.0;
    for (int j = 0; j < m; ++j) {
      double best = std::numeric_limits<double>::infinity();
      for (int c = 0; c < count; ++c) {
        const double d = (features.row(j) - centers.row(c)).squaredNorm();
        if (d < best) best = d, label[j] = c;
      }
      *spread += best;
    }
    if (iteration == kClusterIterations) break;
    Eigen::MatrixXd sums = Eigen::MatrixXd::Zero(count, features.cols());
    std::vector<int> members(count, 0);
    for (int j = 0; j < m; ++j) sums.row(label[j]) += features.row(j), ++members[label[j]];
    for (int c = 0; c < count; ++c)
      if (members[c] > 0) centers.row(c) = sums.row(c) / members[c];
  }
  return label;
}

// labels (#F, in [0, count)) -> regions, numbered by first appearance (empty clusters dropped).
BlendRegions regions_from_labels(const ExampleSet::Impl& set, const TriangleAdjacency& adjacency,
                                 const std::vector<int>& label, int count, double smoothness) {
  std::vector<int> number(count, -1);
  int used = 0;
  for (int l : label)
    if (number[l] < 0) number[l] = used++;
  BlendRegions regions;
  regions.num_regions = used;
  regions.num_triangles = set.num_triangles;
  regions.share.assign(static_cast<size_t>(set.num_triangles) * used, 0.0);
  for (int j = 0; j < set.num_triangles; ++j) regions.share[static_cast<size_t>(j) * used + number[label[j]]] = 1.0;
  soften_borders(adjacency, used, regions.share);
  finish_regions(adjacency, smoothness, regions);
  return regions;
}

}  // namespace

BlendRegions regions_from_vertex_groups(const ExampleSet::Impl& set, const std::vector<int>& vertex_regions,
                                        double smoothness) {
  if (static_cast<int>(vertex_regions.size()) != set.num_vertices)
    throw InputError("vertex_regions has " + std::to_string(vertex_regions.size()) + " entries, the mesh " +
                     std::to_string(set.num_vertices) + " vertices");
  int groups = 0;
  bool ungrouped = false;
  for (size_t v = 0; v < vertex_regions.size(); ++v) {
    if (vertex_regions[v] < -1)
      throw InputError("vertex_regions: vertex " + std::to_string(v) + " has region " +
                       std::to_string(vertex_regions[v]) + " (expected -1 or more)");
    groups = std::max(groups, vertex_regions[v] + 1);
    ungrouped = ungrouped || vertex_regions[v] < 0;
  }
  const int count = groups + (ungrouped ? 1 : 0);
  const TriangleAdjacency adjacency = triangle_adjacency(set.triangles.data(), set.num_triangles, set.num_vertices);
  // Thirds per corner, in the internal order; the ungrouped vertices' region is the last.
  std::vector<double> share(static_cast<size_t>(set.num_triangles) * count, 0.0);
  for (int j = 0; j < set.num_triangles; ++j)
    for (int q = 0; q < 3; ++q) {
      const int region = vertex_regions[set.vertex_of_internal[set.triangles[3 * j + q]]];
      share[static_cast<size_t>(j) * count + (region < 0 ? groups : region)] += 1.0 / 3.0;
    }
  // A triangle wholly in one region has shares of exactly one there.
  for (double& a : share)
    if (a > 0.99) a = 1.0;
  BlendRegions regions;
  regions.num_regions = count;
  regions.num_triangles = set.num_triangles;
  regions.share = std::move(share);
  soften_borders(adjacency, count, regions.share);
  finish_regions(adjacency, smoothness, regions);
  return regions;
}

BlendRegions regions_from_examples(const ExampleSet& examples, int count, double smoothness) {
  const ExampleSet::Impl& set = examples.impl();
  const TriangleAdjacency adjacency = triangle_adjacency(set.triangles.data(), set.num_triangles, set.num_vertices);
  const int m = set.num_triangles;
  if (count == 1 || set.num_examples == 0) return regions_from_labels(set, adjacency, std::vector<int>(m, 0), 1, smoothness);
  const Eigen::MatrixXd features = triangle_motion(examples);
  if (count != kAutomaticRegions) {
    double spread = 0.0;
    return regions_from_labels(set, adjacency, cluster_rows(features, std::min(count, m), &spread), std::min(count, m),
                               smoothness);
  }
  const double total = (features.rowwise() - features.colwise().mean()).squaredNorm();
  std::vector<int> label;
  int chosen = 2;
  for (; chosen <= std::min(kMaxAutomaticRegions, m); ++chosen) {
    double spread = 0.0;
    label = cluster_rows(features, chosen, &spread);
    if (spread <= (1.0 - kExplainedSpread) * total) break;
  }
  return regions_from_labels(set, adjacency, label, std::min(chosen, std::min(kMaxAutomaticRegions, m)), smoothness);
}

}  // namespace meshik
