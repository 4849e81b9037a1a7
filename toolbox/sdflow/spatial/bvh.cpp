#include "sdflow/spatial/bvh.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <algorithm>
#include <cmath>
#include <numeric>

namespace sdflow {

namespace {

//! A float ≤ x, at most two units in the last place below it (|x| within float range). Without
//! branches: refits convert every box, and a data-dependent branch here mispredicts half the time.
float float_at_most(double x)
{
  const float f = static_cast<float>(x); // within half a unit of x
  return f - (std::abs(f) * 0x1p-23f + 0x1p-126f);
}

//! A float ≥ x, at most two units in the last place above it.
float float_at_least(double x) { return -float_at_most(-x); }

//! The 16 low bits of x moved to every third bit position (bit i to bit 3i).
std::uint64_t spread_bits(std::uint32_t x)
{
  std::uint64_t v = x & 0xffff;
  v = (v | v << 16) & 0x0000ff0000ffULL;
  v = (v | v << 8) & 0x00f00f00f00fULL;
  v = (v | v << 4) & 0x0c30c30c30c3ULL;
  v = (v | v << 2) & 0x249249249249ULL;
  return v;
}

//! Sort 48-bit `keys` and permute `values` along (least-significant-digit radix sort, 12-bit
//! digits: 4096 buckets stay in cache while scattering).
void sort_by_key(std::vector<std::uint64_t>& keys, std::vector<std::int32_t>& values)
{
  const std::size_t n = keys.size();
  std::vector<std::uint64_t> key_buffer(n);
  std::vector<std::int32_t> value_buffer(n);
  std::vector<std::size_t> offset(1 << 12);
  for (int shift = 0; shift < 48; shift += 12) {
    std::fill(offset.begin(), offset.end(), 0);
    for (std::uint64_t k : keys)
      ++offset[(k >> shift) & 0xfff];
    std::size_t sum = 0;
    for (auto& o : offset)
      sum += std::exchange(o, sum);
    for (std::size_t i = 0; i < n; ++i) {
      const std::size_t slot = offset[(keys[i] >> shift) & 0xfff]++;
      key_buffer[slot] = keys[i];
      value_buffer[slot] = values[i];
    }
    keys.swap(key_buffer);
    values.swap(value_buffer);
  }
}

} // namespace

Bvh::Bvh(const VertexVectors& positions, const FaceIndices& triangles, const BvhOptions& options)
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
      // Boxes are stored in float: keep well inside its range.
      if (!(std::abs(x) <= 1e30))
        throw InvalidMesh(fmt::format("Bvh: vertex {} has a coordinate that is not finite or beyond ±1e30 ({})", v, x));
      points_[3 * v + k] = x;
    }
}

Bvh::Box32 Bvh::Box32::outward(const Aabb& b)
{
  Box32 out;
  for (int k = 0; k < 3; ++k) {
    out.lo[k] = float_at_most(b.lo[k]);
    out.hi[k] = float_at_least(b.hi[k]);
  }
  return out;
}

float Bvh::float_gap(double margin) { return float_at_least(2.0 * margin); }

void Bvh::build(const BvhOptions& options)
{
  if (options.max_leaf_size < 1)
    throw InvalidParameter(fmt::format("Bvh: max_leaf_size must be at least 1, not {}", options.max_leaf_size));
  const int count = triangle_count();
  nodes_.clear();
  bounds_ = Aabb{};
  slot_triangle_.resize(count);
  std::iota(slot_triangle_.begin(), slot_triangle_.end(), 0);
  triangle_slot_.resize(count);
  slot_box_.resize(count);
  if (count == 0)
    return;

  // Morton codes of the centroids, quantised to 16 bits per axis over the centroids' bounds.
  std::vector<std::array<double, 3>> centroid(count);
  Aabb centroids;
  for (int t = 0; t < count; ++t) {
    const auto& [a, b, c] = triangles_[t];
    for (int k = 0; k < 3; ++k)
      centroid[t][k] = (point(a)[k] + point(b)[k] + point(c)[k]) / 3.0;
    centroids.extend(centroid[t].data());
  }
  std::vector<std::uint64_t> code(count);
  for (int t = 0; t < count; ++t) {
    std::uint64_t key = 0;
    for (int k = 0; k < 3; ++k) {
      const double extent = centroids.hi[k] - centroids.lo[k];
      const double unit = extent > 0 ? (centroid[t][k] - centroids.lo[k]) / extent : 0.0;
      key |= spread_bits(static_cast<std::uint32_t>(std::clamp(unit * 65536.0, 0.0, 65535.0))) << (2 - k);
    }
    code[t] = key;
  }
  sort_by_key(code, slot_triangle_);
  for (int i = 0; i < count; ++i)
    triangle_slot_[slot_triangle_[i]] = i;

  // Top-down: split each range where its highest differing Morton bit changes (a spatial median
  // of the curve); ranges of equal codes split at the middle. Children follow their parent.
  struct Task {
    int node, begin, end;
  };
  nodes_.reserve(2 * count / std::min(options.max_leaf_size, 2) + 1);
  nodes_.emplace_back();
  std::vector<Task> tasks = {{0, 0, count}};
  while (!tasks.empty()) {
    const Task task = tasks.back();
    tasks.pop_back();
    if (task.end - task.begin <= options.max_leaf_size) {
      nodes_[task.node].first = task.begin;
      nodes_[task.node].count = task.end - task.begin;
      continue;
    }
    int mid = task.begin + (task.end - task.begin) / 2;
    const std::uint64_t first = code[task.begin], last = code[task.end - 1];
    if (first != last) {
      const std::uint64_t bit = std::uint64_t{1} << (63 - std::countl_zero(first ^ last));
      mid = static_cast<int>(std::partition_point(code.begin() + task.begin, code.begin() + task.end,
                                                  [&](std::uint64_t c) { return (c & bit) == 0; }) -
                             code.begin());
    }
    const int left = static_cast<int>(nodes_.size());
    nodes_.emplace_back();
    nodes_.emplace_back();
    nodes_[task.node].first = left;
    nodes_[task.node].count = 0;
    tasks.push_back({left + 1, mid, task.end});
    tasks.push_back({left, task.begin, mid});
  }
  refit_nodes();
}

