#include "sdflow/reconstruct/point_normals.h"

#include "sdflow/errors.h"
#include "sdflow/log.h"
#include "sdflow/spatial/detail/point_kd_tree.h"

#include <Eigen/Cholesky>
#include <Eigen/Eigenvalues>
#include <fmt/format.h>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <queue>
#include <utility>
#include <vector>

namespace sdflow {
namespace {

using detail::PointAdaptor;
using KdTree = detail::PointKdTree;

constexpr std::size_t parallel_grain = 512;

//! Adjacency lists of an undirected graph (compressed rows).
struct Graph {
  std::vector<int> offsets; //!< n + 1 entries
  std::vector<int> targets;
  int size() const { return static_cast<int>(offsets.size()) - 1; }
};

//! The symmetric closure of the k-NN relation over the points with keep[i] (all when empty),
//! renumbered by `index` (kept points only).
Graph knn_graph(const NeighbourTable& neighbours, const std::vector<int>& index, int kept)
{
  const auto n = static_cast<int>(neighbours.rows());
  auto id = [&](int i) { return index.empty() ? i : index[i]; };
  Graph g;
  g.offsets.assign(kept + 1, 0);
  for (int i = 0; i < n; ++i) {
    if (id(i) < 0)
      continue;
    for (Eigen::Index c = 0; c < neighbours.cols(); ++c) {
      const int j = neighbours(i, c);
      if (j == i || id(j) < 0)
        continue;
      ++g.offsets[id(i) + 1];
      ++g.offsets[id(j) + 1];
    }
  }
  for (int i = 0; i < kept; ++i)
    g.offsets[i + 1] += g.offsets[i];
  g.targets.resize(g.offsets.back());
  std::vector<int> fill(g.offsets.begin(), g.offsets.end() - 1);
  for (int i = 0; i < n; ++i) {
    if (id(i) < 0)
      continue;
    for (Eigen::Index c = 0; c < neighbours.cols(); ++c) {
      const int j = neighbours(i, c);
      if (j == i || id(j) < 0)
        continue;
      g.targets[fill[id(i)]++] = id(j);
      g.targets[fill[id(j)]++] = id(i);
    }
  }
  // A pair that are each other's neighbours appears twice: keep one copy.
  int write = 0;
  for (int i = 0; i < kept; ++i) {
    const int begin = g.offsets[i], end = g.offsets[i + 1];
    std::sort(g.targets.begin() + begin, g.targets.begin() + end);
    g.offsets[i] = write;
    for (int e = begin; e < end; ++e)
      if (e == begin || g.targets[e] != g.targets[e - 1])
        g.targets[write++] = g.targets[e];
  }
  g.offsets[kept] = write;
  g.targets.resize(write);
  return g;
}

//! The connected component of each node of `graph` (numbered from 0 in order of their first node);
//! `count` receives their number.
std::vector<int> graph_components(const Graph& graph, int& count)
{
  const int n = graph.size();
  std::vector<int> component(n, -1);
  std::vector<int> stack;
  count = 0;
  for (int s = 0; s < n; ++s) {
    if (component[s] >= 0)
      continue;
    component[s] = count;
    stack.push_back(s);
    while (!stack.empty()) {
      const int i = stack.back();
      stack.pop_back();
      for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e)
        if (component[graph.targets[e]] < 0) {
          component[graph.targets[e]] = count;
          stack.push_back(graph.targets[e]);
        }
    }
    ++count;
  }
  return component;
}

//! Orients `normals` in place along Prim's minimum spanning tree of each connected component of
//! `graph`; returns the number of components.
int orient_along_spanning_trees(const VertexVectors& points, VertexVectors& normals, const Graph& graph)
{
  const int n = graph.size();
  // Components first, so each gets its own seed at an extreme point.
  int components = 0;
  const std::vector<int> component = graph_components(graph, components);
  // extreme[c][2 d] has the smallest coordinate d in component c, extreme[c][2 d + 1] the largest.
  std::vector<std::array<int, 6>> extreme(components, {-1, -1, -1, -1, -1, -1});
  for (int i = 0; i < n; ++i) {
    auto& ex = extreme[component[i]];
    for (int d = 0; d < 3; ++d) {
      if (ex[2 * d] < 0 || points(i, d) < points(ex[2 * d], d))
        ex[2 * d] = i;
      if (ex[2 * d + 1] < 0 || points(i, d) > points(ex[2 * d + 1], d))
        ex[2 * d + 1] = i;
    }
  }

  std::vector<char> done(n, 0);
  std::vector<double> best(n, std::numeric_limits<double>::infinity());
  using Entry = std::pair<double, std::pair<int, int>>; // weight, (point, tree parent)
  std::priority_queue<Entry, std::vector<Entry>, std::greater<>> heap;
  for (int c = 0; c < components; ++c) {
    // At the extreme point along ±e_d of a closed surface the outward normal is ±e_d; pick the
    // axis the normal there follows best, so the sign decision is clear-cut.
    int seed = -1, axis = 0, outward = 1;
    double alignment = -1;
    for (int d = 0; d < 3; ++d)
      for (int side = 0; side < 2; ++side) {
        const int i = extreme[c][2 * d + side];
        if (std::abs(normals(i, d)) > alignment) {
          alignment = std::abs(normals(i, d));
          seed = i;
          axis = d;
          outward = side == 0 ? -1 : 1;
        }
      }
    if (outward * normals(seed, axis) < 0)
      normals.row(seed) *= -1;

    heap.push({0.0, {seed, seed}});
    while (!heap.empty()) {
      const auto [weight, link] = heap.top();
      heap.pop();
      const auto [i, parent] = link;
      if (done[i])
        continue;
      done[i] = 1;
      if (normals.row(i).dot(normals.row(parent)) < 0)
        normals.row(i) *= -1;
      for (int e = graph.offsets[i]; e < graph.offsets[i + 1]; ++e) {
        const int j = graph.targets[e];
        if (done[j])
          continue;
        const double w = 1.0 - std::abs(normals.row(i).dot(normals.row(j)));
        if (w < best[j]) {
          best[j] = w;
          heap.push({w, {j, i}});
        }
      }
    }
  }
  return components;
}

//! Unit normal of the degree-2 jet fitted to the neighbourhood `row` of point i.
Eigen::Vector3d fit_jet_normal(const VertexVectors& points, const int* row, Eigen::Index k, int i)
{
  const Eigen::Vector3d p = points.row(i).transpose();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  for (Eigen::Index c = 0; c < k; ++c)
    centroid += points.row(row[c]).transpose();
  centroid /= static_cast<double>(k);
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  for (Eigen::Index c = 0; c < k; ++c) {
    const Eigen::Vector3d d = points.row(row[c]).transpose() - centroid;
    covariance += d * d.transpose();
  }
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> pca;
  pca.computeDirect(covariance);
  // Eigenvalues ascend: the least-spread axis is the first guess at the normal, the height axis
  // of the jet; the other two span the fitting plane.
  const Eigen::Vector3d w = pca.eigenvectors().col(0);
  const Eigen::Vector3d u = pca.eigenvectors().col(2);
  const Eigen::Vector3d v = w.cross(u);

  // Coordinates relative to p, scaled by the mean in-plane distance so the normal equations of
  // the monomials 1, x, y, x², xy, y² are well conditioned whatever the sampling scale.
  double scale = 0;
  for (Eigen::Index c = 0; c < k; ++c) {
    const Eigen::Vector3d d = points.row(row[c]).transpose() - p;
    scale += std::hypot(d.dot(u), d.dot(v));
  }
  scale /= static_cast<double>(k);
  if (!(scale > 0))
    return w;
  Eigen::Matrix<double, 6, 6> normal_matrix = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 1> rhs = Eigen::Matrix<double, 6, 1>::Zero();
  for (Eigen::Index c = 0; c < k; ++c) {
    const Eigen::Vector3d d = points.row(row[c]).transpose() - p;
    const double x = d.dot(u) / scale, y = d.dot(v) / scale, z = d.dot(w) / scale;
    Eigen::Matrix<double, 6, 1> m;
    m << 1, x, y, x * x, x * y, y * y;
    normal_matrix.selfadjointView<Eigen::Lower>().rankUpdate(m);
    rhs += z * m;
  }
  Eigen::LDLT<Eigen::Matrix<double, 6, 6>, Eigen::Lower> ldlt(normal_matrix);
  // Collinear or clustered neighbourhoods leave the quadratic terms undetermined.
  constexpr double min_reciprocal_condition = 1e-12;
  if (ldlt.info() != Eigen::Success || !(ldlt.rcond() > min_reciprocal_condition))
    return w;
  const Eigen::Matrix<double, 6, 1> a = ldlt.solve(rhs);
  // The graph z = J(x, y) has normal (-J_x, -J_y, 1) at the origin (scales cancel for z/x, z/y).
  const Eigen::Vector3d n = (w - a(1) * u - a(2) * v).normalized();
  return n.allFinite() ? n : w;
}

std::vector<int> disagreeing_points(const VertexVectors& normals, const NeighbourTable& neighbours,
                                    const OrientationOptions& options)
{
  const double min_cosine = std::cos(options.agreement_angle);
  std::vector<int> inconsistent;
  for (Eigen::Index i = 0; i < neighbours.rows(); ++i) {
    int agreeing = 0, total = 0;
    for (Eigen::Index c = 0; c < neighbours.cols(); ++c) {
      const int j = neighbours(i, c);
      if (j == i)
        continue;
      ++total;
      agreeing += normals.row(i).dot(normals.row(j)) >= min_cosine;
    }
    if (agreeing < options.min_agreement * total)
      inconsistent.push_back(static_cast<int>(i));
  }
  return inconsistent;
}

void check_options(const OrientationOptions& options)
{
  if (!(options.agreement_angle > 0 && options.agreement_angle < M_PI))
    throw InvalidParameter(fmt::format("orientation: agreement_angle {} is not in (0, π)", options.agreement_angle));
  if (!(options.min_agreement >= 0 && options.min_agreement <= 1))
    throw InvalidParameter(fmt::format("orientation: min_agreement {} is not in [0, 1]", options.min_agreement));
}

} // namespace

