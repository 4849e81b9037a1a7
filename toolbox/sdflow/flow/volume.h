#pragma once
//! \file volume.h
//! \brief Optional exact volume conservation: after a step, each component is offset along its
//! vertex normals (eq. 8) by one uniform distance that restores its material volume
//! (geometry/material_volume.h: the enclosed volume of a closed component, the volume closed by
//! flat caps over the boundary loops of an open one). Boundary vertices move only as the boundary
//! condition lets them (FlowBoundary::rim_restoration_direction); the convenience forms hold them.

#include "sdflow/flow/flow_boundary.h"
#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

struct VolumeRestoration {
  VertexVectors positions;        //!< the corrected positions (#V by 3)
  std::vector<double> offsets;    //!< the normal offset of each component
  double max_relative_error = 0;  //!< largest |V - V_target| / |V_target| left, over the components
  //! restore_volumes_from: the material volumes of the components of `before` that no component
  //! of `after` took over (debris dropped whole): volume nobody is given back.
  std::vector<double> dropped_volumes;
};

//! Offset each component's non-boundary vertices (boundary vertices held) so that its material volume equals
//! `target_volumes[c]` (components in the order of face_component_ids). The volume is a cubic in
//! the offset δ; Newton's method from δ = 0 reaches round-off in a few iterations.
//! Throws InvalidParameter if the target count differs from the component count, SolverFailure if
//! the volume cannot be restored (a component with zero volume gradient).
VolumeRestoration restore_volumes(const Mesh& mesh, const std::vector<double>& target_volumes);

//! A mesh's triangles (face_indices) and components (face_component_ids and whether each is closed),
//! as a flow keeps them while its connectivity holds.
struct MeshComponents {
  const FaceIndices& triangles;
  const std::vector<int>& face_component;
  const std::vector<bool>& closed;
};

//! The same with the mesh's triangles and components given, so that a step does not find them
//! again, and boundary vertices offset along the directions `boundary` gives them. Throws
//! InvalidParameter also when the components do not match the mesh's face count.
VolumeRestoration restore_volumes(const Mesh& mesh, const std::vector<double>& target_volumes,
                                  const MeshComponents& components, const FlowBoundary& boundary);

//! Offset the components of `after`, a re-triangulation of `before`, so that volume lost or gained
//! by the re-triangulation is given back. Each component of `after` belongs to the components of
//! `before` its vertices lie nearest to (as many as 10% of its vertices, or of theirs: a bubble
//! that opened through a large sheet belongs to the sheet's new surface); components so linked form
//! groups (one body that pinched off into two, two bodies that fused), and each group gets
//! back Σ V_before − Σ V_after (material volumes), shared among its new components in proportion
//! to their areas: debris dropped inside a group is given back to it. A group with an open
//! component whose material volume changed sign (a rebuild from points that returned the open
//! surface turned over) is left alone. Components of `before` with no component of `after`
//! (debris dropped whole) are listed in `dropped_volumes`. Throws SolverFailure as
//! restore_volumes does.
VolumeRestoration restore_volumes_from(const Mesh& before, const Mesh& after);

//! The same for `after`, a remeshing of `before` that kept its components and the vertices
//! `vertex_map` takes into it (vertex of `before` → of `after`, -1 for one remeshed away, as a
//! local remeshing reports them): each component of `after` gets back the volume of the component
//! of `before` its kept vertices belong to, without the nearest-point search of
//! restore_volumes_from, to which it falls back when the component counts differ or a component
//! kept no vertex. Throws SolverFailure as restore_volumes does.
VolumeRestoration restore_volumes_kept(const Mesh& before, const Mesh& after, const std::vector<int>& vertex_map);

} // namespace sdflow
