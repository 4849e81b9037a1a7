#include "sdflow/flow/retriangulation.h"

#include "sdflow/errors.h"
#include "sdflow/flow/volume.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/quality.h"
#include "sdflow/remesh/remesh.h"
#include "sdflow/retri/local_surgery.h"
#include "sdflow/spatial/intersect.h"
#include "sdflow/stopwatch.h"

#include <fmt/format.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <memory>
#include <optional>
#include <numbers>

namespace sdflow {
namespace {

//! The self-intersections of the surface from step to step: a SelfIntersectionTracker refitted
//! while the connectivity stays the same, rebuilt when it changes. Its pairs are exactly those of
//! self_intersections(), so the cache changes the cost of a check, never its answer.
class IntersectionWatch {
public:
  std::size_t count(const Mesh& mesh)
  {
    FaceIndices triangles = face_indices(mesh);
    if (tracker_ && vertices_ == mesh.n_vertices() && triangles.rows() == triangles_.rows() && triangles == triangles_)
      return tracker_->update(mesh).size();
    tracker_.emplace(mesh);
    triangles_ = std::move(triangles);
    vertices_ = mesh.n_vertices();
    return tracker_->pairs().size();
  }

  //! The intersecting pairs found by the last count().
  const std::vector<FacePair>& pairs() const { return tracker_->pairs(); }

private:
  std::optional<SelfIntersectionTracker> tracker_;
  FaceIndices triangles_;
  std::size_t vertices_ = 0;
};

//! Edges outside [ℓ/r, rℓ] and triangles with an angle below the schedule's minimum.
struct Degraded {
  long edges = 0, triangles = 0;
  long total() const { return edges + triangles; }
};

Degraded degraded_elements(const Mesh& mesh, const RetriangulationSchedule& s)
{
  const RetriangulationOptions& pipeline = s.pipeline;
  const double ell = pipeline.edge_length;
  // The targets the pipeline's remesher would aim at: a closing neck asks for shorter edges.
  const std::vector<double> target =
      pipeline.edges_per_radius > 0
          ? radius_targets(mesh, {.edges_per_radius = pipeline.edges_per_radius,
                                  .min_length = pipeline.min_edge_fraction * ell, .max_length = ell})
          : std::vector<double>(mesh.n_vertices(), ell);
  Degraded d;
  for (const auto e : mesh.edges()) {
    const double length = mesh.calc_edge_length(e);
    const double local = 0.5 * (target[e.v0().idx()] + target[e.v1().idx()]);
    d.edges += length > s.edge_ratio * local || length * s.edge_ratio < local;
  }
  for (const auto f : mesh.faces())
    d.triangles += smallest_angle_deg(mesh, f) < s.min_angle_deg;
  return d;
}

//! Why the surface needs the pipeline now (empty: it does not). Degraded elements trigger it when
//! they exceed both the schedule's allowance and what the last re-triangulation left behind, so
//! elements the remesher cannot improve (beside a thin neck, say) do not call it after every step.
std::string reason_to_retriangulate(const Mesh& mesh, const RetriangulationSchedule& s, long tolerated,
                                    IntersectionWatch& watch)
{
  if (s.always)
    return "scheduled";
  if (const std::size_t pairs = watch.count(mesh); pairs > 0)
    return fmt::format("{} intersecting face pairs", pairs);
  const Degraded d = degraded_elements(mesh, s);
  const double allowed = std::max(s.degraded_fraction * static_cast<double>(mesh.n_faces()),
                                  static_cast<double>(tolerated));
  if (static_cast<double>(d.total()) > allowed)
    return fmt::format("{} edges outside [ℓ/{}, {}ℓ] of their target ℓ and {} triangles with an angle below {}°", d.edges,
                       s.edge_ratio, s.edge_ratio, d.triangles, s.min_angle_deg);
  return {};
}

} // namespace

void validate_retriangulation_schedule(const RetriangulationSchedule& s)
{
  if (s.every < 1)
    throw InvalidParameter(fmt::format("retriangulation.every must be ≥ 1, got {}", s.every));
  if (!(s.min_angle_deg >= 0 && s.min_angle_deg < 60))
    throw InvalidParameter(fmt::format("retriangulation.min_angle must be in [0, 60) degrees, got {}", s.min_angle_deg));
  if (!(s.degraded_fraction >= 0 && s.degraded_fraction < 1))
    throw InvalidParameter(
        fmt::format("retriangulation.degraded_fraction must be in [0, 1), got {}", s.degraded_fraction));
  if (!(s.edge_ratio > 1) || !std::isfinite(s.edge_ratio))
    throw InvalidParameter(fmt::format("retriangulation.edge_ratio must be a finite number > 1, got {}", s.edge_ratio));
  validate_retriangulation_options(s.pipeline);
}

RetriangulationHook make_retriangulation_hook(const RetriangulationSchedule& schedule)
{
  validate_retriangulation_schedule(schedule);
  if (!(schedule.pipeline.edge_length > 0))
    throw InvalidParameter("the re-triangulation hook needs a resolved target edge length (> 0)");
  auto watch = std::make_shared<IntersectionWatch>();
  return [schedule, watch](Mesh& mesh, const RetriangulationContext& context) {
    RetriangulationReport report;
    if (!context.force && context.step % schedule.every != 0)
      return report;
    Stopwatch stopwatch;
    const std::string reason = context.force ? "no step could be taken"
                                             : reason_to_retriangulate(mesh, schedule, context.tolerated_degraded, *watch);
    report.check_seconds = stopwatch.restart();
    if (reason.empty())
      return report;
    // reason_to_retriangulate looked for intersections unless forced or always re-triangulating.
    std::optional<RetriangulationResult> local;
    std::string route;
    if (schedule.local && !context.force && !schedule.always && !watch->pairs().empty()) {
      LocalSurgery surgery = local_surgery(mesh, watch->pairs(), schedule.pipeline);
      local = std::move(surgery.result);
      if (!local)
        route = fmt::format(" (local surgery: {}; the whole surface instead)", surgery.failure);
    }
    RetriangulationResult r = local ? std::move(*local) : retriangulate(mesh, schedule.pipeline);
    report.pipeline_seconds = r.seconds;
    stopwatch.restart();
    std::string volume_note;
    if (schedule.restore_volume) {
      const double before = enclosed_volume(r.mesh);
      const VolumeRestoration restored = restore_volumes_from(mesh, r.mesh);
      set_vertex_positions(r.mesh, restored.positions);
      const double after = enclosed_volume(r.mesh);
      if (after != 0)
        volume_note = fmt::format("; volume restored by {:.3g} (relative)", (after - before) / after);
    }
    report.volume_seconds = stopwatch.seconds();
    report.remeshed = schedule.pipeline.remesh_iterations > 0;
    report.surgery = r.rebuilt;
    report.split = r.components_after > r.components_before - r.merged_components;
    report.merged = r.merged_components > 0;
    report.degraded_left = degraded_elements(r.mesh, schedule).total();
    report.detail =
        fmt::format("{}{}: {}{}; {} degraded elements left", reason, route, retriangulation_summary(r), volume_note, report.degraded_left);
    mesh = std::move(r.mesh);
    return report;
  };
}

} // namespace sdflow
