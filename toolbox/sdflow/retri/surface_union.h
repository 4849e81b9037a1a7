#pragma once
//! \file surface_union.h
//! \brief The boundary of the union of two surfaces that intersect (the paper's Appendix B): the
//! parts of each surface inside the other and the triangles crossing it are removed, and each pair
//! of facing boundary loops left behind is joined by a band of triangles (zippering, Turk & Levoy
//! 1994), giving one consistently oriented surface. A surface may have a boundary of its own (a
//! sheet): its inside is then the side its normals point away from, and its boundary stays as it is.

#include "sdflow/mesh.h"

namespace sdflow {

struct UnionResult {
  Mesh mesh;                 //!< oriented as the inputs, closed unless one had a boundary; garbage-collected
  int removed_faces_a = 0;   //!< faces of the first surface inside the second or crossing it
  int removed_faces_b = 0;   //!< faces of the second surface inside the first or crossing it
  int joined_loops = 0;      //!< pairs of boundary loops joined by a band
};

//! Union of two oriented surfaces (each may have several components, and a boundary), each one's
//! inside being the side its normals point away from. Without intersections the result is the
//! disjoint union, or the outer surface when one encloses the other; a surface united with itself
//! (the same triangles) gives itself back. Throws InvalidMesh, saying that the bodies overlap, when
//! no face of one lies outside the other (meshed too coarsely for their overlap, or the same body
//! twice), when the loops left by the removal cannot be paired one to one (the surfaces cross along
//! a curve too short for the mesh resolution, or nearly coincide), or when the overlap reaches a
//! surface's own boundary.
UnionResult surface_union(const Mesh& a, const Mesh& b);

//! The surface after two interfaces that touch have merged (Appendix B, whatever the surfaces'
//! orientations): each surface separates two phases, so of the three regions the two surfaces
//! bound near their contact, the one between them is pinched where they touch and the two beyond
//! them join. Each surface is taken with the side away from the other (where less than half of the
//! other's area lies) as its inside, and their union is formed as surface_union does. Two bodies
//! that touch become their union; a cavity that reaches the wall of the body around it, or a closed
//! bubble that reaches a sheet with a boundary, opens through it (the wall or sheet dimpled into
//! the bubble, the sheet's boundary unchanged). Where the surfaces come closer than a triangle's
//! longest edge its faces are removed too, so the joint starts about an edge wide instead of as a
//! cusp narrower than the mesh resolves; not when a face lies deeper inside the other than that
//! (bodies that overlap deeply, not a fresh contact). The result keeps the first surface's orientation.
//! Throws InvalidMesh as surface_union does.
UnionResult merge_touching_surfaces(const Mesh& a, const Mesh& b);

} // namespace sdflow
