#pragma once
//! \file advancing_front.h
//! \brief Surface reconstruction from an oriented point set by greedy advancing front over the
//! Delaunay tetrahedralisation (Cohen-Steiner & Da 2004), docs/design.md §3, stage 4.
//!
//! Every triangle of the result is a facet of the Delaunay tetrahedralisation of the points
//! (TetGen), so the surface cannot intersect itself. Starting from the facet with the smallest
//! empty circumsphere, the surface grows across its boundary edges, always taking next the most
//! plausible candidate: a facet that continues the surface smoothly (its fold with the surface is
//! within `beta`) in increasing order of radius, then facets that fold more, in increasing order
//! of fold, as long as their radius stays within a factor K of their neighbour's (K grows from
//! 1.1 to `radius_ratio_bound` when nothing else is left). Each addition keeps the surface an
//! oriented 2-manifold: an edge has at most two triangles, a vertex a single fan (two fronts
//! that meet at a vertex are joined only together with a Delaunay "ear" that merges the fans).
//! Triangles are oriented by the point normals and must agree with them, which keeps the surface
//! from bridging two nearby sheets. Where no plausible candidate exists the surface keeps a
//! boundary: a sampled disk stays a disk.

#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

struct ReconstructionOptions {
  //! Half-angle (radians) of the wedge around the surface's tangent continuation in which
  //! candidates are ranked by radius alone (CGAL's default 0.52, i.e. 30°).
  double beta = 0.52;
  //! Largest ratio between the radius of a candidate outside the wedge and the radius of the
  //! surface triangle it attaches to (CGAL's default 5); larger ratios leave a boundary there.
  double radius_ratio_bound = 5.0;
  //! Largest angle (radians) between a triangle's normal and the normal of each of its points.
  double max_normal_deviation = M_PI / 3;
  //! The Delaunay tetrahedralisation is computed on points moved by up to this fraction of the
  //! bounding-box diagonal (a fixed pseudo-random pattern); radii, angles and the result use the
  //! points as given. Sampled surfaces are full of degeneracies: a sphere's points are cospherical
  //! to rounding error, a geodesic or grid sampling puts whole families of points in common
  //! planes. Exactly, these force TetGen's exact arithmetic on most tests (5 to 10 times slower);
  //! at 1e-9 they survive as near-degeneracies that multiply the slivers (3.5 times more
  //! tetrahedra on a deformed geodesic sphere than at 1e-6). A perturbation of 1e-6 is 3e-4 of
  //! the spacing of 100k points; only facets within that distance of coplanar could differ from
  //! the exact tetrahedralisation. 0 uses the points as they are.
  double delaunay_perturbation = 1e-6;
};

//! A reconstructed surface and how it relates to the input points.
struct Reconstruction {
  Mesh mesh;                //!< Consistently oriented 2-manifold, possibly with boundary.
  std::vector<int> source;  //!< Input index of each mesh vertex.
  std::vector<int> unused;  //!< Input points that belong to no triangle (outliers, duplicates).
  int components = 0;       //!< Surface pieces grown from separate seeds.
};

//! Reconstruct a surface through `points` (#P by 3) oriented by their unit `normals` (#P by 3),
//! e.g. from oriented_point_normals. Closed pieces come out with the normals' orientation.
//! Throws InvalidParameter on mismatched sizes, fewer than 3 points, all points collinear or bad
//! options; InvalidMesh on non-finite points; SolverFailure if TetGen fails.
Reconstruction reconstruct_surface(const VertexVectors& points, const VertexVectors& normals,
                                   const ReconstructionOptions& options = {});

} // namespace sdflow
