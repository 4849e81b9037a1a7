#pragma once
//! \file marching_tetrahedra.h
//! \brief First triangulation of a level set: marching tetrahedra on an adaptive octree, and
//! cutting a triangulation along a second level set.

#include "sdflow/mesh.h"
#include "sdflow/shapes/implicit.h"

namespace sdflow {

struct MarchingOptions {
  //! Edge of the cells that meet the surface (> 0). Cells away from the surface are coarser.
  double cell_size = 0;
  //! Halvings of cell_size allowed where the surface is complex: narrow slots between two sheets
  //! facing each other (at contact necks), thin tubes. Marching a slot no wider than a cell
  //! bridges it with triangles the remesher cannot untangle; a uniform grid fine enough there
  //! would be far too fine elsewhere.
  int detail_levels = 1;
  //! A cell is complex when the normals ∇f/|∇f| at two of its corners within a cell diagonal of
  //! the surface differ by more than this angle (degrees): nearly opposite normals mean two sheets.
  double detail_angle_deg = 120;
};

//! Triangles of f = 0 by marching tetrahedra (Doi & Koide 1991) on an octree over the surface's
//! box. Cells whose corners are within a cell diagonal of the surface (first-order distance
//! |f|/|∇f|) are refined to `cell_size`, complex ones further; the octree is 2:1 balanced across
//! faces, edges and corners. Regular cells are split into the six Kuhn tetrahedra; cells next to
//! finer ones are split into pyramids from their centre over their triangulated faces, so the
//! tetrahedra conform and the extracted surface has no cracks. Vertices sit at the linear zero
//! of f on tetrahedron edges (f < 0 inside, NaN outside) and are shared, so the result is a
//! 2-manifold, open only where f = 0 leaves the box, facing toward f > 0. It may contain very
//! short edges and slivers: it is the remesher's input. Throws InvalidParameter for bad options.
Mesh marching_tetrahedra(const ImplicitSurface& surface, const MarchingOptions& options);

//! The part of `mesh` where g ≤ 0: triangles crossing g = 0 are cut at the linear zero of g on
//! their edges (vertices on the cut are new, shared between neighbours); orientation is kept and
//! vertices no longer used are dropped.
Mesh clip_mesh(const Mesh& mesh, const ScalarField& g);

} // namespace sdflow
