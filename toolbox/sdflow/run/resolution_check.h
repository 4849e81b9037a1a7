#pragma once
//! \file resolution_check.h
//! \brief Whether a run's re-triangulation can resolve its input: every part (a tail, a wire, a
//! sheet) at least as thick, and every gap between bodies at least as wide, as the finest edge the
//! pipeline's sizing makes (min_edge_fraction · ℓ curvature-adapted, ℓ uniform; retri/pipeline.h). A thinner
//! part would be collapsed by the first remeshing rather than evolved by the flow.

#include "sdflow/mesh.h"
#include "sdflow/retri/pipeline.h"
#include "sdflow/user_terms.h"

#include <Eigen/Core>

#include <optional>
#include <string>

namespace sdflow {

//! The thinnest part of a surface that a re-triangulation cannot resolve.
struct ThinPart {
  Eigen::Vector3d where = Eigen::Vector3d::Zero(); //!< the vertex where it is thinnest
  double size = 0;       //!< its thickness (or the gap's width), spatial/local_thickness.h
  bool gap = false;      //!< a gap between two components, not a part's thickness
  long vertices = 0;     //!< vertices where the surface is thinner than the finest edge
  double finest_edge = 0; //!< the finest edge of the run's sizing (min_edge_fraction · ℓ, or ℓ)
  //! The largest ℓ (two significant digits, rounded down) whose finest edge is no longer than `size`,
  //! checked again at that ℓ (up to four times finer, where the finer sampling finds a thinner spot).
  double resolving_edge_length = 0;
};

//! The thinnest part of `mesh` thinner than the finest edge of the pipeline's sizing (ℓ > 0):
//! `pipeline.min_edge_fraction · pipeline.edge_length`, or ℓ itself with a uniform ℓ
//! (edges_per_radius = 0), if any, measured at the vertices, after splitting edges longer than 2ℓ down to ℓ
//! (refine_exactly: the same surface) so that what lies between far-apart vertices is measured
//! too. The vertices of intersecting faces and their neighbours are left out: two
//! sheets that cross are the flow's first surgery, not a thin part. Throws InvalidParameter for
//! ℓ ≤ 0, InvalidMesh for a surface without triangles.
std::optional<ThinPart> thinnest_unresolved_part(const Mesh& mesh, const RetriangulationOptions& pipeline);

//! One sentence for a user: where the part is, how thin, and the edge length that resolves it, in
//! `terms` (`--edge-length 0.041` by default).
std::string describe_thin_part(const ThinPart& part, double edge_length, const UserTerms& terms = {});

} // namespace sdflow
