#pragma once
//! \file open_orientation.h
//! \brief The orientation of a re-triangulation's open components, checked against the surface it
//! re-triangulated. Validation orients closed components by their volume (out of the material),
//! but an open one has no inside to tell: a rebuild from points whose normals were oriented by a
//! spanning tree (reconstruct/point_normals.h) may return it turned over, and its material volume
//! (geometry/material_volume.h) then changes sign. Each open component is compared with the
//! surface it came from, face by face, and turned back over when most of it disagrees.

#include "sdflow/mesh.h"

namespace sdflow {

//! The open components of `mesh` whose faces, weighted by area, mostly face against the normals
//! of `reference` at its vertices nearest to theirs (Σ_f A_f n_f · N_ref(nearest vertex) < 0 over
//! the component), turned back over (each face's corners reversed; vertices and closed components
//! untouched). Returns how many were turned. `reference` must have vertices when `mesh` has open
//! components.
int orient_open_components_like(const Mesh& reference, Mesh& mesh);

} // namespace sdflow
