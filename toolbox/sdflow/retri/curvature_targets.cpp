#include "sdflow/retri/curvature_targets.h"

#include "sdflow/geometry/weighted_curvature.h"
#include "sdflow/remesh/remesh.h"

namespace sdflow {

std::vector<double> curvature_targets(const Mesh& mesh, const RetriangulationOptions& options, double ell)
{
  const RadiusSizingOptions sizing{.edges_per_radius = options.edges_per_radius,
                                   .min_length = options.min_edge_fraction * ell,
                                   .max_length = ell,
                                   .max_growth = options.graded_remeshing ? kCurvatureTargetGrowth : 0};
  if (!options.anisotropy)
    return radius_targets(mesh, sizing);
  return radius_targets(mesh, largest_weighted_curvature(mesh, *options.anisotropy), sizing);
}

} // namespace sdflow
