#pragma once
//! \file surface_diffusion.h
//! \brief The flow in memory: a surface stepped by the semi-implicit scheme (scheme.h, eq. 6 of the
//! paper) under the time-step rule (time_step.h) and re-triangulated between steps
//! (retriangulation.h). It writes no files: simulation.h records a run of it in a run directory,
//! and the MeshLab plugin and tests step it directly.
//!
//! ```cpp
//! FlowOptions o;                            // sdflow's defaults: adaptive τ, cotangent H,
//! o.end_time = 0.5;                         // re-triangulation on
//! SurfaceDiffusion flow(mesh, o);
//! while (!flow.finished())
//!   flow.step();
//! const Mesh& result = flow.mesh();
//! ```

#include "sdflow/flow/flow_hook.h"
#include "sdflow/flow/flow_options.h"
#include "sdflow/flow/flow_state.h"
#include "sdflow/flow/look_ahead.h"
#include "sdflow/flow/retriangulation.h"
#include "sdflow/flow/scheme.h"
#include "sdflow/flow/step_record.h"
#include "sdflow/flow/time_step.h"
#include "sdflow/flow/trial_solvers.h"
#include "sdflow/geometry/cotangent_cache.h"
#include "sdflow/geometry/material_volume.h"
#include "sdflow/mesh.h"

#include <array>
#include <atomic>
#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace sdflow {

class SurfaceDiffusion {
public:
  //! Start from `initial` (a valid mesh, closed components oriented outward). Without a hook, the
  //! flow makes one from `options.retriangulation` when it is enabled (the default), fixing its ℓ
  //! (0: the initial mean edge length) in options(); when it is off, it stops at the first step
  //! that makes the surface intersect itself (intersection_guard.h). The options are checked once,
  //! when a CheckedFlowOptions is made of them (validate_flow_options: InvalidParameter on options
  //! out of range; a stop condition is not needed), here when FlowOptions are passed, before when
  //! checked ones are. Throws InvalidMesh on a mesh the scheme cannot use.
  SurfaceDiffusion(const Mesh& initial, const CheckedFlowOptions& options, RetriangulationHook retriangulate = {});

  //! Continue from `state` exactly as the flow that saved it would have (same options, as
  //! options() of that flow, and the same hook).
  SurfaceDiffusion(const FlowState& state, const CheckedFlowOptions& options, RetriangulationHook retriangulate = {});

  //! Take one accepted step: trials until the time-step rule accepts one (a step that no τ makes
  //! acceptable is retried once after a forced re-triangulation), then the re-triangulation hook,
  //! beside the next step's first trial when the options look ahead (docs/design.md §10).
  //! Never past `end_time`. Throws SolverFailure when the flow cannot go on stably, or, without
  //! re-triangulation, when the step makes the surface intersect itself (the surface is that of
  //! the last accepted step).
  StepRecord step();

  //! The step limit or end time is reached, or (with stop_at_topology_change) the topology changed.
  bool finished() const;

  const Mesh& mesh() const { return surface_.mesh; }
  long steps() const { return step_; }      //!< index of the last accepted step (0 at the start)
  double time() const { return time_; }
  //! N, H, L, M of the current surface (what the next step uses).
  const FlowOperators& operators() const { return op_; }
  //! w of the last step (the normal velocity is −w), on the current vertices; 0 after a
  //! re-triangulation and at the start.
  const Eigen::VectorXd& velocity() const { return w_.last; }
  //! The options as resolved (the re-triangulation's ℓ and the refinement fixed).
  const FlowOptions& options() const { return p_; }
  FlowMetrics metrics() const;
  FlowState state() const;
  //! Trial steps rejected, and numeric factorisations made, since construction (up to the last
  //! accepted step).
  long rejected_trials() const { return counts().rejected_trials; }
  long factorisations() const { return counts().factorisations; }

  //! The notes made since the last call (also sent to the log as they are made), in order; kept
  //! when step() throws, so the reason can follow them.
  std::vector<FlowNote> take_notes();

private:
  struct Topology {
    std::vector<int> face_component;
    int count = 0;
    std::vector<bool> closed;
    std::vector<BoundaryLoop> loops; //!< the boundary loops, whose caps close material_volumes
    int genus = 0;
  };

  //! Where a step's trials report while they run: a first trial holds its notes back for the step
  //! that takes it, and the trials taken beside the look at the surface stop once `cancel` is set
  //! (LookAhead::look_beside_trial).
  struct TrialContext {
    std::vector<FlowNote>* held_notes = nullptr; //!< null: the notes are published at once
    const std::atomic<bool>* cancel = nullptr;   //!< null: the trials run to their end
  };

  //! The surface and what its connectivity gives: its faces as rows, its components and the
  //! operators' cotangent cache, renewed together when the connectivity changes.
  struct Surface {
    Mesh mesh;
    FaceIndices triangles;
    Topology topology;
    std::optional<CotangentCache> cache;
  };

