#include "sdflow/retri/bvh.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sdflow {
namespace {

//! Nearest point of triangle (a, b, c) to p by Voronoi regions of its corners, edges and interior
//! (Ericson 2005, Real-Time Collision Detection §5.1.5). Returns the barycentric weights.
Eigen::Vector3d closest_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                    const Eigen::Vector3d& c)
{
  const Eigen::Vector3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0)
    return {1, 0, 0};
  const Eigen::Vector3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3)
    return {0, 1, 0};
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) {
    const double v = d1 / (d1 - d3);
    return {1 - v, v, 0};
  }
  const Eigen::Vector3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6)
    return {0, 0, 1};
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) {
    const double w = d2 / (d2 - d6);
    return {1 - w, 0, w};
  }
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && d4 - d3 >= 0 && d5 - d6 >= 0) {
    const double w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
    return {0, 1 - w, w};
  }
  const double sum = va + vb + vc;
  if (sum > 0) {
    const double v = vb / sum, w = vc / sum;
    return {1 - v - w, v, w};
  }
  // A degenerate (collinear) triangle: its nearest point lies on one of its edges.
  Eigen::Vector3d best(1, 0, 0);
  double best_d = (p - a).squaredNorm();
  const Eigen::Vector3d corners[3] = {a, b, c};
  for (int e = 0; e < 3; ++e) {
    const Eigen::Vector3d& s = corners[e];
    const Eigen::Vector3d d = corners[(e + 1) % 3] - s;
    const double len2 = d.squaredNorm();
    const double t = len2 > 0 ? std::clamp((p - s).dot(d) / len2, 0.0, 1.0) : 0.0;
    const double dist = (s + t * d - p).squaredNorm();
    if (dist < best_d) {
      best_d = dist;
      best.setZero();
      best[e] = 1 - t;
      best[(e + 1) % 3] = t;
    }
  }
  return best;
}

} // namespace

Bvh::Bvh(const VertexVectors& positions, const Triangles& triangles, const BvhOptions& options)
{
  copy_positions(positions);
  const int n = vertex_count();
  triangles_.resize(triangles.rows());
  for (Eigen::Index t = 0; t < triangles.rows(); ++t) {
    for (int k = 0; k < 3; ++k) {
      const int v = triangles(t, k);
      if (v < 0 || v >= n)
        throw InvalidMesh(fmt::format("Bvh: triangle {} names vertex {}, outside the {} vertices", t, v, n));
      triangles_[t][k] = v;
    }
  }
  build(options);
}

Bvh::Bvh(const Mesh& mesh, const BvhOptions& options)
{
  copy_positions(vertex_positions(mesh));
  triangles_.resize(mesh.n_faces());
  for (auto f : mesh.all_faces()) {
    if (mesh.status(f).deleted())
      throw InvalidMesh(fmt::format("Bvh: face {} is deleted; garbage-collect the mesh first", f.idx()));
    auto h = f.halfedge();
    triangles_[f.idx()] = {h.from().idx(), h.to().idx(), h.next().to().idx()};
  }
  build(options);
}

void Bvh::copy_positions(const VertexVectors& positions)
{
  points_.resize(3 * static_cast<std::size_t>(positions.rows()));
  for (Eigen::Index v = 0; v < positions.rows(); ++v)
    for (int k = 0; k < 3; ++k) {
      const double x = positions(v, k);
      if (!std::isfinite(x))
        throw InvalidMesh(fmt::format("Bvh: vertex {} has a non-finite coordinate", v));
      points_[3 * v + k] = x;
    }
}

void Bvh::compute_triangle_boxes()
{
  triangle_box_.resize(triangles_.size());
  for (std::size_t t = 0; t < triangles_.size(); ++t) {
    Aabb box;
    for (int v : triangles_[t])
      box.extend(point(v));
    triangle_box_[t] = box;
  }
}

