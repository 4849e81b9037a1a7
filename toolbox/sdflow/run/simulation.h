#pragma once
//! \file simulation.h
//! \brief A run: the flow in memory (surface_diffusion.h) recorded in a run directory:
//! ```
//! DIR/metrics.csv        one row per accepted step (row 0 = the initial surface)
//! DIR/timings.csv        one row per accepted step: its wall time by stage (timings_header)
//! DIR/snapshots/step_NNNNNN.ply, .vtp   surfaces; the .vtp carry per-vertex H, N and w
//! DIR/series.pvd         ParaView time series of the .vtp files
//! DIR/run.toml           the fully resolved parameters
//! DIR/events.log         start, rejections, re-triangulations, resumption, the end or the failure
//! DIR/checkpoint.bin     the state to resume from (checkpoint.h)
//! DIR/run.lock           locked while a process works in DIR (run_lock.h)
//! ```
//! Every file is replaced atomically. metrics.csv and events.log are rewritten at each snapshot and
//! checkpoint, at the end, and at most every two seconds otherwise, so a killed run leaves complete
//! files that may lag the computation; `resume_simulation` truncates them to the checkpoint.

#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/mesh.h"
#include "sdflow/run/parameters.h"

#include <functional>
#include <string>
#include <vector>

namespace sdflow {

//! The columns of metrics.csv, in order; `energy` is ∫ γ dA (SurfaceEnergy::value: the area for the
//! isotropic energy), appended after the columns of earlier versions.
inline constexpr const char* metrics_header =
    "step,time,tau,vertices,faces,components,genus,area,volume,mean_curvature,curvature_deviation_pct,d1,d2,"
    "debris_volume,event,energy";

//! The header of metrics.csv before the `energy` column: a run it heads resumes with the column
//! added (empty in its earlier rows), and `sdflow plot` reads it.
inline constexpr const char* metrics_header_without_energy =
    "step,time,tau,vertices,faces,components,genus,area,volume,mean_curvature,curvature_deviation_pct,d1,d2,"
    "debris_volume,event";

//! One line of metrics.csv (with its newline): the step, time, τ and event, and the flow's metrics.
std::string metrics_row(long step, double time, double tau, const FlowMetrics& metrics, const std::string& event);

//! The columns of timings.csv (seconds of wall time per step): the stages of StepTimes, the
//! run directory's files (`output`), `other`, the rest of the step's total, `cpu`, the CPU
//! seconds of the step itself (files excluded; all threads), and `side_by_side`, the seconds two
//! stages ran at once and both count (StepTimes::side_by_side): the stages and `other` add up to
//! total + side_by_side, and `other` is never negative.
inline constexpr const char* timings_header =
    "step,total,operators,assembly,factorisation,solve,acceptance,retriangulation_check,merge,remesh,"
    "intersections,normals,reconstruction,holes,components,volume_restoration,retriangulation_other,output,other,cpu,"
    "side_by_side";

//! One line of timings.csv (with its newline); `output` is the time spent writing the run's files.
std::string timings_row(long step, const StepTimes& times, double output);

struct SimulationOptions {
  //! Checked where they are made (a front end, before it reads the input; `{.parameters = p}`
  //! checks `p`), so the run checks nothing again.
  CheckedRunParameters parameters;
  RetriangulationHook retriangulate;             //!< optional (else from the parameters' schedule)
  std::function<void(const StepRecord&)> progress; //!< optional, called after every accepted step
  //! Optional, asked before every step: when it answers true the run writes a checkpoint and
  //! returns with `interrupted` set (a signal handler's flag, say; resume continues exactly).
  std::function<bool()> stop_requested;
};

struct SimulationResult {
  Mesh mesh;               //!< the final surface
  long steps = 0;          //!< the index of the last step
  double time = 0;
  long rejected_trials = 0; //!< over this call
  long factorisations = 0;  //!< over this call
  bool interrupted = false; //!< stopped early on `stop_requested`, with a checkpoint of `steps`
  bool restarted = false;   //!< resumed a run that had no checkpoint yet: it started again at step 0
  //! The events of this call besides routine ones (start steps, rejected trials, remeshings):
  //! surgeries, splits, merges, refused re-triangulations and table fallbacks, in order.
  std::vector<StepEvent> events;
};

//! Run the flow from `initial` into `options.parameters->output_dir`, which must not already hold a
//! run (metrics.csv or checkpoint.bin) nor be in use by another process (run_lock.h: the directory
//! is locked while this runs). Throws InvalidParameter on a directory that is a
//! file or holds a run or is locked, InvalidMesh on a mesh the scheme cannot use, SolverFailure
//! when the run becomes unstable (the files written so far stay complete), IoError when an output
//! cannot be written (EnvironmentFailure when the disk is full).
//! The input is taken as it is: the front ends check it first with check_run_input (run_input.h),
//! which refuses what the flow and its re-triangulation cannot take.
SimulationResult run_simulation(const Mesh& initial, const SimulationOptions& options);

//! Continue the run in `options.parameters->output_dir` from its checkpoint, exactly as if it had
//! not stopped (the parameters should be those of its run.toml; the step and time limits may be
//! raised). A run stopped before its first checkpoint (killed in its first moments, or its first
//! checkpoint hit a full disk) starts again at step 0 from its step-0 snapshot, or from its input
//! when even that is missing. Throws IoError if the checkpoint is unreadable, InvalidParameter
//! when another process works in the directory.
SimulationResult resume_simulation(const SimulationOptions& options);

} // namespace sdflow
