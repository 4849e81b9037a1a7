#pragma once
//! \file exact_refinement.h
//! \brief Refinement that leaves the surface exactly where it is: edges longer than a bound are
//! split at their midpoints, the longest first (Rivara's longest-edge bisection, 1984: every split
//! edge is the longest of both its triangles, so no angle falls below half the smallest angle of
//! the input), then edges between coplanar triangles are flipped to the Delaunay choice (Lawson's
//! flips, 1977). A midpoint lies on its edge and a flip inside a plane covers the same two
//! triangles, so creases, corners, the boundary and the enclosed volume stay as given (to the
//! rounding of the midpoints), which isotropic remeshing (remesh.h), whose relaxation and
//! projection cut across creases, does not give.

#include "sdflow/mesh.h"

#include <cstddef>

namespace sdflow {

struct ExactRefinementOptions {
  //! Split every edge longer than this (> 0, finite): the result's edges are at most this long.
  double max_edge_length = 0;
  //! Stop splitting once the mesh has this many vertices (0: no bound); ExactRefinement::stopped
  //! then says so.
  std::size_t max_vertices = 0;
};

struct ExactRefinement {
  Mesh mesh;      //!< the refined surface (no deleted elements); the input's vertices keep their indices
  long splits = 0;
  long flips = 0;
  bool stopped = false; //!< max_vertices was reached before every edge was short enough
};

//! Refine `mesh` (no deleted elements) as above. Throws InvalidParameter for a bound that is not
//! positive and finite.
ExactRefinement refine_exactly(const Mesh& mesh, const ExactRefinementOptions& options);

} // namespace sdflow
