#include "sdflow/flow/surface_diffusion.h"

#include "sdflow/errors.h"
#include "sdflow/flow/refinement.h"
#include "sdflow/flow/volume.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/log.h"
#include "sdflow/spatial/nearest_points.h"
#include "sdflow/stopwatch.h"

#include <fmt/format.h>
#include <tbb/parallel_invoke.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <iterator>
#include <limits>
#include <utility>

namespace sdflow {
namespace {

//! The mesh rebuilt from its arrays, so that a flow and its restoration from a state (which stores
//! the arrays) traverse identical halfedge structures and round identically.
Mesh canonical(const Mesh& mesh) { return make_mesh(vertex_positions(mesh), face_indices(mesh)); }

//! Thrown between the trials of a step taken ahead once the look re-triangulates.
struct TrialsCancelled {};

//! The options with their refinement fixed (refinement.h): an automatic one from `surface` and
//! the run's ℓ (the re-triangulation's target when it is on and given, else the surface's mean edge
//! length: without re-triangulation the mesh keeps its own resolution).
FlowOptions with_refinement(FlowOptions p, const Mesh& surface)
{
  if (p.refinement != 0) // given (checked with the rest)
    return p;
  const double target = p.retriangulation.pipeline.edge_length;
  const double ell = p.retriangulation.enabled && target > 0 ? target : mean_edge_length(surface);
  // A surface without edges has no ℓ: it is refused later, with the reason.
  p.refinement = ell > 0 && std::isfinite(ell) ? automatic_refinement(surface, ell) : 1;
  return p;
}

//! The time-step options the run's controller works with: the adaptive bound refined.
TimeStepOptions refined_time_step(const FlowOptions& p)
{
  TimeStepOptions options = p.time_step;
  options.adaptive = refined(options.adaptive, p.refinement);
  return options;
}

//! D⁴ for the bounding-box diagonal D of `mesh`: the longest adaptive τ (SurfaceDiffusion::step).
double natural_largest_tau(const Mesh& mesh)
{
  Eigen::AlignedBox3d box;
  for (const auto v : mesh.vertices())
    box.extend(to_eigen(mesh.point(v)));
  const double diagonal = box.isEmpty() ? 0.0 : box.diagonal().norm();
  return diagonal > 0 ? std::pow(diagonal, 4) : std::numeric_limits<double>::infinity();
}

} // namespace

SurfaceDiffusion::SurfaceDiffusion(const Mesh& initial, const CheckedFlowOptions& options,
                                   RetriangulationHook retriangulate)
    : p_(with_refinement(*options, initial)), trials_(refined_time_step(p_), p_.solver)
{
  parts_ = scheme_parts(p_.scheme);
  surface_.mesh = canonical(initial);
  parts_.boundary->check_surface(surface_.mesh, UserTerms{.setting = scenario_setting});
  renew_connectivity();
  prepare_retriangulation(std::move(retriangulate), 0);
  w_.last = Eigen::VectorXd::Zero(surface_.mesh.n_vertices());
  op_ = flow_operators(surface_.mesh, p_.scheme, parts_, &*surface_.cache);
}

SurfaceDiffusion::SurfaceDiffusion(const FlowState& state, const CheckedFlowOptions& options,
                                   RetriangulationHook retriangulate)
    : p_(with_refinement(*options, make_mesh(state.positions, state.triangles))),
      trials_(refined_time_step(p_), p_.solver, state.bookkeeping.controller)
{
  parts_ = scheme_parts(p_.scheme);
  step_ = state.step;
  time_ = state.time;
  surface_.mesh = make_mesh(state.positions, state.triangles);
  renew_connectivity();
  prepare_retriangulation(std::move(retriangulate), state.tolerated_degraded);
  w_.previous = state.previous_w;
  w_.earlier = state.earlier_w;
  w_.last = state.previous_w.size() == static_cast<Eigen::Index>(surface_.mesh.n_vertices())
                ? state.previous_w
                : Eigen::VectorXd::Zero(surface_.mesh.n_vertices());
  debris_volume_ = state.debris_volume;
  // Refactorise the anchors' systems: the preconditioners are then the ones the uninterrupted flow
  // would be using, so the CG iterates (and every later decision) are identical.
  const auto anchor_operators = [&](const VertexVectors& positions) {
    return flow_operators(make_mesh(positions, state.triangles), p_.scheme, parts_, &*surface_.cache);
  };
  trials_.restore_solvers(state.bookkeeping, anchor_operators);
  op_ = flow_operators(surface_.mesh, p_.scheme, parts_, &*surface_.cache);
}

bool SurfaceDiffusion::finished() const
{
  constexpr double end_time_tolerance = 1e-12; // relative: the last step is clipped to land on t_end
  return (p_.steps > 0 && step_ >= p_.steps) ||
         (std::isfinite(p_.end_time) && time_ >= p_.end_time * (1 - end_time_tolerance)) || topology_changed_;
}

StepRecord SurfaceDiffusion::step()
{
  const Stopwatch watch;
  const double cpu_start = process_cpu_seconds();
  const long next_step = step_ + 1;
  // The first trial: the one taken while the hook looked at the surface, else one now.
  std::optional<FirstTrial> ahead = ahead_.take(next_step);
  const bool taken_ahead = ahead.has_value();
  FirstTrial first = taken_ahead ? std::move(*ahead) : first_trial(next_step);
  for (FlowNote& n : first.notes)
    publish(std::move(n));
  std::vector<StepEvent> events;
  Accepted accepted = accepted_trial(first, events);
  take(accepted, next_step, first.controller_before);
  StepRecord& record = accepted.record;
  const double left_to_next_step = retriangulate_after_step(events, record.times);

  record.step = step_;
  record.time = time_;
  record.tau = accepted.tau;
  record.rejections = accepted.rejections;
  record.taken_ahead = taken_ahead;
  for (StepEvent& e : events) {
    e.step = step_;
    e.time = time_;
  }
  record.events = std::move(events);
  // A trial taken ahead is part of its own step: what of it ran beside the look counts in both
  // steps (side_by_side), what ran after it in the step it belongs to.
  record.times.total = watch.seconds() - left_to_next_step;
  if (taken_ahead) {
    record.times.total += first.alone_seconds;
    record.times.side_by_side += first.beside_look_seconds;
  }
  record.times.cpu = process_cpu_seconds() - cpu_start;
  return std::move(record);
}

//! Trials of the step after `first` until one is accepted. A step that no τ makes acceptable (a
//! triangle beside a closing neck that turns over whatever the step) is retried after a
//! re-triangulation of the surface it starts from (around where it failed, then, failing again,
//! the whole surface, then the last resort of closing gaps below the run's resolution); a table's
//! step that still fails is then
//! covered by adaptive steps (time_step.h). `events` gets the re-triangulation's and the fallback's.
SurfaceDiffusion::Accepted SurfaceDiffusion::accepted_trial(FirstTrial& first, std::vector<StepEvent>& events)
{
  const long next_step = first.step;
  const TimeStepState controller_before = first.controller_before;
  const bool table = p_.time_step.mode == TimeStepMode::schedule;
  TimeStepController& controller = trials_.controller(); // the same object after restart_controller()
  Accepted a{.record = std::move(first.record),
             .trial = std::move(first.trial),
             .tau = first.tau,
             .rejections = first.rejections,
             .volumes = std::move(first.volumes)};
  const auto restart_controller = [&] {
    TimeStepState s = controller_before;
    s.rejections = 0;
    s.turning_since_tau = 0;
    trials_.restart_controller(s);
  };
  // The hook's forced look at the surface the step starts from (`failed`: where the step failed;
  // `last_resort`: RetriangulationContext::close_unresolved_gaps), adopted when it changed it.
  const auto forced = [&](const std::vector<int>& failed, bool last_resort) {
    const VertexVectors before = vertex_positions(surface_.mesh);
    RetriangulationReport report = call_retriangulation(surface_.mesh, true, a.record.times, {}, failed, last_resort);
    note_refusal(report, events);
    if (report.changed()) {
      adopt_retriangulation(report, before, events, a.record.times);
      restart_controller();
    }
    return report;
  };
  // Re-triangulate the surface the step starts from; true when that changed it. The first call
  // gives the hook `failed`, the vertices where the last trial failed, to remesh around alone; if
  // it did, and the step fails again, a second call re-triangulates the whole surface.
  bool failed_given = false, whole_tried = false;
  RefusalReason whole_refused = RefusalReason::none;
  const auto retriangulated = [&](std::string_view why, const std::vector<int>& failed) {
    if (!hook_.retriangulates() || whole_tried)
      return false;
    note(next_step, time_, fmt::format("{}: re-triangulating, then trying again", why));
    const RetriangulationReport report =
        forced(std::exchange(failed_given, true) ? std::vector<int>{} : failed, false);
    whole_tried = !report.local;
    if (whole_tried)
      whole_refused = report.refusal;
    return report.changed();
  };
  // The last resort of a step that still cannot be taken after the whole surface's re-triangulation
  // was refused for stage 1's own crossings: the hook closes the gaps the flow brought below what
  // the run resolves (RetriangulationContext::close_unresolved_gaps); once a step.
  bool last_resort_tried = false;
  const auto closed_unresolved_gaps = [&](std::string_view why) {
    if (!hook_.retriangulates() || whole_refused != RefusalReason::remeshing_crossed ||
        std::exchange(last_resort_tried, true))
      return false;
    note(next_step, time_,
         fmt::format("{}: closing the gaps the flow brought below what the run resolves (the last resort), then "
                     "trying again",
                     why));
    return forced({}, true).changed();
  };
  for (bool taken = false;;) {
    try {
      if (!std::exchange(taken, true)) {
        if (first.failure)
          std::rethrow_exception(first.failure);
      } else {
        a.tau = trial_step({}, next_step, a.trial, a.record, a.rejections, a.volumes);
      }
      break;
    } catch (const TimeStepTooLarge&) {
      throw; // a smaller τ is needed, not a new surface or adaptive steps in its place
    } catch (const TrianglesTurning& e) {
      // Re-triangulated (at most twice a step), the step starts again; refused, τ shrinks on as the rule asks.
      controller.forget_turning();
      retriangulated(e.what(), e.vertices);
      continue;
    } catch (const SolverFailure& e) {
      const auto* unacceptable = dynamic_cast<const UnacceptableStep*>(&e);
      const std::string why = fmt::format("no acceptable step ({})", e.what());
      if (retriangulated(why, unacceptable ? unacceptable->vertices : std::vector<int>{}) ||
          closed_unresolved_gaps(why))
        continue;
      if (!table || a.fell_back || controller_before.fallback_left > 0)
        throw;
      a.fell_back = true;
      restart_controller();
      controller.fall_back_to_adaptive(next_step);
      std::string reason = fmt::format("the table's step {} cannot be taken ({}): adaptive steps cover its τ = {}",
                                       controller.table_step(next_step), e.what(), controller.state().fallback_left);
      note(next_step, time_, reason, true);
      events.push_back({.kind = StepEventKind::fallback, .detail = std::move(reason)});
    }
  }
  if (a.rejections > 0)
    events.insert(events.begin(), {.kind = StepEventKind::rejected, .rejections = a.rejections});
  if (a.record.start)
    events.insert(events.begin(), {.kind = StepEventKind::start});
  return a;
}

//! The surface moves to the accepted trial's (its volumes restored where asked or after a start
//! step), unless the guard finds it crossing itself (then it throws and the surface stays).
void SurfaceDiffusion::take(Accepted& a, long next_step, const TimeStepState& controller_before)
{
  step_start_ = vertex_positions(surface_.mesh); // also what the guard restores if the new surface crosses
  set_vertex_positions(surface_.mesh, a.trial.positions);
  if (p_.conserve_volume || a.record.start)
    set_vertex_positions(
        surface_.mesh, restore_volumes(surface_.mesh, a.volumes,
                                       {surface_.triangles, surface_.topology.face_component, surface_.topology.closed},
                                       *op_.parts.boundary)
                           .positions);
  if (hook_.guards()) {
    const Stopwatch check;
    try {
      hook_.check(surface_.mesh, next_step, time_ + a.tau);
    } catch (const SolverFailure&) {
      set_vertex_positions(surface_.mesh, step_start_);
      throw;
    }
    a.record.times.retriangulation_check += check.seconds();
  }
  step_ = next_step;
  time_ += a.tau;
  if ((a.fell_back || controller_before.fallback_left > 0) && !trials_.controller().adaptive())
    note(step_, time_, fmt::format("adaptive steps covered the table up to its step {}: the table resumes",
                                   trials_.controller().table_step(step_)));
  w_.earlier = std::exchange(w_.previous, a.trial.w);
  w_.last = a.trial.w;
}

//! The hook's look at the surface just reached (beside the next step's first trial when it may
//! look ahead), or only the new operators without a hook. Returns the wall seconds of that trial
//! which ran after the look (the next step counts them), 0 if none.
double SurfaceDiffusion::retriangulate_after_step(std::vector<StepEvent>& events, StepTimes& times)
{
  if (!hook_.retriangulates()) {
    renew_operators(times);
    return 0;
  }
  const VertexVectors before = vertex_positions(surface_.mesh);
  RetriangulationReport report;
  if (can_look_ahead()) {
    renew_operators(times); // the trial's operators: those of the surface as it stands
    LookAhead::Outcome outcome = ahead_.look_beside_trial(
        surface_.mesh, trials_,
        [&](Mesh& copy, std::function<void()> changing) {
          return call_retriangulation(copy, false, times, std::move(changing));
        },
        [&](const std::atomic<bool>* cancel) { return first_trial(step_ + 1, cancel); });
    if (outcome.held)
      return outcome.alone_seconds;
    note_refusal(outcome.report, events);
    if (outcome.failure)
      std::rethrow_exception(outcome.failure);
    surface_.mesh = std::move(outcome.surface);
    report = std::move(outcome.report);
  } else {
    report = call_retriangulation(surface_.mesh, false, times);
    note_refusal(report, events);
  }
  if (report.changed())
    adopt_retriangulation(report, before, events, times);
  else
    renew_operators(times);
  return 0;
}

FlowMetrics SurfaceDiffusion::metrics() const
{
  const CurvatureDeviation h = curvature_deviation(op_.curvature, op_.areas);
  const Mesh& mesh = surface_.mesh;
  const SphereDeviation d = sphere_deviation(mesh, op_.areas, p_.reference_centre, p_.reference_radius);
  return {.vertices = static_cast<long>(mesh.n_vertices()),
          .faces = static_cast<long>(mesh.n_faces()),
          .components = surface_.topology.count,
          .genus = surface_.topology.genus,
          .area = surface_area(mesh),
          .volume = material_volume(mesh),
          .debris_volume = debris_volume_,
          .mean_curvature = h.mean,
          .curvature_deviation_pct = h.deviation_pct,
          .d1 = d.d1,
          .d2 = d.d2,
          .energy = op_.parts.energy->value(mesh)};
}

FlowState SurfaceDiffusion::state() const
{
  FlowState s;
  s.step = step_;
  s.time = time_;
  s.positions = vertex_positions(surface_.mesh);
  s.triangles = surface_.triangles;
  s.previous_w = w_.previous;
  s.earlier_w = w_.earlier;
  s.tolerated_degraded = hook_.tolerated_degraded();
  s.debris_volume = debris_volume_;
  // The next step's trial taken ahead is not part of it.
  s.bookkeeping = ahead_.holds() ? ahead_.before().bookkeeping : trials_.bookkeeping();
  return s;
}

std::vector<FlowNote> SurfaceDiffusion::take_notes() { return std::exchange(notes_, {}); }

void SurfaceDiffusion::renew_connectivity()
{
  surface_.triangles = face_indices(surface_.mesh);
  surface_.cache.emplace(surface_.mesh);
  renew_topology();
}

void SurfaceDiffusion::renew_topology()
{
  surface_.topology = {};
  surface_.topology.face_component = face_component_ids(surface_.mesh, &surface_.topology.count);
  for (const auto& c : component_topology(surface_.mesh)) {
    surface_.topology.closed.push_back(c.closed());
    surface_.topology.genus += c.genus;
  }
  surface_.topology.loops = boundary_loop_vertices(surface_.mesh, surface_.topology.face_component);
}

void SurfaceDiffusion::prepare_retriangulation(RetriangulationHook hook, long tolerated_degraded)
{
  // The start phase's ℓ: the run's re-triangulation length when it has one (fixed in run.toml, so
  // a resumed run finds the same), else the mean edge length.
  start_length_ = p_.retriangulation.pipeline.edge_length > 0 ? p_.retriangulation.pipeline.edge_length
                                                              : mean_edge_length(surface_.mesh);
  if (hook) {
    hook_ = FlowHook(std::move(hook), false, tolerated_degraded);
    return;
  }
  RetriangulationSchedule& schedule = p_.retriangulation;
  if (!schedule.enabled) {
    hook_ = FlowHook(surface_.mesh, tolerated_degraded);
    return;
  }
  if (!(schedule.pipeline.edge_length > 0))
    schedule.pipeline.edge_length = start_length_;
  schedule.pipeline.keep_boundary = parts_.boundary->keeps_rim();
  schedule.pipeline.resample_boundary = parts_.boundary->resamples_rim();
  schedule.pipeline.anisotropy = parts_.anisotropy;
  RetriangulationSchedule refined_schedule = schedule;
  refined_schedule.pipeline = refined(schedule.pipeline, p_.refinement);
  hook_ = FlowHook(parts_.boundary->rim_topology_hook(make_retriangulation_hook(refined_schedule), refined_schedule),
                   true, tolerated_degraded);
}

RetriangulationReport SurfaceDiffusion::call_retriangulation(Mesh& mesh, bool force, StepTimes& times,
                                                             std::function<void()> changing,
                                                             const std::vector<int>& failed_vertices,
                                                             bool close_unresolved_gaps)
{
  // A forced look re-triangulates the surface a step could not leave: no step led to it.
  const bool stepped = !force && step_start_.rows() == static_cast<Eigen::Index>(mesh.n_vertices());
  return hook_.look(mesh, step_, time_, force, times, std::move(changing), stepped ? &step_start_ : nullptr,
                    failed_vertices, close_unresolved_gaps);
}

//! Take the re-triangulated mesh: new connectivity and operators, fresh factorisations with the
//! orderings carried from the surface `before` it (carried_ordering.h), its events.
void SurfaceDiffusion::note_refusal(const RetriangulationReport& report, std::vector<StepEvent>& events)
{
  if (!report.refused)
    return;
  if (!has_event(events, StepEventKind::refused))
    events.push_back({.kind = StepEventKind::refused,
                      .retriangulation = report.measures,
                      .detail = report.detail,
                      .refusal = report.refusal});
  note(step_, time_, fmt::format("re-triangulation refused ({}): {}", refusal_name(report.refusal), report.detail));
}

void SurfaceDiffusion::adopt_retriangulation(const RetriangulationReport& report, const VertexVectors& before,
                                             std::vector<StepEvent>& events, StepTimes& times)
{
  const int components = surface_.topology.count, genus = surface_.topology.genus;
  debris_volume_ += report.measures.debris_volume;
  step_start_.resize(0, 3); // of other triangles
  // The canonical mesh, the operators' cache of its connectivity and, for the carried orderings,
  // the old vertex nearest each new one are made side by side from the same positions and corners.
  const bool carried = trials_.carries_ordering();
  const VertexVectors after = vertex_positions(surface_.mesh);
  surface_.triangles = face_indices(surface_.mesh);
  std::vector<int> nearest_old;
  tbb::parallel_invoke([&] { surface_.mesh = make_mesh(after, surface_.triangles); },
                       [&] { surface_.cache.emplace(after.rows(), surface_.triangles); },
                       [&] {
                         if (carried)
                           nearest_old = nearest_points(before, after);
                       });
  renew_topology();
  renew_operators(times);
  topology_changed_ =
      topology_changed_ ||
      (p_.stop_at_topology_change && (surface_.topology.count != components || surface_.topology.genus != genus));
  const Stopwatch watch;
  trials_.carry_ordering(nearest_old, op_.laplacian);
  times.factorisation += watch.seconds();
  w_.previous.resize(0);
  w_.earlier.resize(0);
  w_.last = Eigen::VectorXd::Zero(surface_.mesh.n_vertices());
  std::vector<StepEvent> these;
  for (const auto& [flag, kind] :
       {std::pair{report.remeshed, StepEventKind::remeshed}, std::pair{report.surgery, StepEventKind::surgery},
        std::pair{report.split, StepEventKind::split}, std::pair{report.merged, StepEventKind::merged},
        std::pair{report.cleaned, StepEventKind::cleaned}, std::pair{report.touchdown, StepEventKind::touchdown},
        std::pair{report.contact, StepEventKind::contact}})
    if (flag && !has_event(events, kind))
      these.push_back({.kind = kind, .retriangulation = report.measures, .detail = report.detail});
  note(step_, time_, fmt::format("re-triangulated ({}): {}", event_names(these), report.detail));
  events.insert(events.end(), std::make_move_iterator(these.begin()), std::make_move_iterator(these.end()));
}

//! Step `next_step`'s first trials, until the controller accepts one or gives up (then `failure`
//! holds what it threw), with the note that the τ schedule has ended if it has; its notes held back.
FirstTrial SurfaceDiffusion::first_trial(long next_step, const std::atomic<bool>* cancel)
{
  FirstTrial f;
  f.step = next_step;
  f.controller_before = trials_.controller().state();
  const TrialContext context{.held_notes = &f.notes, .cancel = cancel};
  try {
    const auto& schedule = p_.time_step.schedule.entries();
    if (p_.time_step.mode == TimeStepMode::schedule && !trials_.controller().adaptive() &&
        trials_.controller().table_step(next_step) == schedule.back().last_step + 1)
      note(next_step, time_,
           fmt::format("the τ schedule ends at step {}: the steps after it repeat its last τ = {}", next_step - 1,
                       schedule.back().tau),
           true, context.held_notes);
    f.tau = trial_step(context, next_step, f.trial, f.record, f.rejections, f.volumes);
  } catch (const TrialsCancelled&) {
    f.failure = std::current_exception();
    f.cancelled = true;
  } catch (...) {
    f.failure = std::current_exception();
  }
  return f;
}

//! Whether the next step's first trial may run beside the look at the surface: when the options
//! let it (LookAhead::possible), with the flow's own hook, which changes the surface only by
//! re-triangulating it, when the hook looks after this step and a next step is due.
bool SurfaceDiffusion::can_look_ahead() const
{
  return LookAhead::possible(p_, static_cast<long>(surface_.mesh.n_vertices())) && hook_.own() &&
         step_ % p_.retriangulation.every == 0 && !finished();
}

//! The rule's view of the surface before step `next_step`'s trials (TrialPlan).
SurfaceDiffusion::TrialPlan SurfaceDiffusion::plan_trials(long next_step, Eigen::VectorXd edge_lengths)
{
  TrialPlan plan;
  plan.edge_lengths = std::move(edge_lengths);
  plan.adaptive = refined(p_.time_step.adaptive, p_.refinement);
  const AdaptiveOptions& adaptive = plan.adaptive;
  // The start phase (time_step.h) decides on the surface's unresolved variation, every start step:
  // a run's first steps, and the first step on each new triangulation (whose warm starts were
  // reset), where the fresh triangles carry variation the mesh does not resolve that the scheme's
  // β = ½ would flip instead of damping, so that τ would collapse trial after trial.
  const bool new_triangulation = step_ > 0 && w_.previous.size() == 0 && adaptive.start_steps > 0;
  const bool may_start = p_.time_step.mode == TimeStepMode::adaptive && adaptive.initial_tau == 0 &&
                         (next_step <= adaptive.start_steps || new_triangulation);
  TimeStepController& controller = trials_.controller();
  const bool need_automatic_tau =
      controller.adaptive() && controller.state().next_tau == 0 && adaptive.initial_tau == 0;
  const Eigen::VectorXd explicit_speed =
      need_automatic_tau || may_start ? Eigen::VectorXd(op_.rhs.cwiseQuotient(op_.areas).cwiseAbs())
                                      : Eigen::VectorXd();
  plan.automatic =
      need_automatic_tau ? automatic_tau(explicit_speed, op_.held, plan.edge_lengths, adaptive) : 0.0;
  if (may_start)
    plan.resolved = resolved_vertices(explicit_speed, op_.held, plan.edge_lengths);
  plan.start = may_start && is_start_step(adaptive, new_triangulation ? 1 : next_step, plan.resolved, op_.held);
  plan.run_start = plan.start && !new_triangulation;
  plan.time_left = std::isfinite(p_.end_time) ? p_.end_time - time_ : std::numeric_limits<double>::infinity();
  // Adaptive τ stops at D⁴ for the surface's bounding-box diagonal D, some 3500 decay times of its
  // slowest shape mode (limits.h). At rest nothing else bounds it: on a unit sphere it grew 1.25
  // times a step to 10¹¹ by step 500, where the β = ½ scheme damps no mode (each factor tends to
  // −1); the volume drifted by 1.8% and the factorisation lost the mass term (issue 33).
  plan.largest_tau =
      controller.adaptive() ? natural_largest_tau(surface_.mesh) : std::numeric_limits<double>::infinity();
  // On a new triangulation mid-run, no longer a step than the rule would take: the step stays as
  // accurate as the others, only its stiffest modes are damped rather than flipped.
  plan.start_tau = !may_start          ? 0.0
                   : new_triangulation ? std::min(start_tau(adaptive, start_length_),
                                                  controller.propose(next_step, plan.automatic, plan.time_left))
                                       : start_tau(adaptive, start_length_);
  return plan;
}

//! The trial of `tau` from the surface: a start step is backward Euler, with the scheme's β = ½ a
//! mode far shorter than its time scale would come out flipped, not damped (its factor
//! (1 − τk⁴/2)/(1 + τk⁴/2) tends to −1). Its counts and times go to `record`.
StepResult SurfaceDiffusion::solve_trial(double tau, bool start, const std::array<Eigen::VectorXd, 2>& guesses,
                                         long next_step, StepRecord& record)
{
  StepResult trial =
      start ? solve_step(surface_.mesh, op_, tau, kStartBeta, trials_.whole().solver(), guesses)
      : p_.scheme.extrapolate
          ? extrapolated_step(surface_.mesh, op_, tau, p_.scheme, trials_.whole().solver(), trials_.half().solver(),
                              &*surface_.cache, guesses)
          : solve_step(surface_.mesh, op_, tau, p_.scheme.beta, trials_.whole().solver(), guesses);
  record.cg_iterations += trial.solve.iterations;
  trials_.solved(trial);
  StepTimes& times = record.times;
  times.operators += trial.operators_seconds;
  times.assembly += trial.solve.seconds.assembly;
  times.factorisation += trial.solve.seconds.factorisation;
  times.solve += trial.solve.seconds.solve;
  if (trial.factorisations > 0) {
    record.factorised = true;
    logger().debug("step {}: {} factorisations (τ = {})", next_step, trial.factorisations, tau);
  }
  return trial;
}

//! The largest relative change of a component's material volume from `volumes` to the trial's
//! positions (0 when they are not finite: the check refuses those anyway).
double SurfaceDiffusion::largest_volume_change(const VertexVectors& next, const std::vector<double>& volumes) const
{
  double change = 0;
  if (!next.allFinite())
    return change;
  const Topology& topology = surface_.topology;
  const std::vector<double> after =
      material_volumes(next, surface_.triangles, topology.face_component, topology.count, topology.loops);
  for (int k = 0; k < topology.count; ++k)
    if (volumes[k] != 0)
      change = std::max(change, std::abs(after[k] - volumes[k]) / std::abs(volumes[k]));
  return change;
}

//! Trials of step `next_step` until the controller accepts one (returned: its τ); throws
//! SolverFailure as the controller does.
double SurfaceDiffusion::trial_step(const TrialContext& context, long next_step, StepResult& trial,
                                    StepRecord& record, int& rejections, std::vector<double>& volumes)
{
  StepTimes& times = record.times;
  Stopwatch watch;
  const VertexVectors positions = vertex_positions(surface_.mesh);
  Eigen::VectorXd edge_lengths = vertex_mean_edge_lengths(surface_.mesh);
  const Topology& topology = surface_.topology;
  volumes = material_volumes(positions, surface_.triangles, topology.face_component, topology.count, topology.loops);
  TimeStepController& controller = trials_.controller();
  // Only adaptive steps check the energy (check_trial); a constant or tabled τ's trials never read it,
  // so there it stays 0, which the trials below take as no energy to compare with.
  const double energy = controller.adaptive() ? flow_energy(parts_, surface_.mesh, positions) : 0.0;
  times.acceptance += watch.seconds();
  TrialPlan plan = plan_trials(next_step, std::move(edge_lengths));
  const AdaptiveOptions& adaptive = plan.adaptive;
  int start_retries = 0;
  const std::array<Eigen::VectorXd, 2> guesses = warm_starts(w_.previous, w_.earlier);
  for (;;) {
    if (context.cancel && context.cancel->load())
      throw TrialsCancelled();
    // An adaptive τ stays within the boundary condition's bound (a contact line's, substrate_boundary.h)
    // and the surface's own time scale (TrialPlan::largest_tau).
    // A contact line whose own bound is below min_tau has a cell too stiff to step (a sliver or a
    // very short edge at the rim): that is the triangulation's fault, not a τ to crawl at.
    if (controller.adaptive() && op_.tau_limit < adaptive.min_tau)
      throw SolverFailure(fmt::format("the contact line's own τ bound {:.3g} is below adaptive.min_tau = {:g}: a "
                                      "triangle at the contact line is too stiff (a sliver, or a very short edge)",
                                      op_.tau_limit, adaptive.min_tau));
    const double time_bound = controller.adaptive() ? std::min(plan.time_left, op_.tau_limit) : plan.time_left;
    const double tau = plan.start ? std::min(plan.start_tau, plan.time_left)
                                  : std::min(controller.propose(next_step, plan.automatic, time_bound), plan.largest_tau);
    trial = solve_trial(tau, plan.start, guesses, next_step, record);
    watch.restart();
    const double volume_change = largest_volume_change(trial.positions, volumes);
    const double energy_change =
        energy != 0 && trial.positions.allFinite()
            ? (flow_energy(parts_, surface_.mesh, trial.positions) - energy) / std::abs(energy)
            : 0.0;
    StepCheck check = check_trial({.tau = tau,
                                   .now = positions,
                                   .next = trial.positions,
                                   .w = trial.w,
                                   .error = trial.error,
                                   .triangles = surface_.triangles,
                                   .edge_lengths = plan.edge_lengths,
                                   .volume_change = volume_change,
                                   .energy_change = energy_change},
                                  adaptive, controller.adaptive());
    logger().debug("step {}: the trial of τ = {} changes a component's material volume by {:.3g} (relative)", next_step,
                   tau, volume_change);
    if (check.volume_exceeded && !controller.adaptive())
      check.adaptive_tau =
          automatic_tau(op_.rhs.cwiseQuotient(op_.areas).cwiseAbs(), op_.held, plan.edge_lengths, adaptive);
    times.acceptance += watch.seconds();
    if (plan.start) {
      // Backward Euler damps what the mesh cannot follow, and the volumes are restored after the
      // step. On a new triangulation mid-run the displacement bound holds where the surface is
      // resolved; in the run's first steps it does not: there the damping of noise, creases and
      // slivers moves their resolved neighbours too (on CGAL's bunny00.off by 0.57 of an edge at
      // τ_s), and a bound there held τ at 10⁻¹² for hundreds of steps.
      const double resolved_ratio = resolved_displacement_ratio(tau, trial.w, plan.edge_lengths, plan.resolved);
      if (!check.non_finite && check.inverted_triangles == 0 &&
          (plan.run_start || resolved_ratio <= adaptive.max_displacement)) {
        controller.accept_start_step(tau);
        record.start = true;
        return tau;
      }
      ++rejections;
      trials_.rejected();
      note(next_step, time_,
           fmt::format("rejected start step τ = {}: {}, normal displacement {:.3g} of the local edge length where "
                       "the surface is resolved",
                       tau, check.describe(), resolved_ratio),
           false, context.held_notes);
      plan.start_tau = tau * (resolved_ratio > adaptive.max_displacement
                                  ? std::min(adaptive.shrink, adaptive.safety * adaptive.max_displacement / resolved_ratio)
                                  : kStartShrink);
      // Below the τ the rule itself would try, a start step gains nothing.
      plan.start = ++start_retries <= kStartRetries && plan.start_tau > plan.automatic;
      continue;
    }
    if (controller.judge(next_step, tau, check)) {
      if (const auto& aside = controller.energy_stood_aside())
        note(next_step, time_,
             fmt::format("accepted τ = {:g} although the energy rose by {:.3g} (relative): at τ = {:g} it rose by {:.3g}, "
                         "so the rise does not fall with τ as a time step's would; the energy rule stands aside for "
                         "this step",
                         aside->accepted_tau, aside->accepted_rise, aside->rejected_tau, aside->rejected_rise),
             false, context.held_notes);
      return tau;
    }
    ++rejections;
    trials_.rejected();
    note(next_step, time_, fmt::format("rejected τ = {}: {}", tau, check.describe()), false, context.held_notes);
    if (check.inverted_triangles > 0 && hook_.retriangulates() && controller.turning_collapsed())
      throw TrianglesTurning(fmt::format("triangles keep turning over: the next τ, {:g}, would be {:.3g} times the "
                                         "τ = {:g} at which they began",
                                         controller.state().next_tau,
                                         controller.state().next_tau / controller.state().turning_since_tau,
                                         controller.state().turning_since_tau),
                             check.failed_vertices);
  }
}

void SurfaceDiffusion::renew_operators(StepTimes& times)
{
  const Stopwatch watch;
  op_ = flow_operators(surface_.mesh, p_.scheme, parts_, &*surface_.cache);
  times.operators += watch.seconds();
}

void SurfaceDiffusion::note(long step, double time, std::string text, bool warning, std::vector<FlowNote>* held)
{
  FlowNote n{.step = step, .time = time, .text = std::move(text), .warning = warning};
  if (held)
    held->push_back(std::move(n));
  else
    publish(std::move(n));
}

void SurfaceDiffusion::publish(FlowNote n)
{
  if (n.warning)
    logger().warn("{}", n.text);
  else
    logger().info("{}", n.line());
  notes_.push_back(std::move(n));
}

} // namespace sdflow
