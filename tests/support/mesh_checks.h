#pragma once
//! \file mesh_checks.h
//! \brief Brute-force checks of reconstructed and repaired surfaces: exact self-intersection
//! test over all triangle pairs, distances between a mesh and a surface, boundary loops.

#include "sdflow/io/soup.h"
#include "sdflow/mesh.h"

#include <functional>
#include <vector>

namespace sdflow::checks {

//! TetGen's volume and the divergence theorem's agree to this, relative (issue 2).
inline constexpr double kTetgenAgreement = 1e-9;

//! The mesh's vertices and triangles as a polygon soup, for the soup readers' and repairs' paths.
PolygonSoup soup_of(const Mesh& mesh);

//! Number of pairs of triangles that intersect beyond their shared vertices or edge, decided
//! with Shewchuk's exact orient3d (O(F²) with a bounding-box prefilter: small meshes only).
int self_intersecting_pairs(const Mesh& mesh);

//! Euclidean distance from p to the closed triangle abc.
double point_triangle_distance(const Eigen::Vector3d& p, const Eigen::Vector3d& a, const Eigen::Vector3d& b,
                               const Eigen::Vector3d& c);

//! Largest distance from the mesh to a surface, over the vertices, edge midpoints and 6 interior
//! points of every triangle; `distance` gives a point's distance to the surface.
double mesh_to_surface_distance(const Mesh& mesh, const std::function<double(const Eigen::Vector3d&)>& distance);

//! Upper bound of the largest distance from the surface samples to the mesh: each sample's
//! distance to the triangles around its nearest mesh vertex and that vertex's neighbours.
double surface_to_mesh_distance(const Mesh& mesh, const VertexVectors& surface_samples);

//! Vertex indices of each boundary loop, in the order of the boundary halfedges.
std::vector<std::vector<int>> boundary_loops(const Mesh& mesh);

//! True if every vertex has a single fan of triangles (OpenMesh's is_manifold) and no vertex is
//! isolated.
bool is_two_manifold(const Mesh& mesh);

//! Mean edge length.
double mean_edge_length(const Mesh& mesh);

} // namespace sdflow::checks
