#pragma once
//! \file mesh.h
//! \brief The surface type: an OpenMesh triangle mesh with double-precision points.
//!
//! Conventions (docs/design.md §1): vertex i of every per-vertex array is `Mesh::VertexHandle(i)`, so
//! meshes handed to the geometry and flow code carry no deleted elements (call
//! `garbage_collection()` after editing). Closed components are oriented with outward normals.

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <OpenMesh/Core/Mesh/TriMesh_ArrayKernelT.hh>

#include <array>
#include <vector>

namespace sdflow {

//! OpenMesh traits: double points and normals, status flags for editing, previous-halfedge links.
struct MeshTraits : public OpenMesh::DefaultTraits {
  using Point = OpenMesh::Vec3d;
  using Normal = OpenMesh::Vec3d;
  VertexAttributes(OpenMesh::Attributes::Status);
  EdgeAttributes(OpenMesh::Attributes::Status);
  FaceAttributes(OpenMesh::Attributes::Status);
  HalfedgeAttributes(OpenMesh::Attributes::PrevHalfedge);
};

//! An oriented triangulated surface, possibly with boundary and several components.
using Mesh = OpenMesh::TriMesh_ArrayKernelT<MeshTraits>;

//! Per-vertex 3-vectors (#V by 3), row i for vertex i: positions, normals, displacements.
using VertexVectors = Eigen::Matrix<double, Eigen::Dynamic, 3, Eigen::RowMajor>;

//! Triangles as rows of three vertex indices (#F by 3).
using FaceIndices = Eigen::Matrix<int, Eigen::Dynamic, 3, Eigen::RowMajor>;

//! OpenMesh point to Eigen vector.
inline Eigen::Vector3d to_eigen(const Mesh::Point& p) { return {p[0], p[1], p[2]}; }

//! Eigen vector to OpenMesh point.
inline Mesh::Point to_point(const Eigen::Vector3d& v) { return {v.x(), v.y(), v.z()}; }

//! The three corners of a triangle, in the face's orientation: vertex indices and positions.
struct TriangleCorners {
  std::array<int, 3> index;
  std::array<Eigen::Vector3d, 3> point;
};

//! Corners of face f, starting at the vertex OpenMesh lists first.
inline TriangleCorners triangle_corners(const Mesh& mesh, Mesh::FaceHandle f)
{
  TriangleCorners t{};
  int k = 0;
  for (auto v : mesh.fv_range(f)) {
    t.index[k] = v.idx();
    t.point[k++] = to_eigen(mesh.point(v));
  }
  return t;
}

//! Vertex positions as a #V by 3 matrix.
VertexVectors vertex_positions(const Mesh& mesh);

//! Points gathered in a list, as a #P by 3 matrix (row i = points[i]).
VertexVectors point_rows(const std::vector<Eigen::Vector3d>& points);

//! Triangles gathered in a list, as a #F by 3 matrix (row i = triangles[i]).
FaceIndices triangle_rows(const std::vector<std::array<int, 3>>& triangles);

//! Overwrite vertex positions from a #V by 3 matrix (throws InvalidParameter on a size mismatch).
void set_vertex_positions(Mesh& mesh, const VertexVectors& positions);

//! Make a mesh from vertex positions and triangles (indices into `positions`), in this order.
//! Throws InvalidMesh if OpenMesh rejects a triangle (non-manifold or inconsistently oriented).
Mesh make_mesh(const VertexVectors& positions, const FaceIndices& triangles);

//! Triangles as a #F by 3 matrix of vertex indices, in face order.
FaceIndices face_indices(const Mesh& mesh);

//! mesh.garbage_collection() when an element is deleted. With none deleted it leaves the mesh as it
//! was, but still rewrites every handle (19 ms at 95k vertices), so then nothing is done.
void collect_garbage(Mesh& mesh);

} // namespace sdflow
