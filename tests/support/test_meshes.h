#pragma once
//! \file test_meshes.h
//! \brief Small meshes for the tests: grids mapped by a function, disjoint unions, mapped copies,
//! an uneven sphere, worn sphere caps, a CAD plate. Header-only helpers shared by the test files.

#include "sdflow/mesh.h"
#include "sdflow/remesh/face_patch.h"
#include "support/analytic_meshes.h"

#include <algorithm>
#include <array>
#include <functional>
#include <random>
#include <vector>

namespace sdflow::test {


//! An nx × ny quad grid of the unit square [0, nx] × [0, ny] (z = 0), each quad split into two
//! triangles (alternating diagonals when `alternate`), then every vertex mapped by `map`.
inline Mesh grid(int nx, int ny, const std::function<Eigen::Vector3d(double, double)>& map, bool alternate = false)
{
  VertexVectors x((nx + 1) * (ny + 1), 3);
  for (int j = 0; j <= ny; ++j)
    for (int i = 0; i <= nx; ++i)
      x.row(j * (nx + 1) + i) = map(i, j).transpose();
  FaceIndices t(2 * nx * ny, 3);
  int f = 0;
  for (int j = 0; j < ny; ++j)
    for (int i = 0; i < nx; ++i) {
      const int a = j * (nx + 1) + i, b = a + 1, c = a + nx + 1, d = c + 1;
      if (alternate && (i + j) % 2 == 1) {
        t.row(f++) << a, b, c;
        t.row(f++) << b, d, c;
      } else {
        t.row(f++) << a, b, d;
        t.row(f++) << a, d, c;
      }
    }
  return make_mesh(x, t);
}

//! A triangle by its corners' coordinates, from its smallest corner on, in its own orientation:
//! two faces have the same key when they are the same triangle, bit for bit.
using TriangleKey = std::array<std::array<double, 3>, 3>;

inline TriangleKey triangle_key(const Mesh& mesh, Mesh::FaceHandle f)
{
  TriangleKey key{};
  std::size_t k = 0;
  for (const auto v : mesh.fv_range(f)) {
    const auto& p = mesh.point(v);
    key[k++] = {p[0], p[1], p[2]};
  }
  std::rotate(key.begin(), std::min_element(key.begin(), key.end()), key.end());
  return key;
}

//! The disjoint union of meshes (vertex and face indices of each follow those of the previous).
inline Mesh disjoint_union(const std::vector<const Mesh*>& parts)
{
  int nv = 0, nf = 0;
  for (const Mesh* m : parts) {
    nv += static_cast<int>(m->n_vertices());
    nf += static_cast<int>(m->n_faces());
  }
  VertexVectors x(nv, 3);
  FaceIndices t(nf, 3);
  int v0 = 0, f0 = 0;
  for (const Mesh* m : parts) {
    x.middleRows(v0, m->n_vertices()) = vertex_positions(*m);
    t.middleRows(f0, m->n_faces()) = (face_indices(*m).array() + v0).matrix();
    v0 += static_cast<int>(m->n_vertices());
    f0 += static_cast<int>(m->n_faces());
  }
  return make_mesh(x, t);
}

//! Copy of `mesh` with every vertex mapped by `map`.
inline Mesh mapped(const Mesh& mesh, const std::function<Eigen::Vector3d(const Eigen::Vector3d&)>& map)
{
  Mesh out = mesh;
  for (auto v : out.vertices())
    out.set_point(v, to_point(map(to_eigen(out.point(v)))));
  return out;
}

//! A unit sphere made uneven (r = 1 + 0.1 z²), so that the flow moves it, rebuilt from its arrays
//! as a flow holds its surface.
inline Mesh uneven_sphere()
{
  Mesh m = analytic::icosphere(3);
  for (const auto v : m.vertices()) {
    const auto p = m.point(v);
    m.set_point(v, p * (1 + 0.1 * p[2] * p[2]));
  }
  return make_mesh(vertex_positions(m), face_indices(m));
}

//! A worn cap of the unit sphere: the faces of icosphere(5) with centroid z > 0.3, cut out (its rim
//! a boundary loop), and its vertices above z = 0.45 jittered by up to ±0.2 of the mean edge length
//! (fixed seed) and put back on the sphere. Remeshed with its rim kept, it leaves interior vertices
//! too close to the rim (the case the remesher's settling is for). `edge_length`: the mean edge.
inline Mesh worn_sphere_cap(double* edge_length)
{
  Mesh sphere = analytic::icosphere(5);
  double ell = 0;
  for (const auto e : sphere.edges())
    ell += sphere.calc_edge_length(e);
  ell /= static_cast<double>(sphere.n_edges());
  std::mt19937 random(7);
  std::uniform_real_distribution<double> offset(-0.2 * ell, 0.2 * ell);
  std::vector<char> in_cap(sphere.n_faces(), 0);
  for (const auto f : sphere.faces())
    in_cap[f.idx()] = sphere.calc_face_centroid(f)[2] > 0.3;
  for (const auto v : sphere.vertices())
    if (Mesh::Point p = sphere.point(v); p[2] > 0.45) {
      p += Mesh::Point(offset(random), offset(random), offset(random));
      sphere.set_point(v, p / p.norm());
    }
  *edge_length = ell;
  return extract_face_patch(sphere, in_cap).mesh;
}

//! A closed plate `length` × `width` × `thickness` as a CAD export triangulates it: each face a
//! grid of `nx` × `ny` cells cut into two triangles, the rim a strip of long thin triangles between
//! the two grids' edges. Its edges are sharp (90°) and it is thinner than its mean edge.
inline Mesh cad_plate(double length, double width, double thickness, int nx, int ny)
{
  const int layer = (nx + 1) * (ny + 1);
  const auto id = [&](int ix, int iy, int top) { return ix * (ny + 1) + iy + (top ? 0 : layer); };
  VertexVectors x(2 * layer, 3);
  for (int top : {1, 0})
    for (int ix = 0; ix <= nx; ++ix)
      for (int iy = 0; iy <= ny; ++iy)
        x.row(id(ix, iy, top)) << length * ix / nx, width * iy / ny, top ? 0.5 * thickness : -0.5 * thickness;
  std::vector<Eigen::Vector3i> t;
  for (int top : {1, 0})
    for (int ix = 0; ix < nx; ++ix)
      for (int iy = 0; iy < ny; ++iy) {
        const int a = id(ix, iy, top), b = id(ix + 1, iy, top), c = id(ix + 1, iy + 1, top), d = id(ix, iy + 1, top);
        if (top)
          t.insert(t.end(), {{a, b, c}, {a, c, d}});
        else
          t.insert(t.end(), {{a, c, b}, {a, d, c}});
      }
  std::vector<std::array<int, 2>> rim; // the grid's boundary, counter-clockwise seen from the top
  for (int ix = 0; ix < nx; ++ix)
    rim.push_back({ix, 0});
  for (int iy = 0; iy < ny; ++iy)
    rim.push_back({nx, iy});
  for (int ix = nx; ix > 0; --ix)
    rim.push_back({ix, ny});
  for (int iy = ny; iy > 0; --iy)
    rim.push_back({0, iy});
  for (std::size_t k = 0; k < rim.size(); ++k) {
    const auto& p = rim[k];
    const auto& q = rim[(k + 1) % rim.size()];
    const int a = id(p[0], p[1], 1), b = id(q[0], q[1], 1), c = id(q[0], q[1], 0), d = id(p[0], p[1], 0);
    t.insert(t.end(), {{a, d, c}, {a, c, b}});
  }
  FaceIndices faces(static_cast<Eigen::Index>(t.size()), 3);
  for (std::size_t k = 0; k < t.size(); ++k)
    faces.row(static_cast<Eigen::Index>(k)) = t[k].transpose();
  return make_mesh(x, faces);
}

} // namespace sdflow::test
