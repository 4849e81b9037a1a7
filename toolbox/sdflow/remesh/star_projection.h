#pragma once
//! \file star_projection.h
//! \brief Closest points on a reference mesh by a nearest-vertex search: the closest point among
//! the triangles (or boundary edges) around the k reference vertices nearest to the query.
//!
//! The remesher projects boundary vertices onto the input's boundary polylines with it (the BVH
//! of bvh.h covers triangles only). It is exact whenever the closest triangle
//! has one of its corners among the k nearest vertices, which holds for well-shaped reference
//! meshes and queries within about an edge length of the surface (the remesher's case). It is
//! not a general closest-point query: use a BVH for far queries or very uneven triangles.

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <memory>
#include <vector>

namespace sdflow {

class StarProjection {
public:
  //! Copies the geometry of `reference`; throws InvalidMesh if it has no triangles.
  //! `neighbours` is k, the number of nearest reference vertices whose stars are searched.
  explicit StarProjection(const Mesh& reference, int neighbours = 8);
  ~StarProjection();
  StarProjection(StarProjection&&) noexcept;
  StarProjection& operator=(StarProjection&&) noexcept;

  //! Closest point to p on the reference triangles around its nearest vertices.
  Eigen::Vector3d closest_point(const Eigen::Vector3d& p) const;

  //! Closest point to p on the reference boundary edges around its nearest boundary vertices;
  //! p itself when the reference has no boundary.
  Eigen::Vector3d closest_boundary_point(const Eigen::Vector3d& p) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

//! Closest point to p on the triangle abc (Ericson, Real-Time Collision Detection, §5.1.5).
Eigen::Vector3d closest_point_on_triangle(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                                          const Eigen::Vector3d& c);

//! Closest point to p on the segment ab.
Eigen::Vector3d closest_point_on_segment(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b);

} // namespace sdflow
