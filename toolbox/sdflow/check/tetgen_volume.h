#pragma once
//! \file tetgen_volume.h
//! \brief Independent volume check: tetrahedralise each closed component with TetGen (Si 2015)
//! and compare the summed tetrahedron volumes with the divergence-theorem volume.

#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

//! Volumes of one closed component by both methods.
struct ComponentVolumeCheck {
  int component = 0;          //!< index in face_component_ids() order
  int tetrahedra = 0;         //!< tetrahedra TetGen produced inside the component
  double tetgen_volume = 0;   //!< Σ tetrahedron volumes, negative for a cavity (as divergence_volume)
  double divergence_volume = 0; //!< Σ a·(b×c)/6 over the component's triangles
  double relative_difference() const;
};

//! One entry per closed component (components with boundary enclose no volume and are skipped).
//! The surface is kept exactly as given (TetGen switch Y: no Steiner points on it).
//! Throws InvalidMesh if TetGen rejects a component (self-intersecting or degenerate facets), and
//! before calling TetGen for what would crash it: a flat component (no volume), or one whose extent
//! is more than 10⁶ times its shortest edge.
std::vector<ComponentVolumeCheck> tetgen_volume_check(const Mesh& mesh);

//! The same for the closed components listed in `components` only (ids in face_component_ids()
//! order; others and open ones are skipped), e.g. those that cross no other face.
std::vector<ComponentVolumeCheck> tetgen_volume_check(const Mesh& mesh, const std::vector<int>& components);

} // namespace sdflow
