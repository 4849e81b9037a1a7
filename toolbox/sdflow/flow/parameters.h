#pragma once
//! \file parameters.h
//! \brief The parameters of a run, as read from a scenario file and written, fully resolved, to the
//! run directory's `run.toml` (which `--resume` reads back).
//!
//! Scenario keys (all optional; a CLI flag overrides each): the table of parameter_schema.h, which
//! `sdflow run --help-scenario` prints and README's table of scenario keys shows. For example:
//! ```toml
//! preset = "paper"             # the paper's scheme exactly (apply_preset); other keys override it
//! input = "ellipsoid.off"      # relative paths are relative to the scenario file
//! out = "runs/ellipsoid"
//! end_time = 10.0              # (older name: t_end)
//! tau = 0.01                   # implies time_step = "constant"
//! [retriangulation]
//! enabled = true
//! edge_length = 0.0            # ℓ; 0: the initial surface's mean edge length
//! ```

#include "sdflow/flow/retriangulation.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/time_step.h"
#include "sdflow/solve/solver.h"

#include <Eigen/Core>

#include <filesystem>
#include <limits>

namespace sdflow {

struct RunParameters {
  std::filesystem::path input;       //!< the initial mesh
  //! Repair the input when validation refuses it for problems repair fixes (io/repair.h).
  bool repair = false;
  std::filesystem::path output_dir;  //!< the run directory
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
  long snapshot_every = 10;          //!< 0: snapshots of the first and last surface only
  long checkpoint_every = 10;        //!< ≥ 1
  Eigen::Vector3d reference_centre = Eigen::Vector3d::Zero();
  double reference_radius = 1.0;
  RetriangulationSchedule retriangulation;
  //! s > 0, the refinement of the adapted sizing and the displacement bound (flow/refinement.h): the
  //! run uses edges per radius × √s and max_displacement ÷ s; 0: automatic, from the initial
  //! surface's typical radius of curvature and ℓ, fixed when the flow starts (written to run.toml).
  double refinement = 0;
};

//! The names of the `curvature` key: "cotangent" (H = ½ N·ΔX, the default), "normal_integral"
//! (eq. 9), "normal_integral_angle_sum" (eq. 9 divided by the angle sum).
std::string curvature_name(const CurvatureOptions& options);

//! The options a `curvature` name stands for; throws InvalidParameter, listing the names, on another.
CurvatureOptions curvature_options(const std::string& name);

//! The names of the `mass` key: "voronoi" (eq. 10, the default) and "volume_gradient".
std::string mass_name(VertexMass mass);

//! The mass a `mass` name stands for; throws InvalidParameter, listing the names, on another.
VertexMass vertex_mass(const std::string& name);

//! The presets of the `preset` key and `--preset`: "paper" is the paper's scheme exactly (eq. 9 H,
//! Voronoi areas, plain steps, no error control, uniform re-triangulation edge length, no volume
//! restoration after re-triangulation, flat projection in remeshing, the whole re-triangulation
//! pipeline instead of local remeshing and surgery, no start steps, no refinement, the paper's
//! boundary rule); "default" sets those options back to sdflow's defaults. Which parameters a
//! preset sets, and to what, is the schema's (`ParameterEntry::paper`); the others (time steps, β,
//! the re-triangulation's ℓ and triggers) are left alone.
//! Throws InvalidParameter, listing the names, on another name.
void apply_preset(const std::string& name, RunParameters& parameters);

//! Read a scenario or run.toml into `parameters`, overwriting only the keys present (a `preset`
//! first, then the other keys, `time_step` last; run.toml's `[written_by]` table is skipped). Older key names are read too (`t_end`). Relative
//! paths are resolved against the file's folder. Throws IoError (file, line) on a syntax error,
//! InvalidParameter (file, line, key) on an unknown key (with the closest known one), a key given
//! twice under two names, or a value of the wrong type or outside its range.
void read_run_parameters(const std::filesystem::path& file, RunParameters& parameters);

//! Check the range of every parameter in use (the schema's, parameter_schema.h, some taken from the
//! option structs they configure: retriangulation_ranges, substrate_ranges) and their consistency (τ for the chosen mode, an error
//! tolerance with extrapolated steps); throws InvalidParameter naming the key.
void validate_flow_parameters(const RunParameters& parameters);

//! A run's own rule, which the flow does not check: a stop condition (a number of steps or an end
//! time); throws InvalidParameter.
void validate_stop_condition(const RunParameters& parameters);

//! validate_stop_condition and validate_flow_parameters: what a front end checks once, before it
//! reads the input.
void validate_run_parameters(const RunParameters& parameters);

//! The fully resolved parameters as TOML, under the canonical keys (the schedule inline, absolute
//! paths, an infinite limit as `inf`), and a table `[written_by]` with the writer's
//! `sdflow_version` and `sdflow_commit` (version.h), which read_run_parameters skips.
std::string run_parameters_toml(const RunParameters& parameters);

} // namespace sdflow
