#include "sdflow/flow/look_ahead.h"

#include "sdflow/solve/blas_threads.h"
#include "sdflow/stopwatch.h"

#include <tbb/parallel_invoke.h>
#include <tbb/task_arena.h>

#include <algorithm>
#include <utility>

namespace sdflow {

bool LookAhead::possible(const FlowOptions& p, long vertices)
{
  return p.look_ahead && p.retriangulation.pipeline.remesh_iterations > 0 &&
         tbb::this_task_arena::max_concurrency() > 1 && blas_threads_for(vertices, p.solver.blas) == 1;
}

LookAhead::Outcome LookAhead::look_beside_trial(const Mesh& surface, TrialSolvers& trials, const Look& look,
                                                const Trial& trial)
{
  TrialMark before = trials.mark();
  Outcome out;
  FirstTrial first;
  std::atomic<bool> dropped = false; // set by the hook once it re-triangulates: the trial stops
  double look_seconds = 0, trial_seconds = 0;
  const Stopwatch both;
  tbb::parallel_invoke(
    [&] {
      const Stopwatch watch;
      try {
        out.surface = surface;
        out.report = look(out.surface, [&] { dropped = true; });
      } catch (...) {
        out.failure = std::current_exception();
      }
      look_seconds = watch.seconds();
    },
    [&] {
      const Stopwatch watch;
      first = trial(&dropped);
      trial_seconds = watch.seconds();
    });
  const double wall = both.seconds();
  if (!out.failure && !dropped && !out.report.changed() && out.report.degraded_left < 0) {
    first.beside_look_seconds = std::clamp(look_seconds + trial_seconds - wall, 0.0, trial_seconds);
    first.alone_seconds = std::clamp(wall - look_seconds, 0.0, trial_seconds - first.beside_look_seconds);
    held_ = Held{std::move(first), std::move(before)};
    return {.held = true, .alone_seconds = held_->first.alone_seconds};
  }
  // The solvers still hold the factors of the mark unless the trial made one or failed in a solve.
  const bool factors_as_marked =
      (!first.failure || first.cancelled) && trials.counts().factorisations == before.counts.factorisations;
  trials.rewind(before);
  // The flow's own hook changes the surface whenever it decides to, or fails. When it leaves the
  // surface as it was, the flow goes on from the factors it had, as a flow not looking ahead does.
  if ((out.failure || !out.report.changed()) && !factors_as_marked)
    trials.drop_factors();
  return out;
}

std::optional<FirstTrial> LookAhead::take(long step)
{
  std::optional<FirstTrial> first;
  if (held_ && held_->first.step == step)
    first = std::move(held_->first);
  held_.reset();
  return first;
}

} // namespace sdflow
