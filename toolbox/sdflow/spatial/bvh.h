#pragma once
//! \file bvh.h
//! \brief Bounding-volume hierarchy of axis-aligned boxes over the triangles of a surface, built
//! by sorting the triangle centroids along a Morton (Z-order) curve and splitting at its spatial
//! median bits (the LBVH of Lauterbach et al. 2009), O(n log n); refit after vertex motion; queries
//! for overlapping triangle pairs (within one tree or between two), the closest surface point, ray
//! hits and box ranges.
//!
//! The tree keeps its own copy of the vertex positions and triangles in flat arrays, so it stays
//! valid while the mesh it came from changes, and `refit()` moves it to new positions of the same
//! triangles in O(n) without rebuilding. FaceIndices are identified by their index in the input
//! (the face index `f.idx()` for a mesh). Boxes use the exact double coordinates, so overlap
//! queries never miss a pair of touching triangles.

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <algorithm>
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
    // Non-short-circuit: six predictable comparisons beat six unpredictable branches.
    return (lo[0] <= b.hi[0] + gap) & (b.lo[0] <= hi[0] + gap) & (lo[1] <= b.hi[1] + gap) &
           (b.lo[1] <= hi[1] + gap) & (lo[2] <= b.hi[2] + gap) & (b.lo[2] <= hi[2] + gap);
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
  //! Half the surface area, 0 for an empty box.
  double half_area() const
  {
    const double x = hi[0] - lo[0], y = hi[1] - lo[1], z = hi[2] - lo[2];
    return x < 0 ? 0.0 : x * y + y * z + z * x;
  }
};