NeighbourTable nearest_neighbours(const VertexVectors& points, int k)
{
  const auto n = static_cast<int>(points.rows());
  if (k < 2 || k > n)
    throw InvalidParameter(fmt::format("nearest_neighbours: k = {} is not in [2, {}] (the number of points)", k, n));
  for (int i = 0; i < n; ++i)
    if (!points.row(i).allFinite())
      throw InvalidMesh(fmt::format("nearest_neighbours: point {} has a non-finite coordinate", i));
  const PointAdaptor adaptor{points};
  KdTree tree(3, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(10));
  NeighbourTable table(n, k);
  tbb::parallel_for(tbb::blocked_range<int>(0, n, parallel_grain), [&](const tbb::blocked_range<int>& range) {
    std::vector<std::uint32_t> index(k);
    std::vector<double> distance(k);
    for (int i = range.begin(); i != range.end(); ++i) {
      const double query[3] = {points(i, 0), points(i, 1), points(i, 2)};
      tree.knnSearch(query, static_cast<std::size_t>(k), index.data(), distance.data());
      // With duplicates, point i may be missing from its own list; it belongs first.
      int self = k - 1;
      for (int c = 0; c < k; ++c)
        if (static_cast<int>(index[c]) == i) {
          self = c;
          break;
        }
      table(i, 0) = i;
      for (int c = 0, out = 1; c < k; ++c)
        if (c != self)
          table(i, out++) = static_cast<int>(index[c]);
    }
  });
  return table;
}

