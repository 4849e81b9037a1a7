#pragma once
//! \file untangle.h
//! \brief A surface's crossings with itself undone by moving vertices only, connectivity and
//! topology kept: the first thing `sdflow repair --remove-self-intersections` tries
//! (surface_repair.h), before any re-triangulation. Round after round, for each pair of faces of one
//! component that intersect:
//! - a corner whose outside is not outside (the winding number a hair off its face, along the face
//!   normal, is not 0: spatial/winding_number.h) moves along that normal: out where the number is
//!   negative (the walls of a thin part passed through each other: the part is thickened back), in
//!   where it is positive (the corner lies inside another part of the component);
//! - a fold (the faces share a vertex, or face the same way), and a pair no corner of which is
//!   misplaced, is relaxed: its corners move towards the centroid of their neighbours (the umbrella
//!   operator), and on while a triangle around it is turned over against its neighbours.
//! Walls moved apart go on until the part, or the gap, is half an edge wide there. Each move is a
//! fraction of the mean edge length and no vertex goes farther than a few edges from where it was,
//! so the surface changes only where it crossed. Unlike a re-triangulation this cannot cut a thin
//! part open or join two parts. Pairs between two components are left alone: two bodies that
//! overlap are joined by the pipeline's union (surface_union.h).

#include "sdflow/mesh.h"

#include <cstddef>

namespace sdflow {

struct UntangleOptions {
  int max_rounds = 300;        //!< rounds of moves at most (≥ 1)
  int patience = 40;           //!< rounds without a new fewest count of pairs before it gives up (≥ 1)
  double step = 0.2;           //!< a move per round, as a fraction of the mean edge length, in (0, 1]
  double max_displacement = 3; //!< how far a vertex may go in all, in mean edge lengths (> 0)
  //! Walls of a thin part, once apart, are pushed on until the part is this thick there (in mean
  //! edge lengths, ≥ 0), so that a remeshing at the mean edge length can keep them apart.
  double clearance = 0.5;
};

struct UntangleResult {
  Mesh mesh;                      //!< the input with moved vertices (unchanged when nothing crosses)
  std::size_t pairs_before = 0;   //!< intersecting pairs of faces of one component, in the input
  std::size_t pairs_after = 0;    //!< in the result (0 unless the rounds ran out)
  int rounds = 0;                 //!< rounds made
  std::size_t moved_vertices = 0; //!< vertices whose position changed
  double max_displacement = 0;    //!< the largest distance a vertex moved, in mean edge lengths
};

//! Throws InvalidParameter for options out of range.
void validate_untangle_options(const UntangleOptions& options);

//! Move vertices of `mesh` (valid, no deleted elements) until no two faces of one component
//! intersect, or the rounds run out. Throws InvalidParameter for options out of range.
UntangleResult untangle_crossings(const Mesh& mesh, const UntangleOptions& options = {});

} // namespace sdflow
