#include "sdflow/flow/flow_options.h"

#include "sdflow/errors.h"
#include "sdflow/flow/boundary_condition.h"
#include "sdflow/flow/scheme_names.h"
#include "sdflow/flow/surface_energy_options.h"

#include <fmt/format.h>

namespace sdflow {

void validate_flow_options(const FlowOptions& o)
{
  check_in_range(flow_ranges.steps, static_cast<double>(o.steps), "steps");
  check_in_range(flow_ranges.end_time, o.end_time, "end_time");
  check_in_range(flow_ranges.reference_radius, o.reference_radius, "reference_sphere.radius");
  check_in_range(flow_ranges.refinement, o.refinement, "refinement");
  check_in_range(scheme_ranges.beta, o.scheme.beta, "beta");
  if (o.solver.policy == FactorisationPolicy::reuse)
    check_in_range(solver_ranges.cg_tolerance, o.solver.cg_tolerance, "cg_tolerance");
  if (o.scheme.boundary == BoundaryCondition::substrate) {
    check_in_range(substrate_ranges.z, o.scheme.substrate.z, "substrate.z");
    check_in_range(substrate_ranges.contact_angle, o.scheme.substrate.contact_angle, "substrate.contact_angle");
    check_in_range(substrate_ranges.mobility, o.scheme.substrate.mobility, "substrate.mobility");
  }
  const RetriangulationScheduleRanges& r = retriangulation_schedule_ranges;
  check_in_range(r.every, static_cast<double>(o.retriangulation.every), "retriangulation.every");
  check_in_range(r.min_angle, o.retriangulation.min_angle_deg, "retriangulation.min_angle");
  check_in_range(r.edge_ratio, o.retriangulation.edge_ratio, "retriangulation.edge_ratio");
  check_in_range(r.degraded_fraction, o.retriangulation.degraded_fraction, "retriangulation.degraded_fraction");
  validate_retriangulation_options(o.retriangulation.pipeline);
  validate_time_step_options(o.time_step);
  check_in_range(willmore_range, o.scheme.energy.willmore, "energy.willmore");
  if (o.scheme.energy.willmore > 0 && o.scheme.boundary == BoundaryCondition::substrate)
    throw InvalidParameter(fmt::format("energy.willmore = {}: a Willmore term needs a closed surface, and "
                                       "boundary = \"substrate\" is for films with contact lines",
                                       o.scheme.energy.willmore));
  if (o.scheme.energy.kind != SurfaceEnergyKind::isotropic) {
    make_anisotropy(o.scheme.energy); // energy.g's count and values for the kind, or a formula (convex without ε)
    if (o.scheme.curvature.method != CurvatureMethod::cotangent)
      throw InvalidParameter(fmt::format("curvature = \"{}\" chooses how the isotropic energy's H is computed; "
                                         "energy.kind = \"{}\" has a weighted curvature of its own: leave "
                                         "curvature at \"cotangent\"",
                                         curvature_name(o.scheme.curvature), surface_energy_name(o.scheme.energy.kind)));
  }
  if (o.time_step.adaptive.tolerance > 0 && !o.scheme.extrapolate)
    throw InvalidParameter(fmt::format("an error tolerance ({}) needs extrapolated steps (extrapolate = true): "
                                       "they provide the error estimate",
                                       o.time_step.adaptive.tolerance));
}

} // namespace sdflow
