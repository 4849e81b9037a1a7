#include "sdflow/mesh.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <algorithm>

namespace sdflow {

VertexVectors vertex_positions(const Mesh& mesh)
{
  VertexVectors x(mesh.n_vertices(), 3);
  for (auto v : mesh.vertices())
    x.row(v.idx()) = to_eigen(mesh.point(v)).transpose();
  return x;
}

void set_vertex_positions(Mesh& mesh, const VertexVectors& positions)
{
  if (positions.rows() != static_cast<Eigen::Index>(mesh.n_vertices()))
    throw InvalidParameter(fmt::format("set_vertex_positions: {} rows given for a mesh of {} vertices",
                                       positions.rows(), mesh.n_vertices()));
  for (auto v : mesh.vertices())
    mesh.set_point(v, to_point(positions.row(v.idx()).transpose()));
}

Mesh make_mesh(const VertexVectors& positions, const FaceIndices& triangles)
{
  Mesh mesh;
  mesh.reserve(positions.rows(), 3 * triangles.rows() / 2, triangles.rows());
  for (Eigen::Index i = 0; i < positions.rows(); ++i)
    mesh.add_vertex(to_point(positions.row(i).transpose()));
  const auto n = static_cast<int>(positions.rows());
  for (Eigen::Index f = 0; f < triangles.rows(); ++f) {
    const int a = triangles(f, 0), b = triangles(f, 1), c = triangles(f, 2);
    if (a < 0 || b < 0 || c < 0 || a >= n || b >= n || c >= n)
      throw InvalidMesh(fmt::format("triangle {} ({}, {}, {}) indexes outside the {} vertices", f, a, b, c, n));
    if (!mesh.add_face(Mesh::VertexHandle(a), Mesh::VertexHandle(b), Mesh::VertexHandle(c)).is_valid())
      throw InvalidMesh(fmt::format("triangle {} ({}, {}, {}) makes the surface non-manifold or "
                                    "inconsistently oriented", f, a, b, c));
  }
  return mesh;
}

FaceIndices face_indices(const Mesh& mesh)
{
  FaceIndices f(mesh.n_faces(), 3);
  for (auto face : mesh.faces()) {
    int k = 0;
    for (auto v : face.vertices())
      f(face.idx(), k++) = v.idx();
  }
  return f;
}

VertexVectors point_rows(const std::vector<Eigen::Vector3d>& points)
{
  VertexVectors x(static_cast<Eigen::Index>(points.size()), 3);
  for (std::size_t i = 0; i < points.size(); ++i)
    x.row(static_cast<Eigen::Index>(i)) = points[i].transpose();
  return x;
}

FaceIndices triangle_rows(const std::vector<std::array<int, 3>>& triangles)
{
  FaceIndices t(static_cast<Eigen::Index>(triangles.size()), 3);
  for (std::size_t i = 0; i < triangles.size(); ++i)
    t.row(static_cast<Eigen::Index>(i)) << triangles[i][0], triangles[i][1], triangles[i][2];
  return t;
}

void collect_garbage(Mesh& mesh)
{
  const auto deleted = [&](const auto& range) {
    return std::any_of(range.begin(), range.end(), [&](auto handle) { return mesh.status(handle).deleted(); });
  };
  if (deleted(mesh.all_vertices()) || deleted(mesh.all_edges()) || deleted(mesh.all_faces()))
    mesh.garbage_collection();
}

} // namespace sdflow