void Bvh::refit(const VertexVectors& positions)
{
  if (positions.rows() != vertex_count())
    throw InvalidParameter(fmt::format("Bvh::refit: {} positions given for a tree over {} vertices", positions.rows(),
                                       vertex_count()));
  copy_positions(positions);
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
  bounds_ = Aabb{};
  // Children always follow their parent in the array, so a backward sweep sees them first.
  for (auto node = nodes_.rbegin(); node != nodes_.rend(); ++node) {
    if (node->leaf()) {
      Aabb leaf;
      for (int i = node->first; i < node->first + node->count; ++i) {
        Aabb box;
        for (int v : triangles_[slot_triangle_[i]])
          box.extend(point(v));
        slot_box_[i] = Box32::outward(box);
        leaf.extend(box);
      }
      bounds_.extend(leaf);
      node->box = Box32::outward(leaf);
    } else {
      const Box32& l = nodes_[node->first].box;
      const Box32& r = nodes_[node->first + 1].box;
      for (int k = 0; k < 3; ++k) {
        node->box.lo[k] = std::min(l.lo[k], r.lo[k]);
        node->box.hi[k] = std::max(l.hi[k], r.hi[k]);
      }
    }
  }
}

std::vector<std::pair<int, int>> Bvh::traversal_seeds(int count, double margin) const
{
  std::vector<std::pair<int, int>> seeds;
  if (nodes_.empty())
    return seeds;
  const float gap = float_gap(margin);
  seeds.emplace_back(0, 0);
  // Expand every seed one level per sweep (as the traversal would) until there are enough.
  bool expanded = true;
  while (static_cast<int>(seeds.size()) < count && expanded) {
    expanded = false;
    std::vector<std::pair<int, int>> next;
    for (const auto& [a, b] : seeds) {
      const Node& na = nodes_[a];
      const Node& nb = nodes_[b];
      if (a == b && !na.leaf()) {
        next.emplace_back(na.first, na.first);
        next.emplace_back(na.first + 1, na.first + 1);
        next.emplace_back(na.first, na.first + 1);
        expanded = true;
      } else if (a != b && !na.box.overlaps(nb.box, gap)) {
        expanded = true; // contributes nothing
      } else if (a != b && !(na.leaf() && nb.leaf())) {
        if (nb.leaf() || (!na.leaf() && na.box.box().half_area() >= nb.box.box().half_area())) {
          next.emplace_back(na.first, b);
          next.emplace_back(na.first + 1, b);
        } else {
          next.emplace_back(a, nb.first);
          next.emplace_back(a, nb.first + 1);
        }
        expanded = true;
      } else {
        next.emplace_back(a, b);
      }
    }
    seeds.swap(next);
  }
  return seeds;
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
  stack.emplace_back(nodes_.front().box.box().squared_distance(q), 0);
  while (!stack.empty()) {
    const auto [box_distance, index] = stack.back();
    stack.pop_back();
    if (box_distance > best.squared_distance || (best.face >= 0 && box_distance == best.squared_distance))
      continue;
    const Node& node = nodes_[index];
    if (node.leaf()) {
      for (int i = node.first; i < node.first + node.count; ++i) {
        if (slot_box_[i].box().squared_distance(q) > best.squared_distance)
          continue;
        const int t = slot_triangle_[i];
        const auto& [a, b, c] = triangles_[t];
        const Eigen::Vector3d pa = Eigen::Map<const Eigen::Vector3d>(point(a));
        const Eigen::Vector3d pb = Eigen::Map<const Eigen::Vector3d>(point(b));
        const Eigen::Vector3d pc = Eigen::Map<const Eigen::Vector3d>(point(c));
        const Eigen::Vector3d w = nearest_barycentric(query, pa, pb, pc);
        const Eigen::Vector3d x = w[0] * pa + w[1] * pb + w[2] * pc;
        const double d = (x - query).squaredNorm();
        if (d < best.squared_distance || (best.face < 0 && d <= best.squared_distance)) {
          best = {t, x, w, d};
        }
      }
      continue;
    }
    const double dl = nodes_[node.first].box.box().squared_distance(q);
    const double dr = nodes_[node.first + 1].box.box().squared_distance(q);
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
    if (!enters(node.box.box()))
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
