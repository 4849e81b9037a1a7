#pragma once
//! \file local_remesh.h
//! \brief Isotropic remeshing (remesh.h, Botsch & Kobbelt 2004) of the region around chosen faces
//! only: those faces and a few rings around them are cut out as a patch (face_patch.h), remeshed
//! with their boundary kept exactly and new vertices projected onto the surface as it was, and
//! stitched back along that boundary. The rest of the surface keeps its vertices and faces bit for
//! bit, so the cost follows the patch, not the surface.

#include "sdflow/mesh.h"
#include "sdflow/remesh/remesh.h"

#include <vector>

namespace sdflow {

struct LocalRemeshOptions {
  //! ℓ, the uniform target edge length where no per-vertex targets are given (> 0).
  double edge_length = 0;
  //! Split / collapse / flip / relax / project rounds (≥ 1).
  int iterations = 3;
  //! Rings of faces around the chosen ones that are remeshed with them (≥ 1): the patch's kept
  //! boundary lies this many rings out, so that the vertices of the chosen faces and of the first
  //! rings are free to move, merge and split.
  int rings = 3;
  //! Project onto the smooth surface the triangles sample (RemeshOptions::curved_projection), with
  //! the normals of each vertex's whole star; off: onto the flat triangles.
  bool curved_projection = true;
  //! Creases kept inside the patch (RemeshOptions::crease_angle_deg); 0: none.
  double crease_angle_deg = 0;
  //! Remesh nothing when the patch (chosen faces, rings, closure) would hold more than this share
  //! of the surface's faces (in (0, 1]): so much of it is worn that the whole pipeline is called for.
  double max_patch_share = 1;
  //! With targets: relax by area / target² (RemeshOptions::area_weighted_relaxation).
  bool area_weighted_relaxation = false;
};

//! What a local remeshing did.
struct LocalRemeshResult {
  Mesh mesh;               //!< the surface with the patch remeshed (no deleted elements)
  std::vector<int> vertex_map; //!< vertex of the input → of `mesh`; -1 for those remeshed away
  long patch_faces = 0;    //!< faces cut out (the chosen ones, their rings, manifold closure)
  long new_faces = 0;      //!< faces put in their place
  int patches = 0;         //!< connected pieces of the patch
  //! The patch held more than LocalRemeshOptions::max_patch_share of the faces: nothing was
  //! remeshed, `mesh` and `vertex_map` are empty (`patch_faces` says how large it would have been).
  bool declined = false;
  RemeshStatistics statistics;
};

//! Remesh the faces `faces` of `mesh` (no deleted elements) and `options.rings` rings around them,
//! to `targets` (one length per vertex of `mesh`, read at the nearest patch vertex as in
//! nearest_vertex_sizing; empty: the uniform ℓ). The patch's boundary, and everything outside it,
//! is left exactly as it is. Throws InvalidParameter for options out of range, a face index out of
//! range or a wrong target count; InvalidMesh when the patch cannot be cut out or put back.
LocalRemeshResult remesh_locally(const Mesh& mesh, const std::vector<int>& faces, const std::vector<double>& targets,
                                 const LocalRemeshOptions& options);

} // namespace sdflow
