#pragma once
//! \file crease_edges.h
//! \brief Creases: edges where a surface turns sharply within one edge while the triangles on
//! either side are flat, as at a CAD part's edges or where particles were joined. The remesher
//! keeps them (remesh.h, RemeshOptions::crease_angle_deg): a remeshing that smoothed them across
//! would round a crease the flow has not rounded, and the curvature the rounding leaves would call
//! for finer edges at every later remeshing.

#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

//! The interior edges of `mesh` (no deleted elements) whose dihedral angle (between the normals
//! of their two triangles) exceeds `angle_deg` while the surface beside them is flat: on each side,
//! the triangle's other edges that run along the edge (within 75° at their common corner) and the
//! edges at its third corner parallel to it (within 30°) turn by less than half of it. A curvature
//! resolved over a few edges is not a crease: around a thin neck, edges a row apart turn alike.
//! (A box of two triangles a face is a square tube capped: no local test finds its edges.) Such
//! edges count only in lines of at least 5 (joined end to end, or where lines meet): one or two
//! alone are a scan's noise or a coarse tip, which the flow smooths at once.
//! Returned as edge indices, ascending. Throws InvalidParameter unless 0 < angle_deg < 180.
std::vector<int> crease_edges(const Mesh& mesh, double angle_deg);

} // namespace sdflow
