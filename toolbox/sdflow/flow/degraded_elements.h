#pragma once
//! \file degraded_elements.h
//! \brief The elements a run's re-triangulation hook (retriangulation.h) calls degraded: edges
//! outside [ℓ/r, r·ℓ] of their local target ℓ (the pipeline's curvature-adapted sizing,
//! retri/curvature_targets.h, or the uniform ℓ), and triangles with an angle below a minimum.

#include "sdflow/flow/retriangulation.h"
#include "sdflow/mesh.h"

#include <vector>

namespace sdflow {

//! Degraded elements of a surface, and where they are.
struct DegradedElements {
  long edges = 0;            //!< edges outside [ℓ/r, r·ℓ]
  long triangles = 0;        //!< triangles with an angle below the minimum
  std::vector<int> faces;    //!< the faces of both (an edge's one or two faces), ascending
  //! The faces of elements halfway to degraded (edges outside [ℓ/√r, √r·ℓ], angles below twice
  //! the minimum) and the degraded ones, ascending: a local remeshing takes them along, so that
  //! they do not call for the next one a step later (hysteresis, as the whole pipeline has).
  std::vector<int> worn_faces;
  std::vector<double> targets; //!< the target ℓ at each vertex the edges were measured against
  long total() const { return edges + triangles; }
};

//! The degraded elements of `mesh` (no deleted elements) under the schedule's criteria
//! (min_angle_deg, edge_ratio, and the pipeline's ℓ, edges_per_radius and min_edge_fraction).
//! `schedule.pipeline.edge_length` must be resolved (> 0).
DegradedElements degraded_elements(const Mesh& mesh, const RetriangulationSchedule& schedule);

} // namespace sdflow
