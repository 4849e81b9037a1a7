#pragma once
//! \file face_patch.h
//! \brief A patch of a surface's faces cut out as a mesh of its own and put back in place: the
//! region a local remeshing (local_remesh.h) works on, stitched to the untouched surface along
//! its boundary, which both share vertex for vertex.

#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

//! The faces within `rings` rings of the marked ones (one ring: every face sharing a vertex with
//! the faces so far; `marked` has one flag per face of `mesh`, which has no deleted elements),
//! grown further at every vertex around which the patch would have several separate fans of
//! faces, so that the patch is a manifold surface (with boundary) of its own.
std::vector<char> grow_face_patch(const Mesh& mesh, std::vector<char> marked, int rings);

//! A patch cut out of a surface.
struct FacePatch {
  Mesh mesh;                 //!< the patch's faces (in the surface's order) and their vertices
  std::vector<int> vertices; //!< patch vertex → vertex of the surface
};

//! The faces of `mesh` (no deleted elements) flagged in `in_patch` as a mesh of their own.
//! Throws InvalidMesh when they do not form a manifold surface (grow_face_patch makes them one).
FacePatch extract_face_patch(const Mesh& mesh, const std::vector<char>& in_patch);

//! `mesh` with the faces flagged in `in_patch` replaced by `replacement` (no deleted elements),
//! whose boundary must be the patch's boundary: the same vertices at bit-identical positions,
//! joined by the same edges. Outside the patch, vertices and faces keep their positions, connectivity and relative order;
//! the replacement's interior vertices and faces take the slots the patch's interior vertices and
//! faces leave (in order), and any left over come last. Throws InvalidMesh when the replacement's
//! boundary is not the patch's.
struct StitchedPatch {
  Mesh mesh;                   //!< the surface with the replacement in the patch's place
  std::vector<int> vertex_map; //!< vertex of the surface → of `mesh`; -1 for the patch's interior ones
};
StitchedPatch replace_face_patch(const Mesh& mesh, const std::vector<char>& in_patch, const Mesh& replacement);

} // namespace sdflow
