#pragma once
//! \file mesher.h
//! \brief Implicit surface → quality triangulation: marching tetrahedra on a grid fine enough for
//! the topology, then isotropic remeshing (remesh/remesh.h) to the target edge length with every
//! vertex projected onto f = 0 by Newton steps (and boundary vertices onto the curve f = g = 0).
//!
//! This replaces the paper's CGAL Delaunay-refinement surface mesher (§3.1, angle bound 30°):
//! the remeshed triangles are nearly equilateral, and on smooth surfaces the 5th percentile of
//! the per-triangle minimum angle stays above 30°.

#include "sdflow/mesh.h"
#include "sdflow/remesh/remesh.h"
#include "sdflow/shapes/implicit.h"

#include <array>
#include <cstddef>

namespace sdflow {

struct MesherOptions {
  double edge_length = 0; //!< target edge length ℓ; give exactly one of edge_length and vertices
  int vertices = 0;       //!< approximate vertex count: ℓ is adjusted until within 2% of it
  int iterations = 10;    //!< remeshing iterations at the final ℓ
  //! Then refine where the surface curves: this many edges per radius of curvature where that is
  //! shorter than ℓ, down to ℓ/4 (remesh.h, radius_targets); 0 keeps the uniform ℓ. A flow started
  //! on the result begins with its necks resolved, which refining later cannot recover exactly.
  double edges_per_radius = 0;
  //! Marching-grid spacing near the surface; 0 = min(2ℓ, feature_size / 2), refined where complex.
  double grid_cell = 0;
  //! Projection tolerance on |f|/|∇f| relative to the box diagonal.
  double tolerance = 1e-12;
  //! Make sure of the result's topology and that it does not cross itself: the marching grid is
  //! halved (at most 3 times) until halving it no longer changes the components, genus and
  //! boundary loops; then the remeshed surface must keep that topology and have no intersecting
  //! faces (spatial/intersect.h). Otherwise InvalidParameter, saying what and where.
  bool check_topology = true;
};

//! Distribution of the per-triangle minimum angle, in degrees.
struct AngleDistribution {
  double min = 0, p01 = 0, p05 = 0, p25 = 0, median = 0, mean = 0;
  //! Triangle counts with minimum angle in [0°, 10°), [10°, 20°), ..., [50°, 60°].
  std::array<long, 6> histogram{};
};

//! Per-triangle minimum angles of `mesh`, summarised.
AngleDistribution triangle_min_angle_distribution(const Mesh& mesh);

struct MesherResult {
  Mesh mesh;
  double edge_length = 0;            //!< the ℓ finally used
  double grid_cell = 0;              //!< spacing of the marching grid
  std::size_t initial_vertices = 0;  //!< of the marching-tetrahedra triangulation
  std::size_t initial_faces = 0;
  double max_level_set_distance = 0; //!< max over vertices of |f|/|∇f|, relative to the box diagonal
  double max_boundary_distance = 0;  //!< max over boundary vertices of |g|/|∇g|, same scale
  AngleDistribution min_angles;
  RemeshStatistics remesh;           //!< of the last remeshing round
  int remesh_rounds = 0;             //!< rounds needed to reach the vertex count (1 with edge_length)
};

//! Mesh the surface. A closed surface gives closed components oriented outward (toward f > 0).
//! A clipped surface keeps f = 0 where g ≤ 0, with its rim on f = g = 0; a surface that leaves
//! its box is clipped by the box. Throws InvalidParameter for bad options, when f = 0 has no
//! point in the box (an empty level set), or (MesherOptions::check_topology) when the grid or ℓ
//! cannot resolve the surface's topology or the result crosses itself; SolverFailure if a
//! projection fails.
MesherResult mesh_implicit_surface(const ImplicitSurface& surface, const MesherOptions& options);

} // namespace sdflow
