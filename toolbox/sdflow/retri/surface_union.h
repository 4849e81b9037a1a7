#pragma once
//! \file surface_union.h
//! \brief The boundary of the union of two surfaces that intersect (the paper's Appendix B). Both
//! are split along the curves where they cross (corefine.h), the parts of each inside the other are
//! removed, and what is left is joined along the curves, whose vertices both keep: one consistently
//! oriented surface, exact up to the rounding of the crossing points, however coarse the meshes and
//! however deep the overlap. A surface may have a boundary of its own (a sheet): its inside is then
//! the side its normals point away from, and its boundary stays as it is. Where two surfaces have
//! just touched, merge_touching_surfaces joins them by a band about an edge wide instead (zippering,
//! Turk & Levoy 1994), so that the flow does not start from a cusp.

#include "sdflow/mesh.h"

namespace sdflow {

struct UnionResult {
  Mesh mesh;                 //!< oriented as the inputs, closed unless one had a boundary; garbage-collected
  int removed_faces_a = 0;   //!< faces of the first surface (split along the curves) inside the second; with a band, crossing it too
  int removed_faces_b = 0;   //!< faces of the second surface (split along the curves) inside the first; with a band, crossing it too
  int joined_loops = 0;      //!< crossing curves along which the surfaces are joined (pairs of boundary loops joined by a band)
};

//! Union of two oriented surfaces (each may have several components, and a boundary), each one's
//! inside being the side its normals point away from. Without intersections the result is the
//! disjoint union, or the outer surface when one encloses the other; a surface united with itself
//! (the same triangles) gives itself back. When the surfaces are not in general position (a vertex
//! on the other surface, faces in one plane) the second is moved by a round-off amount, at most
//! 10⁻⁸ of the bounding box's diagonal. Throws InvalidMesh when the overlap reaches a surface's own
//! boundary, when a configuration stays degenerate after that move, or when no face of either lies
//! outside the other (the same body twice). A surface that crosses itself has no inside to split
//! by: such a pair is joined as before the corefinement, by bands across the loops left by removing
//! the faces crossing the other or inside it (and refused as InvalidMesh when those loops do not pair).
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
//! (bodies that overlap deeply, not a fresh contact), nor when that band would cross itself or the
//! surfaces (loops that do not face each other): then the exact union, as surface_union forms it.
//! The result keeps the first surface's orientation. Throws InvalidMesh as surface_union does.
UnionResult merge_touching_surfaces(const Mesh& a, const Mesh& b);

} // namespace sdflow
