#pragma once
//! \file bvh.h
//! \brief Bounding-volume hierarchy of axis-aligned boxes over the triangles of a surface: binned
//! surface-area-heuristic build (Wald 2007), refit after vertex motion, and queries for
//! overlapping triangle pairs (within one tree or between two), the closest surface point, ray
//! hits and box ranges.
//!
//! The tree keeps its own copy of the vertex positions and triangles in flat arrays, so it stays
//! valid while the mesh it came from changes, and `refit()` moves it to new positions of the same
//! triangles in O(n) without rebuilding. Triangles are identified by their index in the input
//! (the face index `f.idx()` for a mesh). Boxes use the exact double coordinates, so overlap
//! queries never miss a pair of touching triangles.

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <array>
#include <cstdint>
#include <limits>
#include <utility>
#include <vector>

namespace sdflow {

//! Closed axis-aligned box [lo, hi]; empty (lo > hi) when default-constructed.
struct Aabb {
  std::array<double, 3> lo = {std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity(),
                              std::numeric_limits<double>::infinity()};
  std::array<double, 3> hi = {-std::numeric_limits<double>::infinity(), -std::numeric_limits<double>::infinity(),
                              -std::numeric_limits<double>::infinity()};

  void extend(const double* p)
  {
    for (int k = 0; k < 3; ++k) {
      lo[k] = p[k] < lo[k] ? p[k] : lo[k];
      hi[k] = p[k] > hi[k] ? p[k] : hi[k];
    }
  }
  void extend(const Aabb& b)
  {
    for (int k = 0; k < 3; ++k) {
      lo[k] = b.lo[k] < lo[k] ? b.lo[k] : lo[k];
      hi[k] = b.hi[k] > hi[k] ? b.hi[k] : hi[k];
    }
  }
  //! True when the boxes, each grown by `gap / 2` on every side, share a point.
  bool overlaps(const Aabb& b, double gap = 0.0) const
  {
    return lo[0] <= b.hi[0] + gap && b.lo[0] <= hi[0] + gap && lo[1] <= b.hi[1] + gap && b.lo[1] <= hi[1] + gap &&
           lo[2] <= b.hi[2] + gap && b.lo[2] <= hi[2] + gap;
  }
  //! Squared Euclidean distance from p to the box (0 inside).
  double squared_distance(const double* p) const
  {
    double d = 0;
    for (int k = 0; k < 3; ++k) {
      const double e = p[k] < lo[k] ? lo[k] - p[k] : (p[k] > hi[k] ? p[k] - hi[k] : 0.0);
      d += e * e;
    }
    return d;
  }
  //! Half the surface area (the SAH weight), 0 for an empty box.
  double half_area() const
  {
    const double x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
    return x < 0 ? 0.0 : x * y + y * z + z * x;
  }
};

//! How the tree is built.
struct BvhOptions {
  //! Largest number of triangles in a leaf (≥ 1). Small leaves suit pair queries.
  int max_leaf_size = 4;
  //! Number of bins of the surface-area-heuristic split search (≥ 2).
  int sah_bins = 16;
};

//! The point of the surface nearest to a query point.
struct ClosestPoint {
  int face = -1;                 //!< triangle index, -1 when no triangle lies within the search radius
  Eigen::Vector3d point = Eigen::Vector3d::Zero();
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero(); //!< weights of the triangle's three corners
  double squared_distance = std::numeric_limits<double>::infinity();
};

//! The first triangle a ray meets.
struct RayHit {
  int face = -1;        //!< triangle index, -1 when the ray meets nothing up to its maximum length
  double t = std::numeric_limits<double>::infinity(); //!< hit point = origin + t · direction
  Eigen::Vector3d barycentric = Eigen::Vector3d::Zero();
};

//! Axis-aligned bounding-box tree over triangles (a class: it is kept and refitted across steps).
class Bvh {
public:
  using Triangles = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

