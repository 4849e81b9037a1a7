#pragma once
//! \file substrate_topology_hook.h
//! \brief The flow's re-triangulation hook with the substrate's own topology changes in front of it
//! (substrate_topology.h: the film reaching the substrate, contact lines meeting). The hook keeps
//! contact lines bit for bit and refuses topology changes where the surface does not cross itself;
//! these changes happen where it does not, so they are made first, by the boundary condition's
//! part (SubstrateBoundary::rim_topology_hook), and logged as `touchdown` or `contact` events with
//! the size that triggered them. The material volume of each body is given back as after a
//! re-triangulation (volume.h, restore_volumes_from: the pieces of a broken island share theirs).

#include "sdflow/flow/retriangulation.h"

namespace sdflow {

//! `inner` with the substrate z = `plane_z`'s topology changes looked for first whenever the
//! schedule looks at the surface: δ = min_edge_fraction · ℓ of `schedule.pipeline` (the finest edge
//! the re-triangulation makes; the flow's own pinch-offs happen at widths below it), the cut's reach
//! from ℓ, debris below min_component_faces. When one is made the report carries it (and `split` or
//! `merged` when the component count changed), and `inner` is then called once, forced, on the cut
//! surface: its re-triangulation resamples the new contact lines and remeshes the ragged patch
//! beside them (without it a 8:1 ridge stopped with exit 3 just after breaking); otherwise
//! `inner`'s report is returned as it is.
RetriangulationHook substrate_topology_hook(RetriangulationHook inner, double plane_z,
                                            const RetriangulationSchedule& schedule);

} // namespace sdflow
