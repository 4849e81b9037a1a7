#include "sdflow/flow/flow_hook.h"

#include "sdflow/errors.h"

#include <fmt/format.h>

#include <utility>

namespace sdflow {

FlowHook::FlowHook(RetriangulationHook hook, bool own, long tolerated_degraded)
    : hook_(std::move(hook)), own_(own), tolerated_degraded_(tolerated_degraded)
{
}

FlowHook::FlowHook(const Mesh& mesh, long tolerated_degraded)
    : guard_(std::in_place, mesh), tolerated_degraded_(tolerated_degraded)
{
}

RetriangulationReport FlowHook::look(Mesh& mesh, long step, double time, bool force, StepTimes& times,
                                     std::function<void()> changing, const VertexVectors* step_start,
                                     const std::vector<int>& failed_vertices, bool close_unresolved_gaps)
{
  try {
    RetriangulationReport report = hook_(mesh, {.step = step,
                                                .time = time,
                                                .tolerated_degraded = tolerated_degraded_,
                                                .force = force,
                                                .changing = std::move(changing),
                                                .step_start = step_start,
                                                .failed_vertices = failed_vertices,
                                                .close_unresolved_gaps = close_unresolved_gaps});
    if (report.degraded_left >= 0)
      tolerated_degraded_ = report.degraded_left;
    times.retriangulation_check += report.check_seconds;
    times.volume_restoration += report.volume_seconds;
    times.retriangulation_other += report.other_seconds;
    times.pipeline.add_stages(report.pipeline_seconds);
    times.side_by_side += report.pipeline_seconds.side_by_side;
    return report;
  } catch (const SolverFailure&) {
    throw;
  } catch (const Error& e) {
    throw SolverFailure(fmt::format("re-triangulation after step {} failed: {}", step, e.what()));
  }
}

void FlowHook::check(const Mesh& mesh, long step, double time)
{
  if (guard_)
    guard_->check(mesh, step, time);
}

} // namespace sdflow