VertexVectors jet_normals(const VertexVectors& points, const NeighbourTable& neighbours)
{
  if (neighbours.rows() != points.rows())
    throw InvalidParameter(fmt::format("jet_normals: neighbour table has {} rows for {} points",
                                       neighbours.rows(), points.rows()));
  constexpr int jet_coefficients = 6;
  if (neighbours.cols() < jet_coefficients)
    throw InvalidParameter(fmt::format("jet_normals: a degree-2 jet needs at least {} neighbours, got {}",
                                       jet_coefficients, neighbours.cols()));
  const auto n = static_cast<int>(points.rows());
  VertexVectors normals(n, 3);
  tbb::parallel_for(tbb::blocked_range<int>(0, n, parallel_grain), [&](const tbb::blocked_range<int>& range) {
    for (int i = range.begin(); i != range.end(); ++i)
      normals.row(i) = fit_jet_normal(points, neighbours.row(i).data(), neighbours.cols(), i).transpose();
  });
  return normals;
}

NormalOrientation orient_normals(const VertexVectors& points, const VertexVectors& normals,
                                 const NeighbourTable& neighbours, const OrientationOptions& options)
{
  check_options(options);
  if (normals.rows() != points.rows() || neighbours.rows() != points.rows())
    throw InvalidParameter(fmt::format("orient_normals: {} points, {} normals, {} neighbour rows",
                                       points.rows(), normals.rows(), neighbours.rows()));
  NormalOrientation result;
  result.normals = normals;
  const Graph graph = knn_graph(neighbours, {}, static_cast<int>(points.rows()));
  result.components = orient_along_spanning_trees(points, result.normals, graph);
  result.inconsistent = disagreeing_points(result.normals, neighbours, options);
  return result;
}

