#pragma once
//! \file parameters.h
//! \brief The parameters of a run, as read from a scenario file and written, fully resolved, to the
//! run directory's `run.toml` (which `--resume` reads back).
//!
//! Scenario keys (all optional; a CLI flag of the same name overrides them):
//! ```toml
//! preset = "paper"            # the paper's scheme exactly (apply_preset); other keys override it
//! input = "ellipsoid.off"      # relative paths are relative to the scenario file
//! out = "runs/ellipsoid"
//! steps = 200                  # stop after this many steps (0: no limit)
//! t_end = 10.0                 # stop at this time (absent: no limit)
//! stop_at_topology_change = false # also stop after the first pinch-off, seal or fusion
//! time_step = "adaptive"       # "constant" (needs tau), "schedule" (needs schedule) or "adaptive"
//! tau = 0.01                   # implies time_step = "constant" when time_step is absent
//! schedule = "tables.csv"      # or inline: [[1, 50, 0.01], [51, 100, 0.02]]; implies "schedule"
//! schedule_retries = 0         # halvings of the table's τ allowed for an unstable step
//! beta = 0.5
//! curvature = "cotangent"     # H = ½ N·ΔX; "normal_integral" (eq. 9) or "normal_integral_angle_sum" (Σα, not 2π)
//! mass = "voronoi"             # vertex areas of Δ = M⁻¹L: eq. (10)'s, or "volume_gradient" (scheme.h)
//! extrapolate = false          # local Richardson extrapolation: second order in τ, 3 solves a step
//! solver = "cholmod"           # or "qr"
//! factorisation = "reuse"      # or "every_step"
//! snapshot_every = 10
//! checkpoint_every = 10
//! conserve_volume = false
//! fixed_boundary = false
//! [adaptive]                   # see time_step.h for the rule
//! initial_tau = 0.0            # 0: automatic
//! max_displacement = 0.05
//! growth = 1.25
//! shrink = 0.5
//! safety = 0.8
//! max_volume_change = 1e-3
//! min_tau = 1e-14
//! max_tau = 1e300
//! max_rejections = 25
//! tolerance = 0.0              # bound on the extrapolated step's local error estimate (0: off)
//! [retriangulation]            # see RetriangulationSchedule (retriangulation.h) and retri/pipeline.h
//! enabled = false
//! every = 1
//! min_angle = 15.0             # degrees
//! edge_ratio = 2.0
//! degraded_fraction = 0.0
//! always = false
//! edge_length = 0.0            # ℓ; 0: the initial surface's mean edge length
//! remesh_iterations = 3
//! edges_per_radius = 4.0       # curvature-adapted ℓ (0: uniform ℓ, the paper's)
//! min_edge_fraction = 0.25     # floor of the adapted ℓ, as a fraction of ℓ
//! restore_volume = true        # give back the volume a re-triangulation took or added
//! curved_projection = true     # remesh onto the smooth surface, not its flat triangles
//! neighbours = 18              # k of the jet normals
//! fill_holes = true
//! max_hole_length = 0.0        # 0: automatic
//! min_component_faces = 16
//! min_component_thickness = 0.01
//! [reference_sphere]           # for the d1/d2 columns
//! centre = [0.0, 0.0, 0.0]
//! radius = 1.0
//! ```

#include "sdflow/flow/retriangulation.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/solver.h"
#include "sdflow/flow/time_step.h"

#include <Eigen/Core>

#include <filesystem>
#include <limits>

namespace sdflow {

struct RunParameters {
  std::filesystem::path input;       //!< the initial mesh
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
  long snapshot_every = 10;          //!< 0: snapshots of the first and last surface only
  long checkpoint_every = 10;        //!< ≥ 1
  Eigen::Vector3d reference_centre = Eigen::Vector3d::Zero();
  double reference_radius = 1.0;
  RetriangulationSchedule retriangulation;
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
//! restoration after re-triangulation, flat projection in remeshing); "default" sets those options
//! back to sdflow's defaults.
//! Other parameters (time steps, β, the re-triangulation's ℓ and triggers) are left alone.
//! Throws InvalidParameter, listing the names, on another name.
void apply_preset(const std::string& name, RunParameters& parameters);

//! Read a scenario or run.toml into `parameters`, overwriting only the keys present (a `preset`
//! first, then the other keys). Relative
//! paths are resolved against the file's folder. Throws IoError (file, line) on a syntax error,
//! InvalidParameter on an unknown key or a value of the wrong type or range.
void read_run_parameters(const std::filesystem::path& file, RunParameters& parameters);

//! Check ranges and consistency of what the flow uses (τ for the chosen mode, β, the
//! re-triangulation schedule...); throws InvalidParameter.
void validate_flow_parameters(const RunParameters& parameters);

//! validate_flow_parameters, and a stop condition (a number of steps or an end time) for a run.
void validate_run_parameters(const RunParameters& parameters);

//! The fully resolved parameters as TOML (the schedule inline, absolute paths).
std::string run_parameters_toml(const RunParameters& parameters);

} // namespace sdflow
