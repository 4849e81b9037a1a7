#pragma once
//! \file flow_options.h
//! \brief What the flow in memory (surface_diffusion.h) is told: when it stops, its time steps, its
//! scheme and solver, its re-triangulation, and the reference sphere of its metrics. A recorded run
//! adds where it reads and writes (run/parameters.h, RunParameters); the run schema
//! (run/parameter_schema.h) names every option for scenarios, flags and the MeshLab dialog.

#include "sdflow/flow/retriangulation.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/time_step.h"
#include "sdflow/parameter_range.h"
#include "sdflow/solve/solver.h"

#include <Eigen/Core>

#include <limits>
#include <utility>

namespace sdflow {

struct FlowOptions {
  long steps = 0;                    //!< step limit, 0 for none
  double end_time = std::numeric_limits<double>::infinity(); //!< time limit
  //! Also stop after the first step whose re-triangulation changed the component count or the
  //! genus (a pinch-off, a hole sealing, bodies fusing): for measuring event times.
  bool stop_at_topology_change = false;
  TimeStepOptions time_step;
  SchemeOptions scheme;
  SolverOptions solver;
  bool conserve_volume = false;
  //! Take the next step's first trial on a second core while the re-triangulation hook looks at the
  //! surface, dropping it when the look re-triangulates (surface_diffusion.h): the same results,
  //! sooner. Off: one after the other.
  bool look_ahead = true;
  Eigen::Vector3d reference_centre = Eigen::Vector3d::Zero(); //!< of the sphere FlowMetrics' d1, d2 measure against
  double reference_radius = 1.0;
  RetriangulationSchedule retriangulation;
  //! s > 0, the refinement of the adapted sizing and the displacement bound (refinement.h): the
  //! flow uses edges per radius × √s and max_displacement ÷ s; 0: automatic, from the initial
  //! surface's typical radius of curvature and ℓ, fixed when the flow starts.
  double refinement = 0;
};

//! The allowed values of FlowOptions' own numbers, stated here only: validate_flow_options checks
//! them and the run schema's entries take them (run/schema_run.cpp, run/schema_scheme.cpp).
struct FlowRanges {
  ParameterRange steps{.min = 0};                                                 //!< 0: no limit
  ParameterRange end_time{.min = 0, .min_open = true, .infinite_allowed = true};  //!< ∞: no limit
  ParameterRange reference_radius{.min = 0, .min_open = true};
  ParameterRange refinement{.min = 0, .max = 1e6};                                //!< 0: automatic
};
inline constexpr FlowRanges flow_ranges{};

//! Check every option in use against its range, each stated beside its options (flow_ranges,
//! time_step_ranges, scheme_ranges, substrate_ranges, solver_ranges,
//! retriangulation_schedule_ranges, retriangulation_ranges), and their consistency (the time
//! steps' among themselves, validate_time_step_options; an error tolerance needs extrapolated
//! steps; an anisotropic energy's numbers or formula, and the cotangent curvature beside it).
//! Throws InvalidParameter naming the scenario key. A stop condition is not needed: the flow can
//! step for ever.
void validate_flow_options(const FlowOptions& options);

//! FlowOptions that validate_flow_options accepted: its constructor is that check, so a value of
//! this type has passed it, and the flow, given one, checks nothing again. A front end that
//! checks a run's parameters before it reads the input hands the checked value on
//! (CheckedRunParameters::flow); any other caller passes FlowOptions, checked on the way in.
class CheckedFlowOptions {
public:
  //! Throws InvalidParameter as validate_flow_options does. Implicit, so that
  //! `SurfaceDiffusion(mesh, options)` checks `options` there, once.
  CheckedFlowOptions(FlowOptions options) : options_(std::move(options)) { validate_flow_options(options_); }
  const FlowOptions& operator*() const { return options_; }
  const FlowOptions* operator->() const { return &options_; }

private:
  FlowOptions options_;
};

} // namespace sdflow