  Bvh() = default;
  //! Tree over `triangles` (rows of vertex indices into `positions`). Throws InvalidMesh for an
  //! index out of range or a non-finite coordinate, InvalidParameter for bad options.
  Bvh(const VertexVectors& positions, const Triangles& triangles, const BvhOptions& options = {});
  //! Tree over the faces of `mesh` (which must carry no deleted faces: garbage-collect first).
  explicit Bvh(const Mesh& mesh, const BvhOptions& options = {});

  //! Move the tree to new positions of the same vertices: recompute every box bottom-up, keep the
  //! topology of the tree. O(n). Throws InvalidParameter when the vertex count differs.
  void refit(const VertexVectors& positions);
  //! Refit to the current positions of `mesh` (same vertices and faces as at construction).
  void refit(const Mesh& mesh);

  int triangle_count() const { return static_cast<int>(triangles_.size()); }
  int vertex_count() const { return static_cast<int>(points_.size() / 3); }
  bool empty() const { return triangles_.empty(); }
  const std::array<int, 3>& triangle(int t) const { return triangles_[t]; }
  const double* point(int v) const { return points_.data() + 3 * static_cast<std::size_t>(v); }
  const Aabb& triangle_box(int t) const { return triangle_box_[t]; }
  //! Box of everything (empty box for an empty tree).
  Aabb bounds() const { return nodes_.empty() ? Aabb{} : nodes_.front().box; }
  int node_count() const { return static_cast<int>(nodes_.size()); }

  //! Call `visit(s, t)` once for every unordered pair of distinct triangles s ≠ t whose boxes,
  //! each grown by `margin` on every side, overlap.
  template <class Visit> void for_each_overlapping_pair(Visit&& visit, double margin = 0.0) const;
  //! Call `visit(s, t)` for every triangle s of this tree and t of `other` whose grown boxes overlap.
  template <class Visit> void for_each_overlapping_pair(const Bvh& other, Visit&& visit, double margin = 0.0) const;
  //! Call `visit(t)` for every triangle whose box overlaps `box`.
  template <class Visit> void for_each_in_box(const Aabb& box, Visit&& visit) const;

  //! All pairs of for_each_overlapping_pair, as (smaller, larger) index, sorted.
  std::vector<std::pair<int, int>> overlapping_pairs(double margin = 0.0) const;
  //! All pairs (this tree's triangle, other's triangle) with overlapping grown boxes, sorted.
  std::vector<std::pair<int, int>> overlapping_pairs(const Bvh& other, double margin = 0.0) const;

  //! Nearest surface point to `query` among triangles closer than sqrt(max_squared_distance)
  //! (face = -1 if none, always the case for an empty tree). Exact up to rounding; ties go to the
  //! first triangle found.
  ClosestPoint closest_point(const Eigen::Vector3d& query,
                             double max_squared_distance = std::numeric_limits<double>::infinity()) const;

  //! First triangle met by origin + t · direction, 0 ≤ t ≤ t_max (Möller & Trumbore 1997, in
  //! floating point: rays grazing an edge may miss or hit either neighbour). A segment from a to
  //! b is the ray (a, b - a) with t_max = 1.
  RayHit first_hit(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                   double t_max = std::numeric_limits<double>::infinity()) const;

private:
  //! Leaves hold slots [first, first + count) of the leaf-ordered arrays; an inner node (count 0)
  //! has its two children at first and first + 1, always after itself in the array.
  struct Node {
    Aabb box;
    std::int32_t first = 0;
    std::int32_t count = 0;
    bool leaf() const { return count > 0; }
  };

  void build(const BvhOptions& options);
  void compute_triangle_boxes();
  void refit_nodes();
  void copy_positions(const VertexVectors& positions);

