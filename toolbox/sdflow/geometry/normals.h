#pragma once
//! \file normals.h
//! \brief Vertex normals by eq. (8) of the paper (Max's weights, sin α / (|e_i||e_{i+1}|)).

#include "sdflow/mesh.h"

#include <array>
#include <span>

namespace sdflow {

//! How normals are averaged at boundary vertices.
enum class BoundaryNormalRule {
  eq8,          //!< eq. (8) over the vertex's existing triangles (docs/design.md §1, the default)
  equal_weights //!< unit triangle normals with equal weights 1/m (the paper's §4.3 variant)
};

struct NormalOptions {
  BoundaryNormalRule boundary = BoundaryNormalRule::eq8;
};

//! Unit vertex normals (#V by 3), N' = Σ (e_i × e_{i+1}) / (|e_i|² |e_{i+1}|²), eq. (8).
//! Outward on closed components oriented as docs/design.md §1 requires.
//! Throws InvalidMesh if a vertex has no triangles or its normal is undefined (degenerate star).
VertexVectors vertex_normals(const Mesh& mesh, const NormalOptions& options = {});

//! The same with the triangles' vertex indices given (those of `mesh` in its face order, e.g.
//! CotangentCache's or face_indices'), which spares the walk around every face. Throws
//! InvalidParameter if a triangle names a vertex the mesh does not have.
VertexVectors vertex_normals(const Mesh& mesh, std::span<const std::array<int, 3>> triangles,
                             const NormalOptions& options = {});
VertexVectors vertex_normals(const Mesh& mesh, const FaceIndices& triangles, const NormalOptions& options = {});

} // namespace sdflow
