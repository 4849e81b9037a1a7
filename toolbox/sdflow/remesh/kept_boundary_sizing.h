#pragma once
//! \file kept_boundary_sizing.h
//! \brief Targets for a remeshing that keeps the boundary (BoundaryMode::keep, remesh.h): no finer
//! beside a boundary edge than the edge itself.
//!
//! A kept boundary edge of length L is never split, and the triangle on it is well shaped only with
//! its apex about L away. Asked for much shorter edges beside it (a curvature-adapted sizing near a
//! curved contact line, radius_targets), the remeshing packs rows of vertices against the edge: on a
//! 2 × 2 × 0.5 cuboid island at ℓ = 0.2, whose footprint's corners of radius 0.3 ask for 0.075 beside
//! contact-line edges of 0.2, the row next to the rim came to lie 10⁻⁴ ℓ above it, its triangles
//! folded over the rim edges, and stage 1 was refused at every look (remeshing-crossed). So each
//! target is raised to the floor L_b − |x_v − x_b| of the boundary vertex b nearest to v, L_b the
//! mean length of b's two boundary edges: L at the boundary, nothing one edge length away.

#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

//! Raise `targets` (one per vertex of `mesh`, by index; no deleted vertices) to the floor above at
//! every vertex. A closed mesh keeps its targets.
//! Throws InvalidParameter when the sizes differ.
void floor_targets_beside_kept_boundary(const Mesh& mesh, std::vector<double>& targets);

} // namespace sdflow
