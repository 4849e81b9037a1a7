#pragma once
//! \file point_normals.h
//! \brief Oriented normals of a point set: degree-2 jet fitting over the k nearest neighbours
//! (Cazals & Pouget 2005), oriented along a minimum spanning tree of the k-NN graph (Hoppe,
//! DeRose, Duchamp, McDonald, Stuetzle 1992). Points whose orientation disagrees with their
//! neighbourhood are removed: in the re-triangulation pipeline (docs/design.md §3, stage 3) they mark where
//! two sheets of the surface meet.

#include "sdflow/mesh.h"

#include <Eigen/Core>

#include <vector>

namespace sdflow {

//! Row i lists the k points nearest to point i, nearest first, point i itself included (#P by k).
using NeighbourTable = Eigen::Matrix<int, Eigen::Dynamic, Eigen::Dynamic, Eigen::RowMajor>;

//! The k nearest neighbours of every point (kd-tree, nanoflann), point i itself counted among them
//! as CGAL counts it. Throws InvalidParameter unless 2 <= k <= #P, InvalidMesh on non-finite points.
NeighbourTable nearest_neighbours(const VertexVectors& points, int k);

//! Unoriented unit normals (#P by 3): the normal at the origin of the degree-2 jet
//! z = Σ_{i+j<=2} a_ij x^i y^j fitted by least squares to the neighbours of each point, in the
//! frame of their principal axes centred at the point (Cazals & Pouget 2005). Needs k >= 6; a
//! neighbourhood too degenerate for the fit (collinear points) keeps its principal-axis normal.
//! Accuracy (k = 18, tests/reconstruct/test_point_normals.cpp): without noise the mean angular error
//! falls at least as h² with the spacing h; on unit-size spheres, tori and ellipsoids with noise
//! of standard deviation h²/2 it stays below 0.3 h radians.
VertexVectors jet_normals(const VertexVectors& points, const NeighbourTable& neighbours);

//! When an oriented point counts as consistent with its neighbourhood.
struct OrientationOptions {
  //! A neighbour agrees with point i when their oriented normals make an angle below this
  //! (radians, default 40°). Neighbouring normals of a smooth surface differ by about the
  //! neighbourhood radius times the curvature: no point is removed while spacing × curvature
  //! stays below about 0.3 (k = 18). Across a crossing or between two touching sheets they
  //! differ by 45° to 180°.
  double agreement_angle = 40 * M_PI / 180;
  //! A point is inconsistent when fewer than this fraction of its k - 1 neighbours agree.
  double min_agreement = 0.5;
};

//! Orientation of a set of unoriented normals.
struct NormalOrientation {
  VertexVectors normals;          //!< The input normals, each flipped or not (#P by 3).
  std::vector<int> inconsistent;  //!< Points failing the agreement test, in increasing order.
  int components = 0;             //!< Connected components of the k-NN graph (one seed each).
};

//! Orient unit normals along a minimum spanning tree of the symmetric k-NN graph with edge weights
//! 1 - |n_i · n_j| (Hoppe et al. 1992), grown by Prim's algorithm from one seed per connected
//! component: the component's extreme point along the coordinate axis its normal is most aligned
//! with, whose normal is made to point outward along that axis. Then flags the points whose
//! oriented normal agrees with too few neighbours (OrientationOptions).
NormalOrientation orient_normals(const VertexVectors& points, const VertexVectors& normals,
                                 const NeighbourTable& neighbours, const OrientationOptions& options = {});

//! Options of the whole estimation (jet fit, orientation, removal).
struct PointNormalsOptions {
  //! Neighbourhood size k, the point itself included (CGAL's convention); at least 6.
  int neighbours = 18;
  OrientationOptions orientation;
};

//! Points with oriented unit normals, and the points removed on the way.
struct OrientedPoints {
  VertexVectors points;      //!< The points kept (#K by 3).
  VertexVectors normals;     //!< Their oriented unit normals, outward on closed surfaces (#K by 3).
  std::vector<int> source;   //!< Input index of each kept point.
  std::vector<int> removed;  //!< Input indices of the points removed as inconsistently oriented.
};

//! Jet normals, MST orientation, removal of the inconsistent points, then a second MST
//! orientation of the points kept over the k-NN graph restricted to them (the removal can split
//! it into components that each need their own outward seed, e.g. two sheets that touched).
OrientedPoints oriented_point_normals(const VertexVectors& points, const PointNormalsOptions& options = {});

//! The same on the vertices of a mesh (its connectivity is not used).
OrientedPoints oriented_point_normals(const Mesh& mesh, const PointNormalsOptions& options = {});

//! oriented_point_normals, then each connected piece of the k-NN graph it last oriented along
//! turned to agree on the whole with reference normals (#P by 3; the sum of n·r over the piece is
//! made positive), e.g. the vertex normals of the oriented surface the points were taken from.
//! For a piece of a surface, where the spanning tree's outward seed is not defined (the extreme
//! point of a patch cut from the inner wall of a torus faces inward), but the surface's own
//! orientation is known. Throws as oriented_point_normals, and InvalidParameter when the reference
//! has another row count.
OrientedPoints normals_oriented_by_reference(const VertexVectors& points, const VertexVectors& reference,
                                             const PointNormalsOptions& options = {});

} // namespace sdflow
