#include "sdflow/shapes/marching_tetrahedra.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <unordered_map>
#include <unordered_set>
#include <utility>
#include <vector>

namespace sdflow {
namespace {

using Id = std::uint64_t;

//! Zeros closer than this fraction of an edge to its ends are pulled inside, so no two vertices
//! coincide exactly (the remesher removes the resulting short edges).
constexpr double kMinFraction = 1e-3;
//! Root cells are 2^kCoarseLevels × cell_size: space far from the surface is sampled coarsely.
constexpr int kCoarseLevels = 2;
//! A cell may meet the surface when a corner is within this fraction of its diagonal of it (for
//! a distance-like f, a surface point inside the cube is within half a diagonal of a corner;
//! the rest is margin for the first-order distance |f|/|∇f|).
constexpr double kNearFraction = 0.75;
//! Level field in a cell key (levels fit in 5 bits).
constexpr int kLevelBits = 5;

double zero_fraction(double a, double b)
{
  const double t = a / (a - b);
  return std::isfinite(t) ? std::clamp(t, kMinFraction, 1 - kMinFraction) : 0.5;
}

bool inside(double value) { return value < 0; } // NaN is outside

//! The six Kuhn tetrahedra of a cube: corners 0 → a → a|b → 7 for each order (a, b, c) of the
//! axis bits 1, 2, 4. Every edge joins a corner to one whose bits contain its own, so every face
//! is split along the diagonal from its lowest to its highest corner.
constexpr std::array<std::array<int, 4>, 6> kKuhn = {{
    {0, 1, 3, 7}, {0, 1, 5, 7}, {0, 2, 3, 7}, {0, 2, 6, 7}, {0, 4, 5, 7}, {0, 4, 6, 7},
}};

Mesh mesh_from(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& triangles)
{
  VertexVectors x(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    x.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  FaceIndices t(triangles.size(), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    t.row(static_cast<Eigen::Index>(i)) << triangles[i][0], triangles[i][1], triangles[i][2];
  return make_mesh(x, t);
}

using Point = std::array<std::int64_t, 3>; // lattice coordinates, in units of the finest cell

struct PairHash {
  std::size_t operator()(const std::pair<Id, Id>& p) const { return std::hash<Id>()(p.first * 0x9E3779B97F4A7C15ull ^ p.second); }
};

//! Extracts the triangles of f = 0 from tetrahedra given by lattice points, sharing vertices.
class TetMarcher {
public:
  struct Node {
    Id id;
    Eigen::Vector3d position;
    double value;
  };

  void march(const std::array<Node, 4>& tet)
  {
    std::array<int, 4> in{}, out{};
    int n_in = 0, n_out = 0;
    for (int c = 0; c < 4; ++c)
      (inside(tet[c].value) ? in[n_in++] : out[n_out++]) = c;
    if (n_in == 0 || n_out == 0)
      return;
    // Orientation from the (never degenerate) polygon of edge midpoints: facing outside.
    Eigen::Vector3d toward_out = Eigen::Vector3d::Zero();
    for (int o = 0; o < n_out; ++o)
      toward_out += tet[out[o]].position / n_out;
    for (int o = 0; o < n_in; ++o)
      toward_out -= tet[in[o]].position / n_in;
    const auto midpoint = [&](int a, int b) -> Eigen::Vector3d { return 0.5 * (tet[a].position + tet[b].position); };
    if (n_in == 2) {
      // Quad on the edges i0o0, i0o1, i1o1, i1o0 (a cycle): two triangles along the shorter
      // diagonal.
      const std::array<std::pair<int, int>, 4> q = {{{in[0], out[0]}, {in[0], out[1]}, {in[1], out[1]}, {in[1], out[0]}}};
      std::array<int, 4> v{};
      for (int a = 0; a < 4; ++a)
        v[a] = vertex_on(tet[q[a].first], tet[q[a].second]);
      const Eigen::Vector3d n = (midpoint(q[2].first, q[2].second) - midpoint(q[0].first, q[0].second))
                                    .cross(midpoint(q[3].first, q[3].second) - midpoint(q[1].first, q[1].second));
      if (n.dot(toward_out) < 0)
        std::swap(v[1], v[3]);
      if ((points[v[0]] - points[v[2]]).squaredNorm() <= (points[v[1]] - points[v[3]]).squaredNorm()) {
        triangles.push_back({v[0], v[1], v[2]});
        triangles.push_back({v[0], v[2], v[3]});
      } else {
        triangles.push_back({v[0], v[1], v[3]});
        triangles.push_back({v[1], v[2], v[3]});
      }
      return;
    }
    // One corner apart from the other three: a triangle on its three edges.
    const int apex = n_in == 1 ? in[0] : out[0];
    std::array<int, 3> others{};
    for (int o = 0, m = 0; o < 4; ++o)
      if (o != apex)
        others[m++] = o;
    std::array<int, 3> v{};
    for (int a = 0; a < 3; ++a)
      v[a] = vertex_on(tet[apex], tet[others[a]]);
    const Eigen::Vector3d m0 = midpoint(apex, others[0]), m1 = midpoint(apex, others[1]), m2 = midpoint(apex, others[2]);
    if ((m1 - m0).cross(m2 - m0).dot(toward_out) < 0)
      std::swap(v[1], v[2]);
    triangles.push_back(v);
  }

  std::vector<Eigen::Vector3d> points;
  std::vector<std::array<int, 3>> triangles;

private:
  int vertex_on(const Node& a, const Node& b)
  {
    const Node& lo = a.id < b.id ? a : b;
    const Node& hi = a.id < b.id ? b : a;
    const auto [it, added] = edge_vertex_.try_emplace({lo.id, hi.id}, static_cast<int>(points.size()));
    if (added)
      points.push_back(lo.position + zero_fraction(lo.value, hi.value) * (hi.position - lo.position));
    return it->second;
  }

  std::unordered_map<std::pair<Id, Id>, int, PairHash> edge_vertex_;
};

//! The octree over the lattice, its samples, and its tetrahedra.
class Octree {
public:
  Octree(const ImplicitSurface& surface, const MarchingOptions& options) : surface_(surface), options_(options)
  {
    unit_ = options.cell_size / std::ldexp(1.0, options.detail_levels);
    root_level_ = options.detail_levels + kCoarseLevels;
    const std::int64_t root_units = std::int64_t{1} << root_level_;
    const Eigen::Vector3d extent = surface.box.sizes();
    for (int a = 0; a < 3; ++a) {
      const auto roots = std::max<std::int64_t>(1, static_cast<std::int64_t>(std::ceil(extent[a] / (root_units * unit_))));
      n_[a] = roots * root_units;
    }
    if ((n_[0] + 1) * (n_[1] + 1) > (std::int64_t{1} << 40) / (n_[2] + 1))
      throw InvalidParameter(fmt::format("marching tetrahedra: a lattice of {} x {} x {} points (cell {}, {} detail "
                                         "levels) is too fine", n_[0] + 1, n_[1] + 1, n_[2] + 1, options.cell_size,
                                         options.detail_levels));
    detail_cos_ = std::cos(options.detail_angle_deg * std::numbers::pi / 180);
  }

  Mesh extract()
  {
    refine();
    balance();
    for (Id key : leaves_) {
      const auto [origin, level] = decode(key);
      const std::int64_t size = std::int64_t{1} << level;
      for (int c = 0; c < 8; ++c)
        used_.insert(id(corner(origin, c, size)));
    }
    // Leaves in lattice scanline order, so vertices and triangles come out spatially coherent
    // (the remesher's memory accesses follow them).
    std::vector<Id> order(leaves_.begin(), leaves_.end());
    std::sort(order.begin(), order.end());
    TetMarcher marcher;
    for (Id key : order) {
      const auto [origin, level] = decode(key);
      tetrahedralise(origin, level, marcher);
    }
    return mesh_from(marcher.points, marcher.triangles);
  }

private:
  static Point corner(const Point& origin, int bits, std::int64_t size)
  {
    return {origin[0] + (bits & 1) * size, origin[1] + ((bits >> 1) & 1) * size, origin[2] + ((bits >> 2) & 1) * size};
  }

  Id id(const Point& p) const
  {
    return static_cast<Id>(p[0] + (n_[0] + 1) * (p[1] + (n_[1] + 1) * p[2]));
  }
  Id key(const Point& origin, int level) const { return (id(origin) << kLevelBits) | static_cast<Id>(level); }
  std::pair<Point, int> decode(Id k) const
  {
    const int level = static_cast<int>(k & ((Id{1} << kLevelBits) - 1));
    auto i = static_cast<std::int64_t>(k >> kLevelBits);
    Point p;
    p[0] = i % (n_[0] + 1);
    i /= n_[0] + 1;
    p[1] = i % (n_[1] + 1);
    p[2] = i / (n_[1] + 1);
    return {p, level};
  }

  Eigen::Vector3d position(const Point& p) const
  {
    return surface_.box.min() + unit_ * Eigen::Vector3d(static_cast<double>(p[0]), static_cast<double>(p[1]),
                                                        static_cast<double>(p[2]));
  }

  double value(const Point& p)
  {
    const auto [it, added] = values_.try_emplace(id(p), 0.0);
    if (added)
      it->second = surface_.value(position(p));
    return it->second;
  }

  Eigen::Vector3d gradient(const Point& p)
  {
    const auto [it, added] = gradients_.try_emplace(id(p), Eigen::Vector3d::Zero());
    if (added)
      it->second = level_set_gradient(surface_, position(p));
    return it->second;
  }

  //! Split a cell that may meet the surface while it is coarser than cell_size, or while its
  //! corner normals disagree and detail levels remain.
  bool should_split(const Point& origin, int level)
  {
    if (level == 0)
      return false;
    const std::int64_t size = std::int64_t{1} << level;
    const double diagonal = std::sqrt(3.0) * unit_ * static_cast<double>(size);
    std::array<double, 8> distance{};
    std::array<Eigen::Vector3d, 8> normal;
    int n_inside = 0;
    bool near = false;
    for (int c = 0; c < 8; ++c) {
      const Point p = corner(origin, c, size);
      const double f = value(p);
      n_inside += inside(f);
      const Eigen::Vector3d g = gradient(p);
      const double gn = g.norm();
      distance[c] = std::isfinite(f) && gn > 0 ? std::abs(f) / gn : std::numeric_limits<double>::infinity();
      normal[c] = gn > 0 ? Eigen::Vector3d(g / gn) : Eigen::Vector3d::Zero();
      near |= distance[c] <= kNearFraction * diagonal;
    }
    if (!near && n_inside != 0 && n_inside != 8)
      near = true;
    if (!near)
      return false;
    if (level > options_.detail_levels)
      return true;
    for (int a = 0; a < 8; ++a)
      for (int b = a + 1; b < 8; ++b)
        if (distance[a] <= diagonal && distance[b] <= diagonal && normal[a].dot(normal[b]) < detail_cos_)
          return true;
    return false;
  }

  void refine()
  {
    std::vector<std::pair<Point, int>> stack;
    const std::int64_t root = std::int64_t{1} << root_level_;
    for (std::int64_t k = 0; k < n_[2]; k += root)
      for (std::int64_t j = 0; j < n_[1]; j += root)
        for (std::int64_t i = 0; i < n_[0]; i += root)
          stack.push_back({{i, j, k}, root_level_});
    while (!stack.empty()) {
      const auto [origin, level] = stack.back();
      stack.pop_back();
      if (!should_split(origin, level)) {
        leaves_.insert(key(origin, level));
        continue;
      }
      const std::int64_t half = std::int64_t{1} << (level - 1);
      for (int c = 0; c < 8; ++c)
        stack.push_back({corner(origin, c, half), level - 1});
    }
  }

  //! The leaf of level ≥ min_level containing lattice point p, as (origin, level); level −1 if
  //! the leaf there is finer.
  std::pair<Point, int> leaf_at(const Point& p, int min_level) const
  {
    for (int level = min_level; level <= root_level_; ++level) {
      const std::int64_t mask = ~((std::int64_t{1} << level) - 1);
      const Point origin = {p[0] & mask, p[1] & mask, p[2] & mask};
      if (leaves_.count(key(origin, level)))
        return {origin, level};
    }
    return {p, -1};
  }

  //! 2:1 balance across faces, edges and corners: no leaf touches one more than twice its size.
  void balance()
  {
    std::vector<Id> work(leaves_.begin(), leaves_.end());
    while (!work.empty()) {
      const Id k = work.back();
      work.pop_back();
      if (!leaves_.count(k))
        continue;
      const auto [origin, level] = decode(k);
      const std::int64_t size = std::int64_t{1} << level;
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            if (dx == 0 && dy == 0 && dz == 0)
              continue;
            const std::array<int, 3> d = {dx, dy, dz};
            Point probe{};
            bool inside_lattice = true;
            for (int a = 0; a < 3; ++a) {
              probe[a] = d[a] < 0 ? origin[a] - 1 : d[a] > 0 ? origin[a] + size : origin[a];
              inside_lattice &= probe[a] >= 0 && probe[a] < n_[a];
            }
            if (!inside_lattice)
              continue;
            const auto [neighbour, neighbour_level] = leaf_at(probe, level + 2);
            if (neighbour_level < 0)
              continue;
            leaves_.erase(key(neighbour, neighbour_level));
            const std::int64_t half = std::int64_t{1} << (neighbour_level - 1);
            for (int c = 0; c < 8; ++c) {
              const Id child = key(corner(neighbour, c, half), neighbour_level - 1);
              leaves_.insert(child);
              work.push_back(child);
            }
            work.push_back(k); // look again: the neighbour's child may still be too coarse
          }
    }
  }

  bool used(const Point& p) const { return used_.count(id(p)) != 0; }

  TetMarcher::Node node(const Point& p) { return {id(p), position(p), value(p)}; }

  //! FaceIndices of a face square (origin, axes u and v, size) as both cells sharing it see it:
  //! split into four where the other side is finer, fanned from the centre where an edge carries
  //! a finer cell's corner, else cut along the Kuhn diagonal (lowest to highest corner).
  void face_triangles(const Point& origin, int u, int v, std::int64_t size, std::vector<std::array<Point, 3>>& out) const
  {
    const auto offset = [&](std::int64_t a, std::int64_t b) {
      Point p = origin;
      p[u] += a;
      p[v] += b;
      return p;
    };
    const std::int64_t half = size / 2;
    if (size >= 2 && used(offset(half, half))) {
      for (const auto& [a, b] : {std::pair{0, 0}, {1, 0}, {0, 1}, {1, 1}})
        face_triangles(offset(a * half, b * half), u, v, half, out);
      return;
    }
    const std::array<Point, 4> corners = {offset(0, 0), offset(size, 0), offset(size, size), offset(0, size)};
    const std::array<Point, 4> mids = {offset(half, 0), offset(size, half), offset(half, size), offset(0, half)};
    std::vector<Point> ring;
    for (int c = 0; c < 4; ++c) {
      ring.push_back(corners[c]);
      if (size >= 2 && used(mids[c]))
        ring.push_back(mids[c]);
    }
    if (ring.size() == 4) {
      out.push_back({corners[0], corners[1], corners[2]});
      out.push_back({corners[0], corners[2], corners[3]});
      return;
    }
    const Point centre = offset(half, half);
    for (std::size_t c = 0; c < ring.size(); ++c)
      out.push_back({centre, ring[c], ring[(c + 1) % ring.size()]});
  }

  void tetrahedralise(const Point& origin, int level, TetMarcher& marcher)
  {
    const std::int64_t size = std::int64_t{1} << level;
    // Far from the surface (all corners on one side, each over a diagonal away): nothing to do.
    const double diagonal = std::sqrt(3.0) * unit_ * static_cast<double>(size);
    bool far = true;
    const bool first_inside = inside(value(origin));
    for (int c = 0; c < 8 && far; ++c) {
      const Point p = corner(origin, c, size);
      const double f = value(p);
      far = inside(f) == first_inside && std::abs(f) > diagonal * gradient(p).norm();
    }
    if (far)
      return;
    bool regular = true;
    if (level > 0) {
      const std::int64_t h = size / 2;
      // Edge midpoints and face centres: lattice points at half-size offsets, not all zero.
      for (int a = 0; a <= 2 && regular; ++a)
        for (int b = 0; b <= 2 && regular; ++b)
          for (int c = 0; c <= 2 && regular; ++c) {
            const int halves = (a == 1) + (b == 1) + (c == 1);
            if (halves == 1 || halves == 2)
              regular = !used({origin[0] + a * h, origin[1] + b * h, origin[2] + c * h});
          }
    }
    if (regular) {
      std::array<TetMarcher::Node, 8> corners;
      for (int c = 0; c < 8; ++c)
        corners[c] = node(corner(origin, c, size));
      bool mixed = false;
      for (int c = 1; c < 8; ++c)
        mixed |= inside(corners[c].value) != inside(corners[0].value);
      if (!mixed)
        return;
      for (const auto& tet : kKuhn)
        marcher.march({corners[tet[0]], corners[tet[1]], corners[tet[2]], corners[tet[3]]});
      return;
    }
    // Transition cell: pyramids from the centre over the triangulated faces.
    const std::int64_t h = size / 2;
    const TetMarcher::Node centre = node({origin[0] + h, origin[1] + h, origin[2] + h});
    std::vector<std::array<Point, 3>> faces;
    for (int axis = 0; axis < 3; ++axis) {
      const int u = (axis + 1) % 3, v = (axis + 2) % 3;
      for (int side = 0; side < 2; ++side) {
        Point face = origin;
        face[axis] += side * size;
        face_triangles(face, std::min(u, v), std::max(u, v), size, faces);
      }
    }
    for (const auto& t : faces)
      marcher.march({centre, node(t[0]), node(t[1]), node(t[2])});
  }

  const ImplicitSurface& surface_;
  const MarchingOptions& options_;
  double unit_ = 0;
  int root_level_ = 0;
  double detail_cos_ = 0;
  std::array<std::int64_t, 3> n_{};
  std::unordered_map<Id, double> values_;
  std::unordered_map<Id, Eigen::Vector3d> gradients_;
  std::unordered_set<Id> leaves_;
  std::unordered_set<Id> used_;
};

} // namespace

Mesh marching_tetrahedra(const ImplicitSurface& surface, const MarchingOptions& options)
{
  if (!(options.cell_size > 0) || !std::isfinite(options.cell_size))
    throw InvalidParameter(fmt::format("marching tetrahedra: cell size {} must be positive", options.cell_size));
  if (options.detail_levels < 0 || options.detail_levels > 10)
    throw InvalidParameter(fmt::format("marching tetrahedra: detail levels {} must be in [0, 10]", options.detail_levels));
  if (!(surface.box.sizes().array() > 0).all())
    throw InvalidParameter("marching tetrahedra: the box must have positive extent on every axis");
  Octree octree(surface, options);
  return octree.extract();
}

Mesh clip_mesh(const Mesh& mesh, const ScalarField& g)
{
  const VertexVectors x = vertex_positions(mesh);
  const auto faces = face_indices(mesh);
  std::vector<double> value(x.rows());
  for (Eigen::Index v = 0; v < x.rows(); ++v)
    value[v] = g(x.row(v).transpose());
  const auto kept = [&](int v) { return value[v] <= 0; }; // NaN is dropped

  std::vector<Eigen::Vector3d> points;
  std::vector<int> new_id(x.rows(), -1);
  std::unordered_map<std::int64_t, int> cut_vertex;
  const auto keep = [&](int v) {
    if (new_id[v] < 0) {
      new_id[v] = static_cast<int>(points.size());
      points.push_back(x.row(v).transpose());
    }
    return new_id[v];
  };
  const auto cut = [&](int a, int b) { // a kept, b dropped
    const std::int64_t key = std::int64_t{std::min(a, b)} * x.rows() + std::max(a, b);
    const auto [it, added] = cut_vertex.try_emplace(key, static_cast<int>(points.size()));
    if (added) {
      const Eigen::Vector3d pa = x.row(a).transpose(), pb = x.row(b).transpose();
      points.push_back(pa + zero_fraction(value[a], value[b]) * (pb - pa));
    }
    return it->second;
  };
  std::vector<std::array<int, 3>> triangles;
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    std::array<int, 3> t = {faces(f, 0), faces(f, 1), faces(f, 2)};
    const int count = kept(t[0]) + kept(t[1]) + kept(t[2]);
    if (count == 0)
      continue;
    if (count == 3) {
      triangles.push_back({keep(t[0]), keep(t[1]), keep(t[2])});
      continue;
    }
    // Rotate (keeping the orientation) so that t[0] is the lone kept corner (count 1) or t[2]
    // the lone dropped one (count 2).
    while (count == 1 ? !kept(t[0]) : kept(t[2]))
      std::rotate(t.begin(), t.begin() + 1, t.end());
    if (count == 1) {
      triangles.push_back({keep(t[0]), cut(t[0], t[1]), cut(t[0], t[2])});
    } else {
      const int a = keep(t[0]), b = keep(t[1]), bc = cut(t[1], t[2]), ca = cut(t[0], t[2]);
      triangles.push_back({a, b, bc});
      triangles.push_back({a, bc, ca});
    }
  }
  return mesh_from(points, triangles);
}

} // namespace sdflow
