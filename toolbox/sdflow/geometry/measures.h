#pragma once
//! \file measures.h
//! \brief Area, enclosed volume, edge lengths, mean-curvature deviation and the sphere distances D1/D2 of §4.4.

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace sdflow {

//! Sum of triangle areas (§2.2.4).
double surface_area(const Mesh& mesh);

//! Signed volume a·(b×c)/6 of the cone from the origin over the triangle (a, b, c): summed over
//! the triangles of a closed surface, the volume it encloses (divergence theorem, §2.2.4).
inline double cone_volume(const Eigen::Vector3d& a, const Eigen::Vector3d& b, const Eigen::Vector3d& c)
{
  return a.dot(b.cross(c)) / 6.0;
}

//! cone_volume of face f, its corners taken from its halfedge: from, to, next's to.
double cone_volume(const Mesh& mesh, Mesh::FaceHandle f);

//! Signed enclosed volume by the divergence theorem, Σ a·(b×c)/6 over triangles (§2.2.4).
//! Positive for outward-oriented closed surfaces; meaningful only for closed components.
double enclosed_volume(const Mesh& mesh);

//! Signed volume of each component, in the order of face_component_ids().
std::vector<double> component_volumes(const Mesh& mesh);

//! Signed volume of each component for positions and triangles given as arrays
//! (`face_component[f]` in 0..count-1), e.g. to test a step's trial positions: Σ cone_volume over
//! its triangles, corners in the rows' order. The flow accepts or rejects steps by these sums, so
//! their order is fixed (docs/design.md §8).
std::vector<double> component_volumes(const VertexVectors& positions, const FaceIndices& triangles,
                                      const std::vector<int>& face_component, int count);

//! Mean edge length over the mesh (0 without edges): the scale of ℓ when none is given.
double mean_edge_length(const Mesh& mesh);

//! Mean length of the edges at each vertex (0 at an isolated vertex): the local scale h_v of the
//! time-step rule's displacement bound (time_step.h).
Eigen::VectorXd vertex_mean_edge_lengths(const Mesh& mesh);

//! Mean length of the edges at `v`, summed around it (0 at an isolated vertex): for the few
//! vertices a stage sizes (a hole's loop, the surroundings of a crossing) without the whole mesh's.
double mean_edge_length_at(const Mesh& mesh, Mesh::VertexHandle v);

//! Area-weighted mean curvature H̃ and its L1 deviation H_dev (§2.2.4), weights A(U_i).
struct CurvatureDeviation {
  double mean = 0;          //!< H̃ = Σ H_i A_i / Σ A_i
  double deviation = 0;     //!< H_dev = Σ |H_i - H̃| A_i / Σ A_i
  double deviation_pct = 0; //!< 100 H_dev / |H̃| (infinite when H̃ = 0)
};

//! H̃ and H_dev from per-vertex curvature and vertex areas (mixed Voronoi areas).
CurvatureDeviation curvature_deviation(const Eigen::VectorXd& curvature, const Eigen::VectorXd& vertex_areas);

//! Distances to a reference sphere (§4.4), weights A(U_i): D1 = mean of ||v_i - c| - r|, D2 = mean
//! absolute deviation of ||v_i - c| - r| from D1.
struct SphereDeviation {
  double d1 = 0;
  double d2 = 0;
};

SphereDeviation sphere_deviation(const Mesh& mesh, const Eigen::VectorXd& vertex_areas,
                                 const Eigen::Vector3d& centre = Eigen::Vector3d::Zero(), double radius = 1.0);

} // namespace sdflow
