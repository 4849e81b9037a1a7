#pragma once
//! \file fixed_rim.h
//! \brief Stages 2–5 of the re-triangulation (pipeline.h) on a surface whose boundary is fixed
//! (flow/boundary_condition.h): a band of faces along the boundary loops is kept bit for bit, and
//! everything inside it is rebuilt and zipped to it as a local surgery puts its patch back
//! (local_surgery.h, rebuild_inside_cut). The rebuild from points would otherwise re-triangulate
//! the rim (new vertices on it, the loop moved) and could return the open surface turned over;
//! kept, the rim's vertices, its loops and the surface's orientation come out as they went in.

#include "sdflow/mesh.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/spatial/intersect.h"

#include <vector>

namespace sdflow {

//! Vertex rings of the band kept along a fixed boundary: the local surgery borrows two rings of
//! the kept surface beyond its cut as context for the rebuild, and these stay off the rim.
constexpr int kFixedRimBandRings = 4;

//! By face index: the faces with a vertex fewer than `rings` vertex rings from a boundary vertex
//! (ring 0: the boundary loops' own vertices). None on a closed surface.
std::vector<char> rim_band(const Mesh& mesh, int rings);

//! Stages 2–5 on `mesh` (stage 1's output, no deleted elements), whose self-intersecting face pairs
//! are `crossings`, keeping the band rim_band(mesh, kFixedRimBandRings) and rebuilding the rest
//! (stage 1 is not done again inside it; the seam is remeshed). ℓ is `edge_length`, holes shorter
//! than `hole_bound` are filled. Throws InvalidMesh when a crossing face lies in the band (the rim
//! cannot be kept through the surgery), when the band cannot be kept as a manifold strip, or when
//! no rebuild can be put back (the rebuilt part remeshed, then as rebuilt).
RetriangulationResult rebuild_keeping_rim(const Mesh& mesh, const std::vector<FacePair>& crossings,
                                          const RetriangulationOptions& options, double edge_length,
                                          double hole_bound);

} // namespace sdflow
