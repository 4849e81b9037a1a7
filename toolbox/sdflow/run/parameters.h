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

#include "sdflow/flow/flow_options.h"
#include "sdflow/flow/scheme_names.h"
#include "sdflow/parameter_range.h"

#include <filesystem>
#include <string>

namespace sdflow {

//! A recorded run's parameters: the flow's options (FlowOptions, which SurfaceDiffusion takes
//! as they are) and what only the run uses, where it reads and writes.
struct RunParameters : FlowOptions {
  std::filesystem::path input;       //!< the initial mesh
  //! Repair the input when validation refuses it for problems repair fixes (io/repair.h).
  bool repair = false;
  std::filesystem::path output_dir;  //!< the run directory
  long snapshot_every = 10;          //!< 0: snapshots of the first and last surface only
  long checkpoint_every = 10;        //!< ≥ 1
};

//! `run` with its flow options replaced by `flow`, the options as a flow resolved them
//! (SurfaceDiffusion::options: ℓ and the refinement fixed), for run.toml.
inline RunParameters with_flow_options(RunParameters run, const FlowOptions& flow)
{
  static_cast<FlowOptions&>(run) = flow;
  return run;
}

//! The allowed values of a run's own numbers, stated here only: validate_run_parameters checks them
//! and the run schema's entries take them (schema_run.cpp).
struct RunRanges {
  ParameterRange snapshot_every{.min = 0};   //!< 0: the first and last surface only
  ParameterRange checkpoint_every{.min = 1};
};
inline constexpr RunRanges run_ranges{};

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

//! A run's own rule, which the flow does not check: a stop condition (a number of steps or an end
//! time); throws InvalidParameter.
void validate_stop_condition(const RunParameters& parameters);

//! RunParameters with a stop condition (validate_stop_condition), their own numbers in run_ranges,
//! and their flow options checked (CheckedFlowOptions): the constructor is that check, made once on
//! each path. A front end makes one before it reads the input, so that a bad parameter is reported
//! before a bad file and before the input checks that read the parameters, and hands it to
//! run_simulation or resume_simulation, which check nothing again.
class CheckedRunParameters {
public:
  //! Throws InvalidParameter naming the key. Implicit, so that `{.parameters = p}` of a
  //! SimulationOptions checks `p` there.
  CheckedRunParameters(const RunParameters& parameters);
  const RunParameters& operator*() const { return parameters_; }
  const RunParameters* operator->() const { return &parameters_; }
  //! The flow's options, checked with the rest.
  const CheckedFlowOptions& flow() const { return flow_; }

private:
  RunParameters parameters_;
  CheckedFlowOptions flow_;
};

//! The check of CheckedRunParameters, for a caller that keeps only the verdict (`sdflow run`'s
//! scenario fuzzer, the samples' test): throws InvalidParameter naming the key.
void validate_run_parameters(const RunParameters& parameters);

//! The fully resolved parameters as TOML, under the canonical keys (the schedule inline, absolute
//! paths, an infinite limit as `inf`), and a table `[written_by]` with the writer's
//! `sdflow_version` and `sdflow_commit` (version.h), which read_run_parameters skips.
std::string run_parameters_toml(const RunParameters& parameters);

} // namespace sdflow