//! How the tree is built.
struct BvhOptions {
  //! Largest number of triangles in a leaf (≥ 1). Small leaves suit pair queries.
  int max_leaf_size = 8;
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

//! Barycentric weights of the point of triangle abc nearest to p, by the Voronoi regions of its
//! corners, edges and interior (Ericson 2005, Real-Time Collision Detection §5.1.5); a collinear
//! triangle's nearest point is on one of its edges. Every closest-point query here uses it
//! (inline: called for most triangles a query meets).
inline Eigen::Vector3d nearest_barycentric(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
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

//! Axis-aligned bounding-box tree over triangles (a class: it is kept and refitted across steps).
class Bvh {
public:

  Bvh() = default;
  //! Tree over `triangles` (rows of vertex indices into `positions`). Throws InvalidMesh for an
  //! index out of range or a coordinate that is not finite or beyond ±1e30, InvalidParameter for
  //! bad options.
  Bvh(const VertexVectors& positions, const FaceIndices& triangles, const BvhOptions& options = {});
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
  //! The stored boxes of triangles s and t, grown by `margin`, overlap.
  bool boxes_overlap(int s, int t, double margin = 0.0) const
  {
    return slot_box_[triangle_slot_[s]].overlaps(slot_box_[triangle_slot_[t]], float_gap(margin));
  }
  //! Box of everything (empty box for an empty tree).
  const Aabb& bounds() const { return bounds_; }
  int node_count() const { return static_cast<int>(nodes_.size()); }

  //! Call `visit(s, t)` once for every unordered pair of distinct triangles s ≠ t whose boxes,
  //! each grown by `margin` on every side, overlap (conservatively, see the file comment).
  template <class Visit> void for_each_overlapping_pair(Visit&& visit, double margin = 0.0) const;
  //! Node pairs that together stand for every pair for_each_overlapping_pair() visits, each one
  //! an independent unit of work (for a parallel traversal): at least `count` when the tree is
  //! large enough. A node paired with itself stands for the pairs inside its subtree.
  std::vector<std::pair<int, int>> traversal_seeds(int count, double margin = 0.0) const;
  //! The pairs of one seed of traversal_seeds() (with the same margin).
  template <class Visit>
  void for_each_overlapping_pair(std::pair<int, int> seed, Visit&& visit, double margin = 0.0) const;
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
  //! A float box that contains the double box it was made from.
  struct Box32 {
    float lo[3] = {0, 0, 0};
    float hi[3] = {0, 0, 0};
    static Box32 outward(const Aabb& b);
    //! The boxes grown by gap / 2 overlap. Float arithmetic is enough: each comparison has a float
    //! on its left, so rounding the sum can never turn a true overlap of the exact boxes inside
    //! into a miss.
    bool overlaps(const Box32& b, float gap) const
    {
      return (lo[0] <= b.hi[0] + gap) & (b.lo[0] <= hi[0] + gap) & (lo[1] <= b.hi[1] + gap) &
             (b.lo[1] <= hi[1] + gap) & (lo[2] <= b.hi[2] + gap) & (b.lo[2] <= hi[2] + gap);
    }
    bool overlaps(const Aabb& b) const
    {
      return (double(lo[0]) <= b.hi[0]) & (b.lo[0] <= double(hi[0])) & (double(lo[1]) <= b.hi[1]) &
             (b.lo[1] <= double(hi[1])) & (double(lo[2]) <= b.hi[2]) & (b.lo[2] <= double(hi[2]));
    }
    Aabb box() const { return {{lo[0], lo[1], lo[2]}, {hi[0], hi[1], hi[2]}}; }
  };
  //! Leaves hold slots [first, first + count) of the leaf-ordered arrays; an inner node (count 0)
  //! has its two children at first and first + 1, always after itself in the array.
  struct alignas(32) Node {
    Box32 box;
    std::int32_t first = 0;
    std::int32_t count = 0;
    bool leaf() const { return count > 0; }
  };

  //! 2 · margin as a float rounded up (a gap between boxes each grown by margin).
  static float float_gap(double margin);

  //! Pairs between leaf a of this tree and leaf b of `other`: first keep the triangles of each leaf
  //! whose box meets the other leaf's box, then test only those against each other.
  template <class Visit> void leaf_pairs(const Node& a, const Bvh& other, const Node& b, float gap, Visit& visit) const;

  void build(const BvhOptions& options);
  void refit_nodes();
  void copy_positions(const VertexVectors& positions);

  std::vector<double> points_;                 // 3 per vertex
  std::vector<std::array<int, 3>> triangles_;  // input order
  std::vector<Node> nodes_;                    // root first, siblings adjacent
  std::vector<std::int32_t> slot_triangle_;    // leaf order -> triangle index
  std::vector<std::int32_t> triangle_slot_;    // triangle index -> leaf order
  std::vector<Box32> slot_box_;                // triangle boxes in leaf order
  Aabb bounds_;                                // exact
};

template <class Visit> void Bvh::for_each_overlapping_pair(Visit&& visit, double margin) const
{
  if (!nodes_.empty())
    for_each_overlapping_pair({0, 0}, visit, margin);
}

template <class Visit>
void Bvh::for_each_overlapping_pair(std::pair<int, int> seed, Visit&& visit, double margin) const
{
  const float gap = float_gap(margin);
  // (a, a) stands for "all pairs inside subtree a", (a, b) for "pairs across subtrees a and b".
  std::vector<std::pair<std::int32_t, std::int32_t>> stack;
  stack.reserve(256);
  stack.push_back(seed);
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
      leaf_pairs(na, *this, nb, gap, visit);
    } else if (nb.leaf() || (!na.leaf() && na.box.box().half_area() >= nb.box.box().half_area())) {
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
  const float gap = float_gap(margin);
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
      leaf_pairs(na, other, nb, gap, visit);
    } else if (nb.leaf() || (!na.leaf() && na.box.box().half_area() >= nb.box.box().half_area())) {
      stack.emplace_back(na.first, b);
      stack.emplace_back(na.first + 1, b);
    } else {
      stack.emplace_back(a, nb.first);
      stack.emplace_back(a, nb.first + 1);
    }
  }
}

template <class Visit>
void Bvh::leaf_pairs(const Node& a, const Bvh& other, const Node& b, float gap, Visit& visit) const
{
  constexpr int chunk = 32;
  std::int32_t keep_a[chunk], keep_b[chunk];
  const Box32& box_a = a.box;
  const Box32& box_b = b.box;
  for (int a0 = a.first; a0 < a.first + a.count; a0 += chunk) {
    int na = 0;
    for (int i = a0; i < std::min(a0 + chunk, a.first + a.count); ++i)
      if (slot_box_[i].overlaps(box_b, gap))
        keep_a[na++] = i;
    for (int b0 = b.first; na > 0 && b0 < b.first + b.count; b0 += chunk) {
      int nb = 0;
      for (int j = b0; j < std::min(b0 + chunk, b.first + b.count); ++j)
        if (other.slot_box_[j].overlaps(box_a, gap))
          keep_b[nb++] = j;
      for (int x = 0; x < na; ++x)
        for (int y = 0; y < nb; ++y)
          if (slot_box_[keep_a[x]].overlaps(other.slot_box_[keep_b[y]], gap))
            visit(slot_triangle_[keep_a[x]], other.slot_triangle_[keep_b[y]]);
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
