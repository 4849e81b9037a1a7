#include "sdflow/geometry/normals.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <array>
#include <cmath>

namespace sdflow {

namespace {

//! Eq. (8) over the triangles `corners(f)`, f = 0 .. count-1, each three vertex indices of `mesh`.
template <class Corners>
VertexVectors normals_of_triangles(const Mesh& mesh, Eigen::Index count, const Corners& corners,
                                   const NormalOptions& options)
{
  VertexVectors n = VertexVectors::Zero(mesh.n_vertices(), 3);
  const bool equal_weights = options.boundary == BoundaryNormalRule::equal_weights;
  VertexVectors boundary_sum = equal_weights ? VertexVectors::Zero(mesh.n_vertices(), 3) : VertexVectors();

  const Mesh::Point* points = mesh.points();
  const auto vertices = static_cast<unsigned>(mesh.n_vertices());
  for (Eigen::Index f = 0; f < count; ++f) {
    const std::array<int, 3> idx = corners(f);
    if (static_cast<unsigned>(idx[0]) >= vertices || static_cast<unsigned>(idx[1]) >= vertices ||
        static_cast<unsigned>(idx[2]) >= vertices)
      throw InvalidParameter(fmt::format("vertex normals: a triangle ({}, {}, {}) names a vertex outside the mesh's {}",
                                         idx[0], idx[1], idx[2], vertices));
    const std::array<Eigen::Vector3d, 3> p{to_eigen(points[idx[0]]), to_eigen(points[idx[1]]), to_eigen(points[idx[2]])};
    // Every corner's e_i × e_{i+1} is the face's (p1 - p0) × (p2 - p0); the corner at p_c divides it
    // by the squared lengths of its two sides, those opposite p_{c+2} and p_{c+1}.
    const Eigen::Vector3d cross = (p[1] - p[0]).cross(p[2] - p[0]);
    const std::array<double, 3> opposite{(p[2] - p[1]).squaredNorm(), (p[0] - p[2]).squaredNorm(),
                                         (p[1] - p[0]).squaredNorm()};
    for (int c = 0; c < 3; ++c)
      n.row(idx[c]) += (cross / (opposite[(c + 2) % 3] * opposite[(c + 1) % 3])).transpose();
    if (equal_weights) {
      const double len = cross.norm();
      if (len > 0)
        for (int c = 0; c < 3; ++c)
          boundary_sum.row(idx[c]) += (cross / len).transpose();
    }
  }

  for (auto v : mesh.vertices()) {
    const int i = v.idx();
    if (equal_weights && mesh.is_boundary(v))
      n.row(i) = boundary_sum.row(i);
    const double len = n.row(i).norm();
    if (!(len > 0) || !std::isfinite(len))
      throw InvalidMesh(fmt::format("the normal at vertex {} is undefined ({}): its star is degenerate "
                                    "or empty", i, mesh.is_isolated(v) ? "isolated vertex" : "zero or non-finite sum"));
    n.row(i) /= len;
  }
  return n;
}

} // namespace

VertexVectors vertex_normals(const Mesh& mesh, const NormalOptions& options)
{
  return vertex_normals(mesh, face_indices(mesh), options);
}

VertexVectors vertex_normals(const Mesh& mesh, std::span<const std::array<int, 3>> triangles,
                             const NormalOptions& options)
{
  return normals_of_triangles(mesh, static_cast<Eigen::Index>(triangles.size()),
                              [&](Eigen::Index f) { return triangles[static_cast<std::size_t>(f)]; }, options);
}

VertexVectors vertex_normals(const Mesh& mesh, const FaceIndices& triangles, const NormalOptions& options)
{
  return normals_of_triangles(mesh, triangles.rows(), [&](Eigen::Index f) {
    return std::array<int, 3>{triangles(f, 0), triangles(f, 1), triangles(f, 2)};
  }, options);
}

} // namespace sdflow
