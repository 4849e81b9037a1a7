#pragma once
//! \file material_volume.h
//! \brief The volume of material a surface bounds, for open surfaces too: each component closed by
//! a flat fan from each of its boundary loops to the loop's centroid (its vertex mean), then the
//! divergence theorem (§2.2.4) over the closed surface. On a closed component it is the enclosed
//! volume; on an open one it does not depend on the origin (a closed surface's volume does not),
//! and with a fixed rim the cap does not move, so the volume changes only as the surface moves.

#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

//! One boundary loop: its vertices in the order of its boundary halfedges (v_i → v_{i+1}), and the
//! component (face_component_ids) whose faces it bounds.
struct BoundaryLoop {
  std::vector<int> vertices;
  int component = 0;
};

//! The boundary loops of `mesh` (in the order of topology.h's boundary_loops), given the component
//! of each face.
std::vector<BoundaryLoop> boundary_loop_vertices(const Mesh& mesh, const std::vector<int>& face_component);

//! Signed volume of the cap closing `loop`: Σ cone_volume(v_i, v_{i+1}, c) over its edges, with c
//! the centroid of its vertices. The cap runs along each boundary edge against its face, so it
//! closes the surface with the surface's orientation.
double cap_volume(const VertexVectors& positions, const std::vector<int>& loop);

//! Material volume of each component (`face_component[f]` in 0..count-1): its cone volumes plus
//! the caps of its `loops`.
std::vector<double> material_volumes(const VertexVectors& positions, const FaceIndices& triangles,
                                     const std::vector<int>& face_component, int count,
                                     const std::vector<BoundaryLoop>& loops);

//! The same, each component in the order of face_component_ids.
std::vector<double> material_volumes(const Mesh& mesh);

//! Material volume of the whole mesh: enclosed_volume plus the caps of every boundary loop, so
//! exactly enclosed_volume on a closed mesh.
double material_volume(const Mesh& mesh);

} // namespace sdflow
