#pragma once
//! \file topology_guard.h
//! \brief Whether a re-triangulation's change of topology is one the flow brought: located at the
//! regions where the surface before it crossed itself, and no larger than those regions explain
//! (each one is a neck that pinched or a gap that closed: a component or a handle made or lost,
//! a seal around a contact both at once).

#include "sdflow/mesh.h"
#include "sdflow/retri/components.h"
#include "sdflow/spatial/intersect.h"

#include <string>
#include <vector>

namespace sdflow {

//! How the guard locates and bounds a change; the defaults are the run's.
struct TopologyGuardOptions {
  //! Crossing faces whose centroids lie within this many ℓ of each other (through a chain of
  //! them) form one crossing region: a neck or a contact a few edges across.
  double region_gap = 2;
  //! A component of the result with a vertex within this many ℓ of a crossing face's vertex is
  //! at a crossing (the local surgery's first patch radius: what a rebuild there may reach).
  double reach = 3;
  //! Changes one region may bring, each a component or a handle or a boundary loop made or lost:
  //! a pinch or a merge is one, a ring-shaped contact that seals a void is two (a component for the
  //! void, a handle around it).
  int changes_per_region = 2;
};

//! The guard's finding.
struct TopologyGuardVerdict {
  bool explained = true; //!< the change is the flow's
  int regions = 0;       //!< crossing regions
  //! At the crossings: |Δ components| + |Δ genus| + |Δ boundary loops| of the components there.
  int changes = 0;
  std::string reason; //!< why not, when not explained
};

//! Whether `after`, a re-triangulation of `before`, changed the topology only as the crossings of
//! `before` (its intersecting face pairs, not empty) explain: every component of `after` away from
//! them (farther than TopologyGuardOptions::reach plus one ℓ) came from a component of `before`
//! away from them (farther than `reach`; the one whose vertices lie nearest to its own) with its
//! genus and boundary loops, one for one, and every component of `before` away from them is still
//! there, unless `debris` (the pipeline's stage 6) would have dropped it from `before` already; the
//! components at the crossings change by at most changes_per_region per crossing region.
//! `edge_length` is the run's ℓ. Throws InvalidParameter without crossings or with ℓ ≤ 0.
TopologyGuardVerdict explain_topology_change(const Mesh& before, const Mesh& after,
                                             const std::vector<FacePair>& crossings, double edge_length,
                                             const ComponentOptions& debris, const TopologyGuardOptions& options = {});

} // namespace sdflow
