#pragma once
//! \file remove_intersections.h
//! \brief Removing the self-intersecting faces of a surface, then the vertices left without a face
//! (paper §3.2.1, docs/design.md §3 step 2): the surface that remains intersects itself nowhere, and
//! its holes are what the point-normal and reconstruction steps repair.

#include "sdflow/mesh.h"
#include "sdflow/spatial/intersect.h"

#include <vector>

namespace sdflow {

//! The surface without its intersecting faces, and what was removed (all in input indices).
struct RemovalResult {
  Mesh mesh;                                //!< garbage-collected; every vertex has a face
  std::vector<FacePair> intersecting_pairs; //!< as self_intersections() found them
  std::vector<int> removed_faces;           //!< faces of those pairs (degenerate ones included), sorted
  std::vector<int> removed_vertices;        //!< vertices left without a face (or without one before), sorted
  std::vector<int> vertex_origin;           //!< input index of each output vertex
  std::vector<int> face_origin;             //!< input index of each output face
  //! Output vertices where the remaining faces meet in more than one fan (a pinch: the removal cut
  //! the surface around them), valid in OpenMesh but not a manifold neighbourhood.
  std::vector<int> pinched_vertices;
};

//! Delete every face of every intersecting pair (self_intersections(), exact), then every vertex
//! without a face. The input must carry no deleted faces.
RemovalResult remove_self_intersections(const Mesh& mesh);

//! The same with the mesh's self-intersections already found (`pairs`, as self_intersections()
//! returns them).
RemovalResult remove_self_intersections(const Mesh& mesh, std::vector<FacePair> pairs);

} // namespace sdflow
