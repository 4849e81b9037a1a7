#pragma once
//! \file corefine.h
//! \brief Two surfaces split along the curves where they cross (corefinement, as CGAL's
//! `PMP::corefine` does; Lévy's and Attene's mesh Booleans start the same way): every crossing
//! point of an edge of one surface through a face of the other becomes a vertex both share, and
//! every face crossed is re-triangulated in its plane with the crossing segments as edges. After it
//! no face of one surface crosses the other; the curves are edges of both.
//!
//! The crossing points are decided with exact predicates (spatial/predicates.h) and placed in
//! floating point. Configurations not in general position (a vertex of one surface on the plane of
//! a face of the other that it meets, an edge through an edge, coplanar faces) are not resolved:
//! corefine throws CorefinementDegenerate for them, and the caller may move one surface by a
//! round-off amount and try again (surface_union.h does).

#include "sdflow/errors.h"
#include "sdflow/mesh.h"

#include <array>
#include <vector>

namespace sdflow {

//! A configuration corefine does not resolve (not in general position, or a piece of a face too
//! thin to triangulate); a translation of one surface by far less than an edge removes it.
class CorefinementDegenerate : public InvalidMesh {
public:
  using InvalidMesh::InvalidMesh;
};

struct Corefinement {
  //! The first surface's vertices (its indices), then the second's (shifted by its vertex count),
  //! then the crossing points.
  VertexVectors points;
  std::vector<std::array<int, 3>> faces_a; //!< the first surface's faces, split, oriented as they were
  std::vector<std::array<int, 3>> faces_b; //!< the second surface's faces, split, oriented as they were
  std::vector<std::array<int, 2>> curve;   //!< the crossing curves' edges, each as (smaller, larger) index
};

//! Split `a` and `b` along their crossing curves. Faces that no curve crosses are copied as they
//! are; a face is cut into the pieces its curves bound (a curve that closes inside one face, where a
//! vertex of the other surface pokes through it, bounds a piece and a hole in the piece around it),
//! and each piece triangulated so that its worst triangle is the roundest. Throws
//! CorefinementDegenerate as stated above, and InvalidMesh when a crossing curve ends on the
//! boundary of a surface that has one (its edge would have to be cut).
Corefinement corefine(const Mesh& a, const Mesh& b);

} // namespace sdflow