  //! w of the last two accepted steps, CG's warm starts (scheme.h, warm_starts), and velocity():
  //! the last w, or 0 on a new triangulation.
  struct Velocities {
    Eigen::VectorXd previous, earlier, last;
  };

  //! The step's accepted trial and what it took (accepted_trial).
  struct Accepted {
    StepRecord record;
    StepResult trial;
    double tau = 0;
    int rejections = 0;
    std::vector<double> volumes; //!< of the components before the trial, for their restoration
    bool fell_back = false;      //!< a table's step was handed to adaptive steps
  };

  Accepted accepted_trial(FirstTrial& first, std::vector<StepEvent>& events);
  void take(Accepted& accepted, long next_step, const TimeStepState& controller_before);
  double retriangulate_after_step(std::vector<StepEvent>& events, StepTimes& times);
  //! The counts without the trial taken ahead, if one is held.
  const TrialCounts& counts() const { return ahead_.holds() ? ahead_.before().counts : trials_.counts(); }
  FirstTrial first_trial(long next_step, const std::atomic<bool>* cancel = nullptr);
  bool can_look_ahead() const;
  void publish(FlowNote note);
  //! The faces, the operators' cache and the topology of the surface's mesh.
  void renew_connectivity();
  //! The topology of the surface's mesh: its components, which are closed, the total genus.
  void renew_topology();
  //! hook_: the caller's `hook`, or the one of the options' schedule with its ℓ fixed now; without
  //! either, the guard that stops the flow at a self-intersection (intersection_guard.h).
  void prepare_retriangulation(RetriangulationHook hook, long tolerated_degraded);
  //! The hook's look at `mesh`, the flow's surface or a copy of it, after the last step (FlowHook::look;
  //! `failed_vertices`: where a step that forces it failed, RetriangulationContext::failed_vertices;
  //! `close_unresolved_gaps`: the last resort of a step that cannot be taken, the context's field of that name).
  RetriangulationReport call_retriangulation(Mesh& mesh, bool force, StepTimes& times,
                                             std::function<void()> changing = {},
                                             const std::vector<int>& failed_vertices = {},
                                             bool close_unresolved_gaps = false);
  //! A refused re-triangulation (RetriangulationReport::refused) becomes an event and a warning.
  void note_refusal(const RetriangulationReport& report, std::vector<StepEvent>& events);
  void adopt_retriangulation(const RetriangulationReport& report, const VertexVectors& before,
                             std::vector<StepEvent>& events, StepTimes& times);
  void renew_operators(StepTimes& times);
  //! What a step's trials share: the time-step rule's view of the surface before them.
  struct TrialPlan {
    Eigen::VectorXd edge_lengths; //!< h_v, each vertex's mean edge length
    AdaptiveOptions adaptive;     //!< the rule, refined with the run's resolution
    double automatic = 0;         //!< the rule's τ from the explicit speed (0: not needed)
    std::vector<bool> resolved;   //!< in a start phase, where the surface is resolved
    bool start = false;           //!< the next trial is a start step (backward Euler)
    //! It is one of the run's first start steps: they damp what the mesh does not resolve, and the
    //! displacement bound at resolved vertices is waived (time_step.h, start phase).
    bool run_start = false;
    double start_tau = 0;         //!< its τ
    double time_left = 0;         //!< to the end time (+∞ without one)
    double largest_tau = 0;       //!< the surface's own time scale (+∞ for a constant τ or a table)
  };
  TrialPlan plan_trials(long next_step, Eigen::VectorXd edge_lengths);
  StepResult solve_trial(double tau, bool start, const std::array<Eigen::VectorXd, 2>& guesses, long next_step,
                         StepRecord& record);
  double largest_volume_change(const VertexVectors& next, const std::vector<double>& volumes) const;
  double trial_step(const TrialContext& context, long next_step, StepResult& trial, StepRecord& record,
                    int& rejections, std::vector<double>& volumes);
  //! A note published at once, or held in `held` (TrialContext::held_notes) when that is not null.
  void note(long step, double time, std::string text, bool warning = false, std::vector<FlowNote>* held = nullptr);

  FlowOptions p_;
  FlowHook hook_;        // what happens to the surface between steps
  TrialSolvers trials_;  // the controller and the solvers: what trials change besides the surface
  Surface surface_;
  SchemeParts parts_;    // made once: an anisotropic energy's stiffness is a search over the sphere
  FlowOperators op_;     // of surface_: what the next step uses
  long step_ = 0;
  double time_ = 0;
  double start_length_ = 0;       // ℓ of the start phase's τ_s (time_step.h)
  double debris_volume_ = 0;      // FlowMetrics::debris_volume
  bool topology_changed_ = false; // with stop_at_topology_change: finished after this step
  //! The positions the last step started from while the surface keeps its triangles since
  //! (RetriangulationContext::step_start); empty after a re-triangulation.
  VertexVectors step_start_;
  Velocities w_;
  std::vector<FlowNote> notes_;   // made since the last take_notes()
  LookAhead ahead_;               // the next step's first trial, when one was taken beside the look
};

} // namespace sdflow