void Bvh::build(const BvhOptions& options)
{
  if (options.max_leaf_size < 1)
    throw InvalidParameter(fmt::format("Bvh: max_leaf_size must be at least 1, not {}", options.max_leaf_size));
  if (options.sah_bins < 2)
    throw InvalidParameter(fmt::format("Bvh: sah_bins must be at least 2, not {}", options.sah_bins));
  compute_triangle_boxes();
  const int count = triangle_count();
  nodes_.clear();
  slot_triangle_.resize(count);
  std::iota(slot_triangle_.begin(), slot_triangle_.end(), 0);
  if (count == 0) {
    slot_box_.clear();
    return;
  }
  std::vector<std::array<double, 3>> centre(count);
  for (int t = 0; t < count; ++t)
    for (int k = 0; k < 3; ++k)
      centre[t][k] = 0.5 * (triangle_box_[t].lo[k] + triangle_box_[t].hi[k]);

  struct Task {
    int node, begin, end;
  };
  struct Bin {
    Aabb box;
    int count = 0;
  };
  const int bins = options.sah_bins;
  std::vector<Bin> bin(bins);
  std::vector<double> right_area(bins);
  std::vector<int> right_count(bins);
  nodes_.reserve(2 * (count / options.max_leaf_size) + 2);
  nodes_.emplace_back();
  std::vector<Task> tasks = {{0, 0, count}};
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    Aabb box, centres;
    for (int i = task.begin; i < task.end; ++i) {
      box.extend(triangle_box_[slot_triangle_[i]]);
      centres.extend(centre[slot_triangle_[i]].data());
    }
    nodes_[task.node].box = box;
    const int n = task.end - task.begin;
    if (n <= options.max_leaf_size) {
      nodes_[task.node].first = task.begin;
      nodes_[task.node].count = n;
      continue;
    }
    int axis = 0;
    for (int k = 1; k < 3; ++k)
      if (centres.hi[k] - centres.lo[k] > centres.hi[axis] - centres.lo[axis])
        axis = k;
    const double lo = centres.lo[axis], extent = centres.hi[axis] - centres.lo[axis];
    int mid = task.begin + n / 2;
    if (extent > 0) {
      // Binned SAH along the widest centroid axis: cost of a split = Σ side count × side area.
      const double scale = bins / extent;
      auto bin_of = [&](int t) { return std::min(bins - 1, static_cast<int>((centre[t][axis] - lo) * scale)); };
      std::fill(bin.begin(), bin.end(), Bin{});
      for (int i = task.begin; i < task.end; ++i) {
        Bin& b = bin[bin_of(slot_triangle_[i])];
        b.box.extend(triangle_box_[slot_triangle_[i]]);
        ++b.count;
      }
      Aabb acc;
      int acc_count = 0;
      for (int b = bins - 1; b > 0; --b) {
        acc.extend(bin[b].box);
        acc_count += bin[b].count;
        right_area[b] = acc.half_area();
        right_count[b] = acc_count;
      }
      acc = Aabb{};
      acc_count = 0;
      double best_cost = std::numeric_limits<double>::infinity();
      int best = -1;
      for (int b = 0; b + 1 < bins; ++b) {
        acc.extend(bin[b].box);
        acc_count += bin[b].count;
        if (acc_count == 0 || right_count[b + 1] == 0)
          continue;
        const double cost = acc_count * acc.half_area() + right_count[b + 1] * right_area[b + 1];
        if (cost < best_cost) {
          best_cost = cost;
          best = b;
        }
      }
      if (best >= 0) {
        auto split = std::partition(slot_triangle_.begin() + task.begin, slot_triangle_.begin() + task.end,
                                    [&](int t) { return bin_of(t) <= best; });
        mid = static_cast<int>(split - slot_triangle_.begin());
      } else {
        // Every centroid fell in one bin: split at the median centroid instead.
        std::nth_element(slot_triangle_.begin() + task.begin, slot_triangle_.begin() + mid,
                         slot_triangle_.begin() + task.end,
                         [&](int s, int t) { return centre[s][axis] < centre[t][axis]; });
      }
    }
    // Coincident centroids (extent 0) keep mid = the middle slot: any split is as good.
    const int left = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    nodes_[task.node].first = left;
    nodes_[task.node].count = 0;
    tasks.push_back({left + 1, mid, task.end});
    tasks.push_back({left, task.begin, mid});
  }
  slot_box_.resize(count);
  for (int i = 0; i < count; ++i)
    slot_box_[i] = triangle_box_[slot_triangle_[i]];
}

void Bvh::refit(const VertexVectors& positions)
{
  if (positions.rows() != vertex_count())
    throw InvalidParameter(fmt::format("Bvh::refit: {} positions given for a tree over {} vertices", positions.rows(),
                                       vertex_count()));
  copy_positions(positions);
  compute_triangle_boxes();
  refit_nodes();
}

void Bvh::refit(const Mesh& mesh)
{
  if (static_cast<int>(mesh.n_faces()) != triangle_count())
    throw InvalidParameter(fmt::format("Bvh::refit: the mesh has {} faces, the tree {} triangles", mesh.n_faces(),
                                       triangle_count()));
  refit(vertex_positions(mesh));
}

void Bvh::refit_nodes()
{
  for (std::size_t i = 0; i < slot_triangle_.size(); ++i)
    slot_box_[i] = triangle_box_[slot_triangle_[i]];
  // Children always follow their parent in the array, so a backward sweep sees them first.
  for (auto node = nodes_.rbegin(); node != nodes_.rend(); ++node) {
    Aabb box;
    if (node->leaf()) {
      for (int i = node->first; i < node->first + node->count; ++i)
        box.extend(slot_box_[i]);
    } else {
      box = nodes_[node->first].box;
      box.extend(nodes_[node->first + 1].box);
    }
    node->box = box;
  }
}

