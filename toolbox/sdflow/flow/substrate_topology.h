#pragma once
//! \file substrate_topology.h
//! \brief Topology changes of a film or island on the substrate z = z₀ (docs/method.md, "Substrate:
//! topology changes"), the ones its own re-triangulations cannot make because they keep contact
//! lines bit for bit:
//! - **touchdown**: the free surface comes lower than δ above the plane away from its contact lines
//!   (farther than ℓ from them in the plane: a film meeting the plane at θ above 14° is higher
//!   than δ = ℓ/4 there). The low part is cut out (the faces of every
//!   vertex lower than δ connected to the lowest ones), and the rim it leaves is put on the plane: a
//!   new contact line. A dimple in a film opens a hole; a neck flattened across an island breaks it.
//! - **contact lines meeting**: two stretches of contact line (of two loops, or of one loop far
//!   apart along it) come closer than δ in the plane. Across the material between them (an island's
//!   footprint pinching) the surface within ½ ℓ of the gap is cut out as above and the island
//!   breaks; across the bare substrate (two islands, or the two sides of a closing hole, meeting) the
//!   two stretches within ℓ of the gap are zipped by a strip of triangles in the plane by the
//!   shortest-diagonal rule (Christiansen & Sederberg 1978), which leaves the volume as it is.
//! The cut keeps the surface an oriented manifold: a vertex left with two fans of faces keeps its
//! larger one, faces lying flat on the plane after the rim is lowered are dropped, and pieces
//! smaller than `min_component_faces` faces are dropped as debris. δ is the run's finest edge
//! (min_edge_fraction · ℓ), the width below which the flow's own pinch-offs happen; the volume is
//! given back by the caller (flow/substrate_topology_hook.h).

#include "sdflow/mesh.h"

#include <limits>
#include <string>

namespace sdflow {

struct SubstrateTopologyOptions {
  double z = 0;          //!< the substrate's plane z = z₀
  double threshold = 0;  //!< δ (> 0): the height or gap below which the topology changes
  double edge_length = 0; //!< ℓ (> 0): the reach of the cut and of the zip
  int min_component_faces = 16; //!< pieces the cut leaves with fewer faces are debris
};

enum class SubstrateChange {
  none,
  touchdown, //!< the film reached the substrate: cut by the plane
  contact,   //!< two contact lines met: cut across the material, or zipped across the bare plane
};

struct SubstrateTopologyResult {
  SubstrateChange change = SubstrateChange::none;
  //! `contact`: the gap between the contact lines was bridged by material (the island's footprint
  //! pinched, so the surface was cut), not bare substrate (zipped).
  bool across_material = false;
  //! What triggered it: the lowest height above the plane of the film away from its contact lines
  //! (touchdown), or the gap between the two contact lines (contact). NaN with no change.
  double size = std::numeric_limits<double>::quiet_NaN();
  long faces_removed = 0, faces_added = 0, debris_faces = 0;
  Mesh mesh; //!< the changed surface (with a change)
  std::string detail; //!< one phrase for events.log
};

//! Look for one substrate topology change on `mesh` (an open surface whose boundary loops lie on
//! the plane) and make it: touchdown first, then contact lines meeting (the closest pair). Returns
//! `change == none` and no mesh when neither is found or the cut would leave no face. Throws
//! InvalidParameter when δ or ℓ is not > 0.
SubstrateTopologyResult change_substrate_topology(const Mesh& mesh, const SubstrateTopologyOptions& options);

} // namespace sdflow