namespace {

//! Oriented points as oriented_point_normals makes them, and the k-NN graph over the points kept
//! along which they were last oriented.
struct OrientedAlongGraph {
  OrientedPoints oriented;
  Graph graph;
};

OrientedAlongGraph orient_and_drop(const VertexVectors& points, const PointNormalsOptions& options)
{
  const NeighbourTable neighbours = nearest_neighbours(points, options.neighbours);
  NormalOrientation orientation =
      orient_normals(points, jet_normals(points, neighbours), neighbours, options.orientation);

  const auto n = static_cast<int>(points.rows());
  std::vector<int> index(n, 0);
  for (int i : orientation.inconsistent)
    index[i] = -1;
  OrientedAlongGraph along;
  OrientedPoints& result = along.oriented;
  result.removed = std::move(orientation.inconsistent);
  const int kept = n - static_cast<int>(result.removed.size());
  result.points.resize(kept, 3);
  result.normals.resize(kept, 3);
  result.source.reserve(kept);
  for (int i = 0; i < n; ++i)
    if (index[i] == 0) {
      index[i] = static_cast<int>(result.source.size());
      result.points.row(index[i]) = points.row(i);
      result.normals.row(index[i]) = orientation.normals.row(i);
      result.source.push_back(i);
    }
  along.graph = knn_graph(neighbours, index, kept);
  if (!result.removed.empty()) {
    const int components = orient_along_spanning_trees(result.points, result.normals, along.graph);
    logger().debug("point normals: {} of {} points removed as inconsistently oriented; {} components remain",
                   result.removed.size(), n, components);
  }
  return along;
}

} // namespace

OrientedPoints oriented_point_normals(const VertexVectors& points, const PointNormalsOptions& options)
{
  return orient_and_drop(points, options).oriented;
}

OrientedPoints oriented_point_normals(const Mesh& mesh, const PointNormalsOptions& options)
{
  return oriented_point_normals(vertex_positions(mesh), options);
}

OrientedPoints normals_oriented_by_reference(const VertexVectors& points, const VertexVectors& reference,
                                             const PointNormalsOptions& options)
{
  if (reference.rows() != points.rows())
    throw InvalidParameter(fmt::format("normals_oriented_by_reference: {} points, {} reference normals",
                                       points.rows(), reference.rows()));
  OrientedAlongGraph along = orient_and_drop(points, options);
  OrientedPoints& result = along.oriented;
  int count = 0;
  const std::vector<int> component = graph_components(along.graph, count);
  std::vector<double> agreement(static_cast<std::size_t>(count), 0);
  for (Eigen::Index i = 0; i < result.points.rows(); ++i)
    agreement[static_cast<std::size_t>(component[static_cast<std::size_t>(i)])] +=
        result.normals.row(i).dot(reference.row(result.source[static_cast<std::size_t>(i)]));
  for (Eigen::Index i = 0; i < result.points.rows(); ++i)
    if (agreement[static_cast<std::size_t>(component[static_cast<std::size_t>(i)])] < 0)
      result.normals.row(i) *= -1;
  return result;
}

} // namespace sdflow
