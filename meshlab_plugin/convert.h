#pragma once
//! \file convert.h
//! \brief The plugin's one conversion between MeshLab's single-precision world and sdflow's double
//! precision: meshes (CMeshO ↔ Surface) and the float parameters of MeshLab's dialogs.

#include "surface.h"

#include <common/ml_mesh_type.h>

namespace sdflow::meshlab {

//! The live (not deleted) vertices and faces of `mesh`, renumbered densely in storage order.
//! Widening float to double is exact, so a surface read from a file gives the same doubles here as
//! when sdflow reads the file itself.
Surface to_surface(const CMeshO& mesh);

//! Replace every vertex and face of `mesh` by `shaded` (rounded to float): positions, triangles,
//! per-vertex normals and per-vertex quality = mean curvature; face normals and the bounding box
//! are recomputed. Other per-vertex data (colour, texture coordinates) does not survive.
//! `mesh` is left untouched if `shaded` is inconsistent (throws std::invalid_argument).
void replace_mesh(CMeshO& mesh, const ShadedSurface& shaded);

//! The double a user meant by a value MeshLab stores as float: the shortest decimal that rounds
//! to `value` (so 0.001f becomes 0.001, not 0.0010000000474974513). Parameters typed into a
//! dialog or an .mlx script then equal those given to `sdflow run` on the command line.
double intended_double(float value);

} // namespace sdflow::meshlab
