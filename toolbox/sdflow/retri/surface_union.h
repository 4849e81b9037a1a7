#pragma once
//! \file surface_union.h
//! \brief The boundary of the union of two closed surfaces that intersect (the paper's Appendix B):
//! the parts of each surface inside the other and the triangles crossing it are removed, and each
//! pair of facing boundary loops left behind is joined by a band of triangles (zippering, Turk &
//! Levoy 1994), giving one closed, consistently oriented surface.

#include "sdflow/mesh.h"

namespace sdflow {

struct UnionResult {
  Mesh mesh;                 //!< closed, outward-oriented; garbage-collected
  int removed_faces_a = 0;   //!< faces of the first surface inside the second or crossing it
  int removed_faces_b = 0;   //!< faces of the second surface inside the first or crossing it
  int joined_loops = 0;      //!< pairs of boundary loops joined by a band
};

//! Union of two outward-oriented closed surfaces (each may have several components).
//! Without intersections the result is the disjoint union, or the outer surface when one encloses
//! the other; a surface united with itself (the same triangles) gives itself back. Throws InvalidMesh
//! when nothing would be left (the surfaces coincide over large parts), or when the loops left by the removal cannot be paired one to one
//! (the surfaces touch along a curve too short for the mesh resolution).
UnionResult surface_union(const Mesh& a, const Mesh& b);

} // namespace sdflow
