#pragma once
//! \file intersection_guard.h
//! \brief A flow without re-triangulation cannot pass a topology change: a neck pinching off, a
//! hole sealing or bodies touching leave the surface crossing itself, and the steps after that
//! evolve a surface that bounds no body. The guard looks for self-intersections after every step
//! (a SelfIntersectionTracker refitted, cheap beside the step's solve; spatial/intersect.h) and
//! stops the flow there, naming the option that would carry it through.

#include "sdflow/mesh.h"
#include "sdflow/spatial/intersect.h"

namespace sdflow {

class SelfIntersectionGuard {
public:
  //! Watch `mesh`, whose connectivity stays that of every later check.
  explicit SelfIntersectionGuard(const Mesh& mesh);

  //! Throws SolverFailure when `mesh` (same connectivity, moved by step `step` to time `time`)
  //! intersects itself; the message counts the pairs, names the first and says how to turn
  //! re-triangulation on (`--retriangulate`, `retriangulation.enabled`, MeshLab's Re-triangulate).
  void check(const Mesh& mesh, long step, double time);

private:
  SelfIntersectionTracker tracker_;
};

} // namespace sdflow
