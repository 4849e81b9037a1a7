#pragma once
//! \file zip_loops.h
//! \brief The strip of triangles between two closed polylines that bound a band of surface, by
//! the shortest-diagonal rule for contour stitching (Christiansen & Sederberg 1978): walking both
//! loops, each triangle advances on the loop whose next diagonal is shorter, unless that triangle
//! would face against the surface's normals there, or have zero area, and the other would not (a
//! fold where a loop zigzags).

#include "sdflow/mesh.h"

#include <array>
#include <vector>

namespace sdflow {

//! Triangles (indices into `positions`) filling the band between loop `outer` and loop `inner`,
//! both listed as the boundary halfedges of the surfaces they end (outer: of the surface the
//! band continues, running the same way as inner's for a band between them). The strip uses
//! each outer edge a_i → a_{i+1} as a_{i+1} → a_i and each inner edge b_j → b_{j+1} as it is, so
//! it joins the two surfaces with one orientation. `normals` (#V by 3, any length) are the surfaces'
//! normals at the loops' vertices. Throws InvalidMesh when a loop has fewer than three vertices or
//! the loops run opposite ways.
std::vector<std::array<int, 3>> zip_loops(const VertexVectors& positions, const VertexVectors& normals,
                                          const std::vector<int>& outer, const std::vector<int>& inner);

} // namespace sdflow
