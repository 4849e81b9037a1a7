#include "sdflow/flow/substrate_topology_hook.h"

#include "sdflow/flow/substrate_topology.h"
#include "sdflow/flow/volume.h"
#include "sdflow/geometry/material_volume.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/stopwatch.h"

#include <fmt/format.h>

#include <numeric>
#include <utility>

namespace sdflow {

RetriangulationHook substrate_topology_hook(RetriangulationHook inner, double plane_z,
                                            const RetriangulationSchedule& schedule)
{
  const double ell = schedule.pipeline.edge_length;
  const SubstrateTopologyOptions options{.z = plane_z,
                                         .threshold = schedule.pipeline.min_edge_fraction * ell,
                                         .edge_length = ell,
                                         .min_component_faces = schedule.pipeline.min_component_faces};
  const bool restore = schedule.restore_volume;
  const long every = schedule.every;
  return [inner = std::move(inner), options, restore, every](Mesh& mesh, const RetriangulationContext& context) {
    if (!context.force && context.step % every != 0)
      return inner(mesh, context);
    Stopwatch stopwatch;
    SubstrateTopologyResult change = change_substrate_topology(mesh, options);
    const double look_seconds = stopwatch.restart();
    if (change.change == SubstrateChange::none) {
      RetriangulationReport report = inner(mesh, context);
      report.check_seconds += look_seconds;
      return report;
    }
    if (context.changing)
      context.changing();
    RetriangulationReport report;
    report.check_seconds = look_seconds;
    RetriangulationMeasures& m = report.measures;
    m.crossing_size = change.size;
    m.before = count_topology(mesh);
    m.after = count_topology(change.mesh);
    m.faces_before = static_cast<long>(mesh.n_faces());
    m.faces_after = static_cast<long>(change.mesh.n_faces());
    m.faces_rebuilt = change.faces_removed + change.debris_faces + change.faces_added;
    std::string volume_note;
    if (restore) {
      const double old_volume = material_volume(change.mesh);
      const VolumeRestoration restored = restore_volumes_from(mesh, change.mesh);
      set_vertex_positions(change.mesh, restored.positions);
      m.debris_volume = std::accumulate(restored.dropped_volumes.begin(), restored.dropped_volumes.end(), 0.0);
      m.volume_restored = (material_volume(change.mesh) - old_volume) / old_volume;
      volume_note = fmt::format("; volume restored ({:+.3g} relative)", m.volume_restored);
      report.volume_seconds = stopwatch.restart();
    }
    report.touchdown = change.change == SubstrateChange::touchdown;
    report.contact = change.change == SubstrateChange::contact;
    report.split = m.after.components > m.before.components;
    report.merged = m.after.components < m.before.components;
    report.detail = fmt::format("{}: components {} → {}, boundary loops {} → {}, genus {} → {}{}", change.detail,
                                m.before.components, m.after.components, m.before.boundary_loops,
                                m.after.boundary_loops, m.before.genus, m.after.genus, volume_note);
    mesh = std::move(change.mesh);
    // The cut leaves fresh contact lines and a ragged patch beside them; a re-triangulation now
    // (the rim resampled along itself, the rest remeshed) makes of them a surface the next step can
    // take. A refused one leaves the cut surface as it is.
    const RetriangulationReport tidy =
        inner(mesh, {.step = context.step, .time = context.time, .tolerated_degraded = 0, .force = true});
    if (tidy.changed()) {
      report.remeshed = tidy.remeshed;
      report.surgery = tidy.surgery;
      report.cleaned = tidy.cleaned;
      report.degraded_left = tidy.degraded_left;
      report.pipeline_seconds = tidy.pipeline_seconds;
      report.check_seconds += tidy.check_seconds;
      report.volume_seconds += tidy.volume_seconds;
      m.faces_after = static_cast<long>(mesh.n_faces());
      m.after = count_topology(mesh);
      report.detail += "; then " + tidy.detail;
    }
    return report;
  };
}

} // namespace sdflow
