#include "support/analytic_meshes.h"

#include <cmath>
#include <array>
#include <map>
#include <numbers>
#include <utility>
#include <vector>

namespace sdflow::analytic {
namespace {


//! Unit icosahedron subdivided `level` times, every vertex on the unit sphere.
std::pair<std::vector<Eigen::Vector3d>, std::vector<std::array<int, 3>>> unit_icosphere(int level)
{
  const double t = (1.0 + std::sqrt(5.0)) / 2.0;
  std::vector<Eigen::Vector3d> v = {{-1, t, 0}, {1, t, 0},  {-1, -t, 0}, {1, -t, 0}, {0, -1, t},  {0, 1, t},
                                    {0, -1, -t}, {0, 1, -t}, {t, 0, -1},  {t, 0, 1},  {-t, 0, -1}, {-t, 0, 1}};
  for (auto& p : v)
    p.normalize();
  std::vector<std::array<int, 3>> f = {{0, 11, 5}, {0, 5, 1},  {0, 1, 7},   {0, 7, 10}, {0, 10, 11},
                                       {1, 5, 9},  {5, 11, 4}, {11, 10, 2}, {10, 7, 6}, {7, 1, 8},
                                       {3, 9, 4},  {3, 4, 2},  {3, 2, 6},   {3, 6, 8},  {3, 8, 9},
                                       {4, 9, 5},  {2, 4, 11}, {6, 2, 10},  {8, 6, 7},  {9, 8, 1}};
  for (int l = 0; l < level; ++l) {
    std::map<std::pair<int, int>, int> midpoint;
    auto mid = [&](int a, int b) {
      const auto key = std::minmax(a, b);
      auto [it, inserted] = midpoint.try_emplace(key, static_cast<int>(v.size()));
      if (inserted)
        v.push_back((v[a] + v[b]).normalized());
      return it->second;
    };
    std::vector<std::array<int, 3>> next;
    next.reserve(4 * f.size());
    for (const auto& [a, b, c] : f) {
      const int ab = mid(a, b), bc = mid(b, c), ca = mid(c, a);
      next.push_back({a, ab, ca});
      next.push_back({b, bc, ab});
      next.push_back({c, ca, bc});
      next.push_back({ab, bc, ca});
    }
    f = std::move(next);
  }
  return {v, f};
}

Mesh mesh_from(const std::vector<Eigen::Vector3d>& points, const std::vector<std::array<int, 3>>& faces)
{
  VertexVectors x(points.size(), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    x.row(i) = points[i].transpose();
  FaceIndices t(faces.size(), 3);
  for (std::size_t i = 0; i < faces.size(); ++i)
    t.row(i) << faces[i][0], faces[i][1], faces[i][2];
  return make_mesh(x, t);
}

} // namespace

Mesh icosphere(int level, double radius, const Eigen::Vector3d& centre)
{
  auto [points, faces] = unit_icosphere(level);
  for (auto& p : points)
    p = centre + radius * p;
  return mesh_from(points, faces);
}

Mesh ellipsoid(int level, double a, double b, double c)
{
  auto [points, faces] = unit_icosphere(level);
  for (auto& p : points)
    p = Eigen::Vector3d(a * p.x(), b * p.y(), c * p.z());
  return mesh_from(points, faces);
}

Mesh torus(int around, int tube, double major, double minor)
{
  std::vector<Eigen::Vector3d> points;
  points.reserve(static_cast<std::size_t>(around) * tube);
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < tube; ++j) {
      const double u = 2 * std::numbers::pi * i / around, v = 2 * std::numbers::pi * j / tube;
      const double rho = major + minor * std::cos(v);
      points.emplace_back(rho * std::cos(u), rho * std::sin(u), minor * std::sin(v));
    }
  auto id = [&](int i, int j) { return ((i + around) % around) * tube + (j + tube) % tube; };
  std::vector<std::array<int, 3>> faces;
  for (int i = 0; i < around; ++i)
    for (int j = 0; j < tube; ++j) {
      // (u, v) is positively oriented with the outward normal (∂u × ∂v points outward).
      const int a = id(i, j), b = id(i + 1, j), c = id(i + 1, j + 1), d = id(i, j + 1);
      faces.push_back({a, b, c});
      faces.push_back({a, c, d});
    }
  return mesh_from(points, faces);
}

Mesh conformal_torus(int rows, double major, double minor)
{
  // w(v) = (2r/c) atan(k tan(v/2)), c = √(R² - r²), k = √((R - r)/(R + r)); total length W = 2πr/c.
  const double c = std::sqrt(major * major - minor * minor), k = std::sqrt((major - minor) / (major + minor));
  const double w_total = 2 * std::numbers::pi * minor / c;
  rows += rows % 2;
  // Equilateral rows are √3/2 apart, so columns = 2π / side with side = W / (rows √3/2).
  const int columns = std::max(3, static_cast<int>(std::lround(2 * std::numbers::pi * rows * std::sqrt(3.0) / 2 / w_total)));
  std::vector<Eigen::Vector3d> points;
  for (int j = 0; j < rows; ++j) {
    const double w = -w_total / 2 + w_total * j / rows;
    const double v = 2 * std::atan(std::tan(w * c / (2 * minor)) / k);
    for (int i = 0; i < columns; ++i) {
      const double u = 2 * std::numbers::pi * (i + 0.5 * (j % 2)) / columns;
      const double rho = major + minor * std::cos(v);
      points.emplace_back(rho * std::cos(u), rho * std::sin(u), minor * std::sin(v));
    }
  }
  auto id = [&](int j, int i) { return ((j + rows) % rows) * columns + (i + columns) % columns; };
  std::vector<std::array<int, 3>> faces;
  for (int j = 0; j < rows; ++j)
    for (int i = 0; i < columns; ++i) {
      // Counter-clockwise in (u, w), which is outward; odd rows are shifted half a column.
      if (j % 2 == 0) {
        faces.push_back({id(j, i), id(j, i + 1), id(j + 1, i)});
        faces.push_back({id(j + 1, i), id(j, i + 1), id(j + 1, i + 1)});
      } else {
        faces.push_back({id(j, i), id(j, i + 1), id(j + 1, i + 1)});
        faces.push_back({id(j + 1, i), id(j, i), id(j + 1, i + 1)});
      }
    }
  return mesh_from(points, faces);
}

Mesh spherical_cap(int rings, double radius, double degrees)
{
  const double angle = degrees * std::numbers::pi / 180;
  Mesh cap = disk(rings);
  for (auto v : cap.vertices()) {
    auto p = cap.point(v);
    const double r = std::hypot(p[0], p[1]), phi = std::atan2(p[1], p[0]), psi = r * angle;
    p = Mesh::Point(radius * std::sin(psi) * std::cos(phi), radius * std::sin(psi) * std::sin(phi),
                    cap.is_boundary(v) ? 0.0 : radius * (std::cos(psi) - std::cos(angle)));
    cap.set_point(v, p);
  }
  return cap;
}

Mesh disk(int rings, double radius)
{
  std::vector<Eigen::Vector3d> points{{0, 0, 0}};
  std::vector<std::array<int, 3>> faces;
  // Ring k has 6k vertices, so triangles stay close to equilateral.
  auto ring_start = [](int k) { return k == 0 ? 0 : 1 + 3 * k * (k - 1); };
  for (int k = 1; k <= rings; ++k)
    for (int s = 0; s < 6 * k; ++s) {
      const double angle = 2 * std::numbers::pi * s / (6 * k);
      points.emplace_back(radius * k / rings * std::cos(angle), radius * k / rings * std::sin(angle), 0.0);
    }
  for (int k = 1; k <= rings; ++k) {
    const int outer = ring_start(k), n_outer = 6 * k;
    if (k == 1) {
      for (int o = 0; o < n_outer; ++o)
        faces.push_back({0, outer + o, outer + (o + 1) % n_outer});
      continue;
    }
    const int inner = ring_start(k - 1), n_inner = 6 * (k - 1);
    // Walk both rings together by angle; each step closes one counter-clockwise (+z) triangle.
    for (int i = 0, o = 0; i < n_inner || o < n_outer;) {
      const bool advance_outer = o < n_outer && (i >= n_inner || (o + 1) * n_inner <= (i + 1) * n_outer);
      if (advance_outer) {
        faces.push_back({inner + i % n_inner, outer + o, outer + (o + 1) % n_outer});
        ++o;
      } else {
        faces.push_back({inner + i, outer + o % n_outer, inner + (i + 1) % n_inner});
        ++i;
      }
    }
  }
  return mesh_from(points, faces);
}

namespace {

//! The convex polyhedron of `points` with the triangles `faces`, each turned to face away from the
//! centroid.
Mesh convex_polyhedron(VertexVectors points, FaceIndices faces)
{
  const Eigen::Vector3d centre = points.colwise().mean().transpose();
  for (Eigen::Index f = 0; f < faces.rows(); ++f) {
    const Eigen::Vector3d a = points.row(faces(f, 0)).transpose(), b = points.row(faces(f, 1)).transpose(),
                          c = points.row(faces(f, 2)).transpose();
    if ((b - a).cross(c - a).dot(a - centre) < 0)
      std::swap(faces(f, 1), faces(f, 2));
  }
  return make_mesh(points, faces);
}

} // namespace

Mesh cube(double edge, const Eigen::Vector3d& centre)
{
  VertexVectors x(8, 3);
  for (int i = 0; i < 8; ++i)
    x.row(i) = (centre + edge * Eigen::Vector3d((i & 1) - 0.5, ((i >> 1) & 1) - 0.5, ((i >> 2) & 1) - 0.5)).transpose();
  FaceIndices t(12, 3);
  // Vertex i has x, y, z from bits 0, 1, 2 of i; each face is a quad of the vertices with one bit fixed.
  t << 0, 2, 6, 0, 6, 4, 1, 3, 7, 1, 7, 5, 0, 1, 5, 0, 5, 4, 2, 3, 7, 2, 7, 6, 0, 1, 3, 0, 3, 2, 4, 5, 7, 4, 7, 6;
  return convex_polyhedron(x, t);
}

Mesh regular_tetrahedron()
{
  VertexVectors x(4, 3);
  x << 1, 1, 1, 1, -1, -1, -1, 1, -1, -1, -1, 1;
  x /= std::sqrt(3.0);
  FaceIndices t(4, 3);
  t << 0, 1, 2, 0, 1, 3, 0, 2, 3, 1, 2, 3;
  return convex_polyhedron(x, t);
}

Mesh regular_octahedron()
{
  VertexVectors x(6, 3);
  x << 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1, 0, 0, 0, 1, 0, 0, -1;
  FaceIndices t(8, 3);
  t << 0, 2, 4, 2, 1, 4, 1, 3, 4, 3, 0, 4, 0, 2, 5, 2, 1, 5, 1, 3, 5, 3, 0, 5;
  return convex_polyhedron(x, t);
}

Mesh fanned_frame(int segments)
{
  constexpr double outer = 10, inner = 6, height = 4;
  const std::array<Eigen::Vector2d, 4> corners{Eigen::Vector2d(-1, -1), Eigen::Vector2d(1, -1), Eigen::Vector2d(1, 1),
                                               Eigen::Vector2d(-1, 1)};
  const int ring = 4 * segments;     // outer vertices per layer
  const int layer = ring + 4;        // then the hole's four corners
  VertexVectors x(2 * layer, 3);
  for (int z = 0; z < 2; ++z) {
    for (int k = 0; k < 4; ++k) {
      for (int j = 0; j < segments; ++j) {
        const Eigen::Vector2d p =
            outer * (corners[k] + (corners[(k + 1) % 4] - corners[k]) * (static_cast<double>(j) / segments));
        x.row(z * layer + k * segments + j) << p.x(), p.y(), z * height;
      }
      x.row(z * layer + ring + k) << inner * corners[k].x(), inner * corners[k].y(), z * height;
    }
  }
  const auto o = [&](int z, int i) { return z * layer + (i % ring); };
  const auto h = [&](int z, int k) { return z * layer + ring + (k % 4); };
  std::vector<Eigen::Vector3i> t;
  for (int k = 0; k < 4; ++k) {
    for (int j = 0; j < segments; ++j) {
      const int i = k * segments + j;
      t.emplace_back(h(1, k), o(1, i), o(1, i + 1)); // top, fanned from the hole's corner
      t.emplace_back(h(0, k), o(0, i + 1), o(0, i)); // bottom
    }
    t.emplace_back(h(1, k), o(1, (k + 1) * segments), h(1, k + 1));
    t.emplace_back(h(0, k), h(0, k + 1), o(0, (k + 1) * segments));
    t.emplace_back(h(0, k), h(1, k + 1), h(0, k + 1)); // the hole's wall
    t.emplace_back(h(0, k), h(1, k), h(1, k + 1));
  }
  for (int i = 0; i < ring; ++i) { // the outer wall
    t.emplace_back(o(0, i), o(0, i + 1), o(1, i + 1));
    t.emplace_back(o(0, i), o(1, i + 1), o(1, i));
  }
  FaceIndices faces(static_cast<Eigen::Index>(t.size()), 3);
  for (std::size_t f = 0; f < t.size(); ++f)
    faces.row(static_cast<Eigen::Index>(f)) = t[f].transpose();
  return make_mesh(x, faces);
}

Mesh disjoint_union(const Mesh& a, const Mesh& b)
{
  VertexVectors x(a.n_vertices() + b.n_vertices(), 3);
  x << vertex_positions(a), vertex_positions(b);
  FaceIndices t(a.n_faces() + b.n_faces(), 3);
  t << face_indices(a), (face_indices(b).array() + static_cast<int>(a.n_vertices())).matrix();
  return make_mesh(x, t);
}

double torus_mean_curvature(double major, double minor, double v)
{
  return -(major + 2 * minor * std::cos(v)) / (2 * minor * (major + minor * std::cos(v)));
}

Eigen::Vector3d ellipsoid_normal(double a, double b, double c, const Eigen::Vector3d& p)
{
  return Eigen::Vector3d(p.x() / (a * a), p.y() / (b * b), p.z() / (c * c)).normalized();
}

double ellipsoid_mean_curvature(double a, double b, double c, const Eigen::Vector3d& p)
{
  // For x²/a²+y²/b²+z²/c² = 1: H = -(|p|² - a² - b² - c²)·... use the gradient form
  // H = -div(∇f/|∇f|)/2 with f = x²/a² + y²/b² + z²/c² - 1.
  const Eigen::Vector3d g(2 * p.x() / (a * a), 2 * p.y() / (b * b), 2 * p.z() / (c * c));
  const Eigen::Vector3d hess(2 / (a * a), 2 / (b * b), 2 / (c * c));
  const double gn = g.norm();
  // div(g/|g|) = (tr(Hf) |g|² - gᵀ Hf g) / |g|³
  double tr = hess.sum(), gHg = 0;
  for (int i = 0; i < 3; ++i)
    gHg += g[i] * hess[i] * g[i];
  const double divergence = (tr * gn * gn - gHg) / (gn * gn * gn);
  return -0.5 * divergence;
}

} // namespace sdflow::analytic
