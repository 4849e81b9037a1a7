#pragma once
//! \file remesh.h
//! \brief Isotropic remeshing (Botsch & Kobbelt 2004, "A remeshing approach to multiresolution
//! modeling"): the first step of the re-triangulation of paper §3.2.1 and the finishing step of
//! the implicit-surface mesher.
//!
//! Each iteration splits edges longer than 4/3 ℓ, collapses edges shorter than 4/5 ℓ (unless the
//! collapse would create an edge longer than 4/3 ℓ, invert a triangle or change the topology),
//! flips edges toward valence 6 (4 on the boundary), relaxes vertices tangentially and projects
//! them back onto the reference surface. What "the reference surface" is belongs to the caller:
//! a projection function (onto an implicit surface for the mesher, onto the pre-remesh surface
//! through a closest-point grid for the re-triangulation pipeline). After every iteration the
//! mesh is renumbered along a Morton curve (spatial_order.h), so the sweeps of the next one, and
//! their projections, read memory in order.

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <functional>
#include <vector>

namespace sdflow {

//! The remesher splits edges longer than this × their target: refined edges then lie between
//! 2/3 ℓ and 4/3 ℓ (with kRemeshCollapseRatio) and their mean is near ℓ.
inline constexpr double kRemeshSplitRatio = 4.0 / 3.0;
//! The remesher collapses edges shorter than this × their target.
inline constexpr double kRemeshCollapseRatio = 4.0 / 5.0;

//! Maps a point near the surface to its closest point on it (or on a boundary curve).
using PointProjection = std::function<Eigen::Vector3d(const Eigen::Vector3d&)>;
//! Maps a point near the surface to its closest point on the part of the surface that faces the
//! given direction (a normal of the remeshed surface there; zero: any part), so that where two
//! sheets lie closer than an edge (a thin blade, a tail) a vertex stays on its own sheet.
using FacingProjection = std::function<Eigen::Vector3d(const Eigen::Vector3d&, const Eigen::Vector3d&)>;

//! Target edge length at a point, for adaptive remeshing.
using SizingField = std::function<double(const Eigen::Vector3d&)>;

enum class BoundaryMode {
  remesh, //!< boundary edges are split and collapsed along the boundary, vertices slide on it
  keep,   //!< boundary vertices and edges are left exactly as they are
};

struct RemeshOptions {
  //! ℓ, the target edge length; 0 takes the input's mean edge length.
  double edge_length = 0;
  //! Split / collapse / flip / relax / project rounds.
  int iterations = 10;
  //! Tangential relaxation sweeps (each followed by projection) per iteration.
  int relaxation_steps = 3;
  //! Closest point on the surface. Empty: the input mesh itself (exact closest point, through
  //! the grid of spatial/closest_point_grid.h). A given function is called from one thread at a
  //! time; with both projections left empty the relaxation sweeps run on TBB threads (with the
  //! same results).
  PointProjection project;
  //! Closest point on the surface facing the remeshed surface's normal, used for interior vertices
  //! in place of `project` when set (the default projections are such: the input mesh's triangles
  //! that face the vertex, closest_point_grid.h). Empty with a given `project`: that one.
  FacingProjection project_facing;
  //! With the default projection: lift the closest point on the input's flat triangles onto the
  //! smooth surface they sample (a Phong tessellation from the eq. 8 normals), so that remeshing
  //! does not shrink convex parts by the triangles' sagitta. Off: the flat triangles themselves.
  bool curved_projection = false;
  //! Closest point on the boundary curves (BoundaryMode::remesh). Empty: the input's boundary
  //! polylines, through a nearest-vertex search (remesh/star_projection.h).
  PointProjection project_boundary;
  BoundaryMode boundary = BoundaryMode::remesh;
  //! Boundary vertices where the boundary turns by more than this angle (degrees) are corners:
  //! never moved or removed, so polygonal boundaries keep their shape.
  double boundary_corner_angle_deg = 45;
  //! Interior edges turning by more than this angle (degrees) between flat triangles are creases
  //! (crease_edges.h): never flipped or smoothed across, split at their midpoints and collapsed only
  //! along the crease, their vertices never relaxed, and those where a crease ends or meets
  //! another never moved or removed. 0 keeps no crease.
  double crease_angle_deg = 0;
  //! With BoundaryMode::keep: after the last iteration, let the vertices beside the kept boundary
  //! settle (Remesher::settle_beside_kept_boundary) and collapse the short edges left between them
  //! and the boundary. The rounds of remeshing leave such edges where a row of vertices came to lie
  //! too close to a boundary that cannot move toward them.
  bool settle_kept_boundary = false;
  //! Local target ℓ(p) for adaptive remeshing (e.g. curvature_sizing, or nearest_vertex_sizing of
  //! radius_targets); empty: uniform ℓ. It is called from several threads at once (both of those
  //! may be). An edge's target is the mean of the targets at its two ends.
  SizingField sizing;
  //! With a sizing field: relax each vertex toward the centroid of its faces' centroids, each
  //! weighted by its area / target² (Dunyach et al. 2013, "Adaptive remeshing for real-time mesh
  //! deformation"), instead of toward the centroid of its neighbours weighted by their targets. The
  //! latter pulls vertices out of a band of small targets toward the larger ones around it: where
  //! targets drop fourfold within an edge or two (a neck, a crease between particles) it leaves
  //! slivers and triangles of up to 178°. The re-triangulation uses it when graded
  //! (RetriangulationOptions::graded_remeshing).
  bool area_weighted_relaxation = false;
  //! Stop splitting once the mesh has this many vertices (0: no bound), and remesh no further
  //! (RemeshStatistics::stopped says so): for a caller that discards a remeshing grown beyond
  //! what its targets ask for rather than waiting for it.
  std::size_t max_vertices = 0;
};

//! What the remesher did, summed over all iterations.
struct RemeshStatistics {
  long splits = 0;
  long collapses = 0;
  long flips = 0;
  long relaxation_reverts = 0; //!< vertex moves undone because they would have inverted a triangle
  double edge_length = 0; //!< the ℓ used (uniform part)
  //! The mesh reached RemeshOptions::max_vertices: it is valid, but not remeshed to its targets.
  bool stopped = false;
};

struct RemeshResult {
  Mesh mesh; //!< garbage-collected (vertex i is VertexHandle(i)), numbered along a Morton curve
  RemeshStatistics statistics;
};

//! Isotropic remeshing of `mesh` (Botsch & Kobbelt 2004). Genus, components and boundary loops
//! are preserved (collapses pass OpenMesh's link condition; boundary vertices stay on the
//! boundary). Throws InvalidParameter for a non-positive ℓ, negative iteration counts or a
//! sizing field that returns a non-positive length, InvalidMesh for an empty mesh.
RemeshResult isotropic_remesh(const Mesh& mesh, const RemeshOptions& options = {});

//! The projection of RemeshOptions::curved_projection onto `surface` (no deleted elements): its
//! closest point, lifted onto the smooth surface by the Phong tessellation of the given unit vertex
//! normals (#V by 3; eq. 8's, possibly computed on a larger surface than this one, so that a
//! patch's boundary vertices get the normals of their whole star). Safe to call from several
//! threads. Throws InvalidMesh for a surface without triangles, InvalidParameter for a wrong
//! normal count.
FacingProjection curved_surface_projection(const Mesh& surface, VertexVectors normals);

//! Curvature-adapted sizing (Dunyach et al. 2013): ℓ(v) = √(6ε/κ − 3ε²) where κ is the largest
//! absolute principal curvature at v (from the discrete mean curvature, eq. 9, and the angle
//! defect), so the chord deviates at most ε from the surface; clamped to [min_length, max_length].
struct CurvatureSizingOptions {
  double tolerance = 0;  //!< ε, the approximation error allowed (> 0)
  double min_length = 0; //!< smallest target (> 0)
  double max_length = 0; //!< largest target (≥ min_length)
};

//! Sizing field from the curvature of `mesh`: the target at a point is the one of the nearest
//! vertex of `mesh`. Throws InvalidParameter for out-of-range options.
SizingField curvature_sizing(const Mesh& mesh, const CurvatureSizingOptions& options);

//! A sizing field from a target length at each vertex of `mesh` (no deleted elements): the target
//! at a point is the one of the nearest vertex. Throws InvalidParameter unless there is one length
//! per vertex.
SizingField nearest_vertex_sizing(const Mesh& mesh, std::vector<double> lengths);

//! Targets by the radius of curvature: ℓ(v) = 1 / (n κ(v)), n edges per radius of curvature at
//! the vertex (κ its largest absolute principal curvature, from the cotangent H and the angle
//! defect), clamped to [min_length, max_length]. A thinning neck of radius r gets edges of r / n,
//! so it stays resolved as it closes; flat and gently curved parts keep max_length. Where the
//! radius of curvature is below the local mean edge length h (a crease, a fold, two sheets that
//! crossed), the curvature is not one the mesh resolves: the target there is h (clamped).
struct RadiusSizingOptions {
  double edges_per_radius = 4; //!< n (> 0)
  double min_length = 0;       //!< floor (> 0)
  double max_length = 0;       //!< ceiling (≥ min_length, finite)
  //! Gradient limit (≥ 0, 0: none): targets are lowered until none exceeds a neighbour's by more
  //! than this × the edge between them (Persson 2006), so that they grade over several edges where
  //! the curvature jumps (a neck, a crease) instead of within one, where the remesher has to leave
  //! slivers.
  double max_growth = 0;
};

//! The target length ℓ(v) of the rule above at each vertex of `mesh` (no deleted elements).
//! Throws InvalidParameter for out-of-range options.
std::vector<double> radius_targets(const Mesh& mesh, const RadiusSizingOptions& options);

//! The same rule with a given κ at each vertex (#V, ≥ 0) in place of the geometric one: e.g. the
//! weighted curvature of an anisotropic energy (geometry/weighted_curvature.h). Throws
//! InvalidParameter for out-of-range options or a wrong count.
std::vector<double> radius_targets(const Mesh& mesh, const Eigen::VectorXd& kappa, const RadiusSizingOptions& options);

} // namespace sdflow
