#pragma once
//! \file test_meshes.h
//! \brief Small meshes for the tests: grids mapped by a function, disjoint unions, mapped copies,
//! worn sphere caps. Header-only helpers shared by the test files.

#include "sdflow/mesh.h"
#include "sdflow/remesh/face_patch.h"
#include "support/analytic_meshes.h"

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

} // namespace sdflow::test