  std::vector<double> points_;                 // 3 per vertex
  std::vector<std::array<int, 3>> triangles_;  // input order
  std::vector<Aabb> triangle_box_;             // input order
  std::vector<Node> nodes_;                    // root first
  std::vector<std::int32_t> slot_triangle_;    // leaf order -> triangle index
  std::vector<Aabb> slot_box_;                 // leaf order copy of the triangle boxes, for locality
};

template <class Visit> void Bvh::for_each_overlapping_pair(Visit&& visit, double margin) const
{
  if (nodes_.empty())
    return;
  const double gap = 2.0 * margin;
  // (a, a) stands for "all pairs inside subtree a", (a, b) for "pairs across subtrees a and b".
  std::vector<std::pair<std::int32_t, std::int32_t>> stack;
  stack.reserve(256);
  stack.emplace_back(0, 0);
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    const Node& na = nodes_[a];
    if (a == b) {
      if (na.leaf()) {
        for (int i = na.first; i < na.first + na.count; ++i)
          for (int j = i + 1; j < na.first + na.count; ++j)
            if (slot_box_[i].overlaps(slot_box_[j], gap))
              visit(slot_triangle_[i], slot_triangle_[j]);
      } else {
        stack.emplace_back(na.first, na.first + 1);
        stack.emplace_back(na.first + 1, na.first + 1);
        stack.emplace_back(na.first, na.first);
      }
      continue;
    }
    const Node& nb = nodes_[b];
    if (!na.box.overlaps(nb.box, gap))
      continue;
    if (na.leaf() && nb.leaf()) {
      for (int i = na.first; i < na.first + na.count; ++i)
        for (int j = nb.first; j < nb.first + nb.count; ++j)
          if (slot_box_[i].overlaps(slot_box_[j], gap))
            visit(slot_triangle_[i], slot_triangle_[j]);
    } else if (nb.leaf() || (!na.leaf() && na.box.half_area() >= nb.box.half_area())) {
      stack.emplace_back(na.first, b);
      stack.emplace_back(na.first + 1, b);
    } else {
      stack.emplace_back(a, nb.first);
      stack.emplace_back(a, nb.first + 1);
    }
  }
}

template <class Visit> void Bvh::for_each_overlapping_pair(const Bvh& other, Visit&& visit, double margin) const
{
  if (nodes_.empty() || other.nodes_.empty())
    return;
  const double gap = 2.0 * margin;
  std::vector<std::pair<std::int32_t, std::int32_t>> stack;
  stack.reserve(256);
  stack.emplace_back(0, 0);
  while (!stack.empty()) {
    const auto [a, b] = stack.back();
    stack.pop_back();
    const Node& na = nodes_[a];
    const Node& nb = other.nodes_[b];
    if (!na.box.overlaps(nb.box, gap))
      continue;
    if (na.leaf() && nb.leaf()) {
      for (int i = na.first; i < na.first + na.count; ++i)
        for (int j = nb.first; j < nb.first + nb.count; ++j)
          if (slot_box_[i].overlaps(other.slot_box_[j], gap))
            visit(slot_triangle_[i], other.slot_triangle_[j]);
    } else if (nb.leaf() || (!na.leaf() && na.box.half_area() >= nb.box.half_area())) {
      stack.emplace_back(na.first, b);
      stack.emplace_back(na.first + 1, b);
    } else {
      stack.emplace_back(a, nb.first);
      stack.emplace_back(a, nb.first + 1);
    }
  }
}

template <class Visit> void Bvh::for_each_in_box(const Aabb& box, Visit&& visit) const
{
  if (nodes_.empty())
    return;
  std::vector<std::int32_t> stack;
  stack.reserve(64);
  stack.push_back(0);
  while (!stack.empty()) {
    const Node& n = nodes_[stack.back()];
    stack.pop_back();
    if (!n.box.overlaps(box))
      continue;
    if (n.leaf()) {
      for (int i = n.first; i < n.first + n.count; ++i)
        if (slot_box_[i].overlaps(box))
          visit(slot_triangle_[i]);
    } else {
      stack.push_back(n.first);
      stack.push_back(n.first + 1);
    }
  }
}

} // namespace sdflow