std::vector<std::pair<int, int>> Bvh::overlapping_pairs(double margin) const
{
  std::vector<std::pair<int, int>> pairs;
  for_each_overlapping_pair([&](int s, int t) { pairs.emplace_back(std::min(s, t), std::max(s, t)); }, margin);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

std::vector<std::pair<int, int>> Bvh::overlapping_pairs(const Bvh& other, double margin) const
{
  std::vector<std::pair<int, int>> pairs;
  for_each_overlapping_pair(other, [&](int s, int t) { pairs.emplace_back(s, t); }, margin);
  std::sort(pairs.begin(), pairs.end());
  return pairs;
}

ClosestPoint Bvh::closest_point(const Eigen::Vector3d& query, double max_squared_distance) const
{
  ClosestPoint best;
  best.squared_distance = max_squared_distance;
  if (nodes_.empty())
    return best;
  const double q[3] = {query.x(), query.y(), query.z()};
  // Depth-first, nearer child first, pruning boxes farther than the best triangle so far.
  std::vector<std::pair<double, std::int32_t>> stack;
  stack.reserve(64);
  stack.emplace_back(nodes_.front().box.squared_distance(q), 0);
  while (!stack.empty()) {
    const auto [box_distance, index] = stack.back();
    stack.pop_back();
    if (box_distance > best.squared_distance || (best.face >= 0 && box_distance == best.squared_distance))
      continue;
    const Node& node = nodes_[index];
    if (node.leaf()) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (slot_box_[i].squared_distance(q) > best.squared_distance)
          continue;
        const int t = slot_triangle_[i];
        const auto& [a, b, c] = triangles_[t];
        const Eigen::Vector3d pa = Eigen::Map<const Eigen::Vector3d>(point(a));
        const Eigen::Vector3d pb = Eigen::Map<const Eigen::Vector3d>(point(b));
        const Eigen::Vector3d pc = Eigen::Map<const Eigen::Vector3d>(point(c));
        const Eigen::Vector3d w = closest_on_triangle(query, pa, pb, pc);
        const Eigen::Vector3d x = w[0] * pa + w[1] * pb + w[2] * pc;
        const double d = (x - query).squaredNorm();
        if (d < best.squared_distance || (best.face < 0 && d <= best.squared_distance)) {
          best = {t, x, w, d};
        }
      }
      continue;
    }
    const double dl = nodes_[node.first].box.squared_distance(q);
    const double dr = nodes_[node.first + 1].box.squared_distance(q);
    // Push the farther child first so the nearer one is searched first.
    if (dl <= dr) {
      stack.emplace_back(dr, node.first + 1);
      stack.emplace_back(dl, node.first);
    } else {
      stack.emplace_back(dl, node.first);
      stack.emplace_back(dr, node.first + 1);
    }
  }
  return best;
}

RayHit Bvh::first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction, double t_max) const
{
  RayHit hit;
  hit.t = t_max;
  if (nodes_.empty())
    return hit;
  const double o[3] = {origin.x(), origin.y(), origin.z()};
  const double inv[3] = {1.0 / direction.x(), 1.0 / direction.y(), 1.0 / direction.z()};
  // Slab test; a zero direction component gives ±inf bounds, and the NaN of (0 · inf) for an
  // origin on a slab plane is dropped by the argument order: std::max(near, NaN) returns near.
  auto enters = [&](const Aabb& box) {
    double near = 0.0, far = hit.t;
    for (int k = 0; k < 3; ++k) {
      const double t0 = (box.lo[k] - o[k]) * inv[k], t1 = (box.hi[k] - o[k]) * inv[k];
      near = std::max(near, std::min(t0, t1));
      far = std::min(far, std::max(t0, t1));
    }
    return near <= far;
  };
  std::vector<std::int32_t> stack;
  stack.reserve(64);
  stack.push_back(0);
  while (!stack.empty()) {
    const Node& node = nodes_[stack.back()];
    stack.pop_back();
    if (!enters(node.box))
      continue;
    if (!node.leaf()) {
      stack.push_back(node.first + 1);
      stack.push_back(node.first);
      continue;
    }
    for (int i = node.first; i < node.first + node.count; ++i) {
      const int t = slot_triangle_[i];
      const auto& [a, b, c] = triangles_[t];
      const Eigen::Vector3d pa = Eigen::Map<const Eigen::Vector3d>(point(a));
      const Eigen::Vector3d e1 = Eigen::Map<const Eigen::Vector3d>(point(b)) - pa;
      const Eigen::Vector3d e2 = Eigen::Map<const Eigen::Vector3d>(point(c)) - pa;
      const Eigen::Vector3d pvec = direction.cross(e2);
      const double det = e1.dot(pvec);
      if (det == 0)
        continue;
      const Eigen::Vector3d tvec = origin - pa;
      const double u = tvec.dot(pvec) / det;
      if (u < 0 || u > 1)
        continue;
      const Eigen::Vector3d qvec = tvec.cross(e1);
      const double v = direction.dot(qvec) / det;
      if (v < 0 || u + v > 1)
        continue;
      const double tt = e2.dot(qvec) / det;
      if (tt >= 0 && tt <= hit.t && (hit.face < 0 || tt < hit.t)) {
        hit.face = t;
        hit.t = tt;
        hit.barycentric = {1 - u - v, u, v};
      }
    }
  }
  return hit;
}

} // namespace sdflow
