#include "sdflow/flow/retriangulation.h"

#include "sdflow/errors.h"
#include "sdflow/flow/crossing_width.h"
#include "sdflow/flow/degraded_elements.h"
#include "sdflow/flow/topology_guard.h"
#include "sdflow/flow/volume.h"
#include "sdflow/geometry/material_volume.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/remesh/local_remesh.h"
#include "sdflow/retri/local_surgery.h"
#include "sdflow/spatial/intersect.h"
#include "sdflow/stopwatch.h"

#include <fmt/format.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <exception>
#include <limits>
#include <memory>
#include <numbers>
#include <optional>
#include <utility>

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

//! Why and how the surface is to be re-triangulated now (an empty reason: it is not).
struct Verdict {
  std::string reason;
  bool local = false;        //!< only degraded elements call for it, and the schedule allows a local remeshing
  bool intersecting = false; //!< the surface intersects itself (the watch holds the pairs)
  bool watched = false;      //!< the watch counted this surface's pairs (none when not intersecting)
  long pairs = 0;            //!< intersecting face pairs, when `intersecting`
  DegradedElements degraded; //!< found when nothing intersects
};

//! A surface's intersecting pairs and degraded elements, counted side by side.
struct SurfaceCount {
  std::size_t pairs = 0;
  DegradedElements degraded;
  std::exception_ptr degraded_failure; //!< finding them failed (a crossing can leave a degenerate triangle)

  //! The degraded elements, or the failure to find them rethrown (they count only when nothing intersects).
  DegradedElements degraded_or_throw()
  {
    if (degraded_failure)
      std::rethrow_exception(degraded_failure);
    return std::move(degraded);
  }
};

//! The two counts read the surface independently, so they overlap on two cores; each answer is the
//! one it would be alone.
SurfaceCount count_surface(const Mesh& mesh, const RetriangulationSchedule& s, IntersectionWatch& watch)
{
  SurfaceCount c;
  tbb::parallel_invoke([&] { c.pairs = watch.count(mesh); },
                       [&] {
                         try {
                           c.degraded = degraded_elements(mesh, s);
                         } catch (...) {
                           c.degraded_failure = std::current_exception();
                         }
                       });
  return c;
}

//! Degraded elements left by the last re-triangulation from which on a remesher's own scatter,
//! not the flow, decides whether more have appeared.
constexpr long kScatteredDegraded = 20;

//! How many more degraded elements than the last re-triangulation left (`tolerated`) call for the
//! next: the schedule's degraded_variation of them, and where a remeshing leaves many (a CAD part's
//! sharp edges, which it cannot fix), at least twice their square root, the scatter of such counts
//! from one remeshing to the next. On CGAL's fandisk_large.off successive whole remeshings left
//! 104–198 (about 150), so 5% more, 8 elements, called the whole pipeline every third step, 205
//! times in a run, each leaving as many as it found; later, at 40–70, after every step. Below
//! kScatteredDegraded (every validation run leaves fewer) any increase beyond the variation calls
//! it, as a thinning neck shows only a few; a degraded_variation of 0 keeps the strict rule.
double degraded_slack(const RetriangulationSchedule& s, long tolerated)
{
  const double relative = s.degraded_variation * static_cast<double>(tolerated);
  if (tolerated < kScatteredDegraded || s.degraded_variation == 0)
    return relative;
  return std::max(relative, 2 * std::sqrt(static_cast<double>(tolerated)));
}

//! The pipeline runs when the surface intersects itself (or on `always`). Degraded elements call
//! for a re-triangulation when they exceed both the schedule's allowance and what the last one left
//! behind (by more than the schedule's degraded_variation), so elements the remesher cannot improve
//! (beside a thin neck, at a CAD part's sharp edges) do not call it after every step.
Verdict look_at_surface(const Mesh& mesh, const RetriangulationSchedule& s, long tolerated, IntersectionWatch& watch)
{
  Verdict v;
  if (s.always) {
    v.reason = "scheduled";
    return v;
  }
  SurfaceCount counted = count_surface(mesh, s, watch);
  v.watched = true;
  if (counted.pairs > 0) {
    v.reason = fmt::format("{} intersecting face pairs", counted.pairs);
    v.intersecting = true;
    v.pairs = static_cast<long>(counted.pairs);
    return v;
  }
  v.degraded = counted.degraded_or_throw();
  const DegradedElements& d = v.degraded;
  const double allowed = std::max(s.degraded_fraction * static_cast<double>(mesh.n_faces()),
                                  static_cast<double>(tolerated) + degraded_slack(s, tolerated));
  if (static_cast<double>(d.total()) > allowed) {
    v.reason = fmt::format("{} edges outside [ℓ/{}, {}ℓ] of their target ℓ and {} triangles with an angle below {}°",
                           d.edges, s.edge_ratio, s.edge_ratio, d.triangles, s.min_angle_deg);
    v.local = s.local && s.pipeline.remesh_iterations > 0;
  }
  return v;
}

//! Rings of faces around the worn ones that a local remeshing takes with them. The kept boundary
//! lies this many rings out, so the corners of the worn elements and two rings beyond are free to
//! move, merge and split, and the sizing can grade from the boundary's edges to a finer target
//! inside. Measured on the test's dumbbell (radius 3, ℓ = 0.5) with one round around the degraded
//! faces alone: the first local remeshing left 86 of 95 degraded elements with two rings, 55 with
//! three.
constexpr int kLocalRemeshRings = 3;

//! Give the components of `after`, a re-triangulation of `before`, back their volume (volume.h),
//! through the vertices a local remeshing kept when it gives them (`vertex_map`, else empty);
//! returns the note for events.log, with the volume of each component dropped whole. The relative
//! change it made and the dropped volume go to `measures`.
std::string restore_volume(const Mesh& before, Mesh& after, RetriangulationMeasures& measures,
                           const std::vector<int>& vertex_map = {})
{
  const double old_volume = material_volume(after);
  const VolumeRestoration restored =
      vertex_map.empty() ? restore_volumes_from(before, after) : restore_volumes_kept(before, after, vertex_map);
  set_vertex_positions(after, restored.positions);
  const double new_volume = material_volume(after);
  std::string note;
  if (new_volume != 0) {
    measures.volume_restored = (new_volume - old_volume) / new_volume;
    note = fmt::format("; volume restored by {:.3g} (relative)", measures.volume_restored);
  }
  for (double v : restored.dropped_volumes) {
    note += fmt::format("; a component of volume {:.6g} dropped whole as debris", v);
    measures.debris_volume += v;
  }
  return note;
}

//! The surface whose volumes a re-triangulation of `mesh` gives back: `mesh`, or the one the last
//! resort remeshed into it (RetriangulationContext::remeshed_across_gaps).
const Mesh& volume_source(const Mesh& mesh, const RetriangulationContext& context)
{
  return context.remeshed_across_gaps ? *context.remeshed_across_gaps->from : mesh;
}

//! The largest share of the surface's faces a local remeshing takes (the worn faces with their
//! rings); beyond it the whole pipeline runs. On the three spheres on a plane the first steps,
//! while the surface settles to its curvature-adapted sizing, wear 10–35% of it at once: remeshing
//! all of it then lasts longer than remeshing those patches, which leave the rest as worn as it was.
constexpr double kLocalPatchShare = 0.1;

//! Rounds of local remeshing at most: each one remeshes around what the last one left degraded
//! (a patch's kept boundary can leave a few sharp triangles or off-target edges beside it).
constexpr int kLocalRemeshRounds = 3;

//! What the rounds of a local remeshing did together.
struct LocalRounds {
  LocalRemeshResult result; //!< the last round's mesh, the vertex map through all rounds, the sums
  DegradedElements left;    //!< degraded elements of the result
  int rounds = 0;
};

//! Remesh around the worn faces of `degraded` (degraded_elements.h), then around those the round
//! left, until at most `allowance` degraded elements are left, a round fixes nothing more, or
//! kLocalRemeshRounds have run.
LocalRounds remesh_worn_regions(const Mesh& mesh, const DegradedElements& degraded, const RetriangulationSchedule& s,
                                double allowance)
{
  const RetriangulationOptions& o = s.pipeline;
  LocalRounds rounds;
  LocalRemeshResult& total = rounds.result;
  const Mesh* current = &mesh;
  const DegradedElements* seeds = &degraded;
  while (rounds.rounds < kLocalRemeshRounds) {
    // Only the first round can be declined: later ones work around what it left.
    LocalRemeshResult next =
        remesh_locally(*current, seeds->worn_faces, seeds->targets,
                       {.edge_length = o.edge_length, .iterations = o.remesh_iterations, .rings = kLocalRemeshRings,
                        .curved_projection = o.curved_projection,
                        .crease_angle_deg = o.crease_angle_deg,
                        .max_patch_share = rounds.rounds == 0 ? kLocalPatchShare : 1.0,
                        .area_weighted_relaxation = o.graded_remeshing});
    if (next.declined) {
      total.patch_faces = next.patch_faces;
      total.declined = true;
      return rounds;
    }
    if (rounds.rounds == 0) {
      total.vertex_map = std::move(next.vertex_map);
    } else {
      for (int& v : total.vertex_map)
        v = v >= 0 ? next.vertex_map[v] : -1;
    }
    total.mesh = std::move(next.mesh);
    total.patch_faces += next.patch_faces;
    total.new_faces += next.new_faces;
    total.patches += next.patches;
    total.statistics.splits += next.statistics.splits;
    total.statistics.collapses += next.statistics.collapses;
    total.statistics.flips += next.statistics.flips;
    ++rounds.rounds;
    const long before = seeds->total();
    rounds.left = degraded_elements(total.mesh, s);
    if (static_cast<double>(rounds.left.total()) <= allowance || rounds.left.total() >= before)
      break;
    current = &total.mesh;
    seeds = &rounds.left;
  }
  return rounds;
}

//! restore_volume on a local remeshing `r` of `mesh`; nullopt, with `fallback` saying why (`what` left
//! it), when `r` has a vertex whose degenerate star gives no normal to offset along.
std::optional<std::string> restore_local_volume(const Mesh& mesh, LocalRemeshResult& r, RetriangulationReport& report,
                                                std::string_view what, std::string& fallback)
{
  try {
    return restore_volume(mesh, r.mesh, report.measures, r.vertex_map);
  } catch (const InvalidMesh& e) {
    fallback = fmt::format("{} left a surface whose volume cannot be restored ({}), so the whole pipeline ran; ", what,
                           e.what());
    report.measures = {};
    return std::nullopt;
  }
}

//! The local remeshing of a hook: the regions around the degraded elements remeshed and their
//! volume given back, accepted unless they are too large (kLocalPatchShare), the patch cannot be
//! cut out or put back, or the result intersects itself (then the caller falls back to the whole
//! pipeline, whose note is returned in `fallback`; `verdict.watched` turns false once the watch
//! has counted another surface than `mesh`).
std::optional<Mesh> remesh_degraded_region(const Mesh& mesh, Verdict& verdict, const RetriangulationSchedule& s,
                                           IntersectionWatch& watch, RetriangulationReport& report,
                                           std::string& fallback)
{
  Stopwatch stopwatch;
  LocalRounds rounds;
  try {
    rounds = remesh_worn_regions(mesh, verdict.degraded, s,
                                 s.degraded_fraction * static_cast<double>(mesh.n_faces()));
  } catch (const InvalidMesh& e) {
    fallback = fmt::format("the local remeshing failed ({}), so the whole pipeline ran; ", e.what());
    return std::nullopt;
  }
  LocalRemeshResult& r = rounds.result;
  report.pipeline_seconds.remesh = stopwatch.restart();
  if (r.declined) {
    fallback = fmt::format("the worn regions and their rings hold {} of the {} faces, more than a local remeshing "
                           "takes, so the whole pipeline ran; ",
                           r.patch_faces, mesh.n_faces());
    return std::nullopt;
  }
  const std::optional<std::string> volume_note =
      s.restore_volume ? restore_local_volume(mesh, r, report, "the local remeshing", fallback) : std::string{};
  if (!volume_note)
    return std::nullopt;
  report.volume_seconds = stopwatch.restart();
  verdict.watched = false; // the watch now holds the remeshed surface's pairs
  // The volume restoration moved the vertices by a tiny normal offset: count the degraded elements
  // again, beside the intersection test (the count is wasted only when that test fails).
  SurfaceCount counted = count_surface(r.mesh, s, watch);
  report.pipeline_seconds.intersections = stopwatch.seconds();
  if (counted.pairs > 0) {
    fallback = fmt::format("the local remeshing left {} intersecting face pairs, so the whole pipeline ran; ",
                           counted.pairs);
    report.measures = {}; // of a surface given up
    return std::nullopt;
  }
  report.remeshed = report.local = true;
  report.degraded_left = counted.degraded_or_throw().total();
  report.measures.before = count_topology(mesh);
  report.measures.after = count_topology(r.mesh);
  report.measures.faces_before = static_cast<long>(mesh.n_faces());
  report.measures.faces_after = static_cast<long>(r.mesh.n_faces());
  report.measures.faces_rebuilt = r.patch_faces;
  report.detail = fmt::format("{}: local remeshing of {} faces in {} patches into {} in {} rounds ({} splits, {} "
                              "collapses, {} flips){}; {} degraded elements left",
                              verdict.reason, r.patch_faces, r.patches, r.new_faces, rounds.rounds,
                              r.statistics.splits, r.statistics.collapses, r.statistics.flips, *volume_note,
                              report.degraded_left);
  return std::move(r.mesh);
}

std::string describe_change(const TopologyCount& before, const TopologyCount& after)
{
  std::string s = fmt::format("components {} → {}, genus {} → {}", before.components, after.components, before.genus,
                              after.genus);
  if (before.boundary_loops != after.boundary_loops)
    s += fmt::format(", boundary loops {} → {}", before.boundary_loops, after.boundary_loops);
  return s;
}

//! The faces that have a vertex of `vertices` as a corner, ascending (vertices out of range skipped).
std::vector<int> faces_around(const Mesh& mesh, const std::vector<int>& vertices)
{
  std::vector<int> faces;
  for (int v : vertices) {
    if (v < 0 || v >= static_cast<int>(mesh.n_vertices()))
      continue;
    for (const Mesh::FaceHandle f : mesh.vf_range(mesh.vertex_handle(static_cast<unsigned>(v))))
      faces.push_back(f.idx());
  }
  std::sort(faces.begin(), faces.end()); // not std::ranges: clang with GCC 12's library rejects ranges::unique
  faces.erase(std::unique(faces.begin(), faces.end()), faces.end());
  return faces;
}

//! The largest share of the surface's faces a remeshing around a failed step takes. It is the last
//! resort before the whole pipeline, which on the surfaces where steps fail so (thin CAD parts) is
//! often refused: a patch of up to half the surface still keeps the other half bit for bit.
constexpr double kFailedStepPatchShare = 0.5;

//! A step that no τ makes acceptable fails at a few elements: a sliver or a needle whose triangle
//! turns over, or whose vertex moves beyond the displacement bound, whatever the step. Remesh the
//! region around the vertices where it failed (their stars and one ring more, at most
//! kFailedStepPatchShare of the surface) and give it back its volume. One ring, not the
//! kLocalRemeshRings of worn regions: on a thin CAD plate three rings reach round its sharp rim,
//! whose remeshing crosses the other side (the test's plate: 10 pairs), where one ring does not.
//! The result is taken when it keeps the topology and crosses itself in no more face pairs than
//! the surface did; else the caller runs the whole pipeline, as before (`fallback` says why). On a
//! CAD part the whole pipeline is often refused (it would cut thin walls the flow has not closed),
//! which left the step with no surface to go on.
std::optional<Mesh> remesh_where_step_failed(const Mesh& mesh, const std::vector<int>& failed,
                                             const RetriangulationSchedule& s, IntersectionWatch& watch,
                                             RetriangulationReport& report, std::string& fallback)
{
  Stopwatch stopwatch;
  const std::vector<int> faces = faces_around(mesh, failed);
  if (faces.empty())
    return std::nullopt;
  const std::size_t pairs_before = watch.count(mesh);
  LocalRemeshResult r;
  try {
    const RetriangulationOptions& o = s.pipeline;
    r = remesh_locally(mesh, faces, degraded_elements(mesh, s).targets,
                       {.edge_length = o.edge_length, .iterations = o.remesh_iterations, .rings = 1,
                        .curved_projection = o.curved_projection,
                        .crease_angle_deg = o.crease_angle_deg,
                        .max_patch_share = kFailedStepPatchShare,
                        .area_weighted_relaxation = o.graded_remeshing});
  } catch (const InvalidMesh& e) {
    fallback = fmt::format("the remeshing around the {} vertices where the step failed failed ({}), so the whole "
                           "pipeline ran; ", failed.size(), e.what());
    return std::nullopt;
  }
  report.pipeline_seconds.remesh = stopwatch.restart();
  if (r.declined) {
    fallback = fmt::format("the region around the {} vertices where the step failed holds {} of the {} faces, more "
                           "than a local remeshing takes, so the whole pipeline ran; ",
                           failed.size(), r.patch_faces, mesh.n_faces());
    return std::nullopt;
  }
  const TopologyCount before = count_topology(mesh), after = count_topology(r.mesh);
  if (!(before == after)) {
    fallback = fmt::format("the remeshing around the {} vertices where the step failed would change the topology "
                           "({}), so the whole pipeline ran; ", failed.size(), describe_change(before, after));
    return std::nullopt;
  }
  const std::optional<std::string> volume_note =
      s.restore_volume
          ? restore_local_volume(mesh, r, report,
                                 fmt::format("the remeshing around the {} vertices where the step failed", failed.size()),
                                 fallback)
          : std::string{};
  if (!volume_note)
    return std::nullopt;
  report.volume_seconds = stopwatch.restart();
  SurfaceCount counted = count_surface(r.mesh, s, watch);
  report.pipeline_seconds.intersections = stopwatch.seconds();
  if (counted.pairs > pairs_before) {
    fallback = fmt::format("the remeshing around the {} vertices where the step failed left {} intersecting face "
                           "pairs (the surface had {}), so the whole pipeline ran; ",
                           failed.size(), counted.pairs, pairs_before);
    report.measures = {}; // of a surface given up
    return std::nullopt;
  }
  report.remeshed = report.local = true;
  report.degraded_left = counted.degraded_failure ? degraded_elements(mesh, s).total() : counted.degraded.total();
  report.measures.before = before;
  report.measures.after = after;
  report.measures.faces_before = static_cast<long>(mesh.n_faces());
  report.measures.faces_after = static_cast<long>(r.mesh.n_faces());
  report.measures.faces_rebuilt = r.patch_faces;
  report.detail = fmt::format("no step could be taken: local remeshing around the {} vertices where it failed, {} "
                              "faces in {} patches into {} ({} splits, {} collapses, {} flips){}; {} degraded "
                              "elements left",
                              failed.size(), r.patch_faces, r.patches, r.new_faces, r.statistics.splits,
                              r.statistics.collapses, r.statistics.flips, *volume_note, report.degraded_left);
  return std::move(r.mesh);
}

//! Whether the change from `before` to `after` is only stage 6's clean-up: whole components below
//! the minimum size dropped as debris (a choice the user makes with min_component_faces, whose
//! volume the run accounts for), no other component split, fused, or gained or lost a handle or a
//! boundary loop beyond what the dropped ones held.
bool only_debris_dropped(const TopologyCount& before, const TopologyCount& after, const RetriangulationResult& r)
{
  return r.dropped_components > 0 && after.components + r.dropped_components == before.components &&
         after.genus <= before.genus && after.boundary_loops <= before.boundary_loops;
}

//! The patch radius, in ℓ, of the surgery tried first where a re-triangulation would change the
//! topology at a crossing, and the attempts, each at twice the last radius: on CGAL's elephant.off
//! at t = 3.5e-9 the patch of ½ ℓ left the rebuild nothing inside its cut, and that of 1 ℓ (206
//! faces) undid the fold that the surgery's usual 3 ℓ patch (1023 faces), which took in the whole
//! girth of the trunk, cut through.
constexpr double kFoldPatchRadius = 0.5;
constexpr int kFoldAttempts = 2;

//! The largest relative change of the material volume (debris included) that a re-triangulation
//! at crossings may make before each body is given its volume back. The validation's surgeries
//! change it by at most 7·10⁻⁴ and the corpus's by 10⁻²; a rebuild that filled a thin bowl solid
//! (CGAL's turbine.off) by 0.89.
constexpr double kMaxVolumeChangeAtCrossing = 0.05;

//! Marks `report` refused for `reason`, the surface kept as it was: `what` (for events.log) with
//! the degraded elements the surface keeps.
void refuse(RetriangulationReport& report, RefusalReason reason, const Mesh& mesh, const RetriangulationSchedule& s,
            const std::string& what)
{
  report.refused = true;
  report.refusal = reason;
  report.degraded_left = degraded_elements(mesh, s).total();
  report.detail = fmt::format("{}; {} degraded elements left", what, report.degraded_left);
}

//! The narrowest neck or gap within 2 ℓ of the crossings (crossing_width.h), and how it was measured.
struct CrossingSize {
  double size = 0;
  std::string text; //!< for events.log
};

//! The size at which the flow closed the neck or gap that crossed: measured as the step found it
//! when the context gives the step's start (on the crossed surface the walls have already passed
//! through each other), else before the re-triangulation. Infinite without crossings (only the
//! paper's pipeline, refinement_rounds = 0, changes topology there).
CrossingSize crossing_size(const Mesh& mesh, const std::vector<FacePair>& crossings, double ell,
                           const RetriangulationContext& context)
{
  if (context.remeshed_across_gaps && !crossings.empty()) {
    const double before = context.remeshed_across_gaps->width;
    return {before, fmt::format("the narrowest neck or gap within 2 ℓ of them {:.3g} = {:.3g} ℓ before the "
                                "remeshing that crossed there (the last resort: narrower than any remeshing of the "
                                "run resolves)",
                                before, before / ell)};
  }
  const double width = crossings.empty() ? std::numeric_limits<double>::infinity() : crossing_width(mesh, crossings, ell);
  if (context.step_start && !crossings.empty()) {
    Mesh start = mesh;
    set_vertex_positions(start, *context.step_start);
    const double at_start = crossing_width(start, crossings, ell);
    return {at_start, fmt::format("the narrowest neck or gap within 2 ℓ of them {:.3g} = {:.3g} ℓ at the start of the "
                                  "step that crossed ({:.3g} ℓ after it)",
                                  at_start, at_start / ell, width / ell)};
  }
  return {width, fmt::format("the narrowest neck or gap within 2 ℓ of them {:.3g} = {:.3g} ℓ before the "
                             "re-triangulation",
                             width, width / ell)};
}

//! Where the surface crosses itself and every rebuild was refused or failed (`report`, refused):
//! the crossings' patches capped instead (capped_surgery, local_surgery.h), taken when the change
//! of topology it makes is located at the crossings (explain_topology_change). Otherwise the
//! surface keeps its triangles and the crossing, as before, and the report says why capping did
//! not help. The run would go on crossed, and a crossing left in place grows step by step until no
//! step can be taken (CGAL's elk.off and turbine.off ended so, with exit 3).
void cap_crossings_instead(Mesh& mesh, const std::vector<FacePair>& crossings, const std::string& reason,
                           const RetriangulationSchedule& s, const RetriangulationContext& context,
                           RetriangulationReport& report)
{
  const double ell = s.pipeline.edge_length;
  const LocalSurgery capped = capped_surgery(mesh, crossings, s.pipeline, {.patch_radius = kFoldPatchRadius});
  if (!capped.result) {
    report.detail += fmt::format("; capping the crossings instead failed ({})", capped.failure);
    return;
  }
  RetriangulationResult r = *capped.result;
  const TopologyCount before = count_topology(mesh), after = count_topology(r.mesh);
  std::string topology_note;
  RetriangulationMeasures measured;
  measured.crossing_pairs = static_cast<long>(crossings.size());
  measured.before = before;
  measured.after = after;
  measured.faces_before = static_cast<long>(mesh.n_faces());
  measured.faces_after = static_cast<long>(r.mesh.n_faces());
  measured.faces_rebuilt = r.patch_faces;
  if (!(before == after) && !only_debris_dropped(before, after, r)) {
    const TopologyGuardVerdict located = explain_topology_change(
        mesh, r.mesh, crossings, ell,
        {.min_faces = s.pipeline.min_component_faces, .min_thickness = s.pipeline.min_component_thickness * ell});
    if (!located.explained) {
      report.detail += fmt::format("; capping the crossings instead would change the topology ({}) beyond them ({})",
                                   describe_change(before, after), located.reason);
      return;
    }
    const CrossingSize width = crossing_size(mesh, crossings, ell, context);
    measured.crossing_size = width.size;
    topology_note = fmt::format("; topology changed ({}) where the flow's surface crossed itself ({} face pairs, {})",
                                describe_change(before, after), crossings.size(), width.text);
  }
  const std::string refusal{refusal_name(report.refusal)};
  report = RetriangulationReport{.check_seconds = report.check_seconds, .pipeline_seconds = report.pipeline_seconds};
  report.measures = measured;
  Stopwatch volume;
  const std::string volume_note =
      s.restore_volume ? restore_volume(volume_source(mesh, context), r.mesh, report.measures) : std::string{};
  report.volume_seconds = volume.seconds();
  report.surgery = true;
  report.split = r.components_after > r.components_before;
  report.cleaned = r.dropped_components > 0;
  report.degraded_left = degraded_elements(r.mesh, s).total();
  report.detail = fmt::format("{}: every rebuild was refused or failed ({}), so the crossings were capped: a patch of "
                              "{} faces within {:.3g} ℓ of them, {} cut loops capped (Liepa){}{}; {} degraded elements left",
                              reason, refusal, r.patch_faces, capped.patch_radius / ell, r.filled_holes, topology_note,
                              volume_note, report.degraded_left);
  mesh = std::move(r.mesh);
}

//! Of `wall`, the seconds of a hook call, those that none of the report's parts counts: the local
//! surgeries tried (and declined), the measures that judge a topology change, the stages of a
//! pipeline that failed (RetriangulationReport::other_seconds).
double unreported_seconds(const RetriangulationReport& r, double wall)
{
  const RetriangulationResult::Seconds& p = r.pipeline_seconds;
  const double counted = r.check_seconds + r.volume_seconds + p.merge + p.remesh + p.intersections + p.normals +
                         p.reconstruction + p.holes + p.components - p.side_by_side;
  return std::max(0.0, wall - counted);
}

} // namespace

std::string_view refusal_name(RefusalReason reason)
{
  switch (reason) {
  case RefusalReason::none: return "";
  case RefusalReason::topology_without_crossing: return "topology-without-crossing";
  case RefusalReason::remeshing_crossed: return "remeshing-crossed";
  case RefusalReason::topology_beyond_crossings: return "topology-beyond-crossings";
  case RefusalReason::nothing_kept: return "nothing-kept";
  case RefusalReason::volume_not_kept: return "volume-not-kept";
  }
  return "unknown";
}

namespace {

//! The looks the last resort takes at most while its rebuild still crosses itself.
constexpr int kLastResortLooks = 3;

//! The flow's last resort (RetriangulationContext::close_unresolved_gaps): `report`, a refusal for
//! stage 1's own crossings, is replaced by what `look` makes of `crossed`, the remeshing it refused,
//! taken as the flow's crossing, when each of its crossings lies where `mesh` is narrower than the
//! finest edge a refinement makes: a gap or a neck the flow closed below anything the run resolves,
//! which no remeshing separates and which blocks the step (CGAL's turbine.off, two walls 0.006 ℓ
//! apart, and femur.off, a void 0.02 ℓ thick, stopped with exit 3 so). Otherwise, or when that look
//! changes nothing or is refused too, the refusal stands and its detail says why.
void close_unresolved_gaps(Mesh& mesh, CrossedRemeshing crossed, const RetriangulationSchedule& schedule,
                           const RetriangulationContext& context, RetriangulationReport& report,
                           const RetriangulationHook& look)
{
  const double ell = schedule.pipeline.edge_length;
  const double finest = finest_refinement_edge(schedule.pipeline, ell);
  const std::vector<double> widths = widths_where_remeshing_crossed(mesh, crossed.mesh, crossed.pairs, ell);
  const double widest = widths.empty() ? std::numeric_limits<double>::infinity()
                                       : *std::max_element(widths.begin(), widths.end());
  if (!(widest <= finest)) {
    report.detail += fmt::format("; not taken as the flow's crossing: the remeshing crossed where the surface is "
                                 "{:.3g} ℓ wide, which a finer remeshing would resolve (finest edge {:.3g} ℓ)",
                                 widest / ell, finest / ell);
    return;
  }
  RetriangulationContext taken = context;
  taken.force = false;
  taken.close_unresolved_gaps = false;
  taken.step_start = nullptr;
  taken.failed_vertices.clear();
  taken.remeshed_across_gaps = RetriangulationContext::Remeshed{.from = &mesh, .width = widest};
  Mesh surface = std::move(crossed.mesh);
  RetriangulationReport second = look(surface, taken);
  // A rebuild of sheets this close can cross itself again; the looks go on (as the run's next
  // look would) while it does, and a surface left crossing is not taken.
  for (int again = 1; !second.refused && second.changed() && again < kLastResortLooks &&
                      !self_intersections(surface).empty();
       ++again) {
    RetriangulationReport next = look(surface, taken);
    second.refused = next.refused;
    second.refusal = next.refusal;
    second.remeshed = second.remeshed || next.remeshed;
    second.surgery = second.surgery || next.surgery;
    second.split = second.split || next.split;
    second.merged = second.merged || next.merged;
    second.cleaned = second.cleaned || next.cleaned;
    second.detail += fmt::format("; crossing itself still, again: {}", next.detail);
    second.degraded_left = next.degraded_left;
    second.measures.after = next.measures.after;
    second.measures.faces_after = next.measures.faces_after;
    // Each look gives back the volumes of the surface first remeshed, so the last one's count
    // what was dropped in all.
    second.measures.debris_volume = next.measures.debris_volume;
    second.measures.volume_restored = next.measures.volume_restored;
    if (!std::isnan(next.measures.crossing_size))
      second.measures.crossing_size = next.measures.crossing_size;
  }
  if (second.refused || !second.changed() || !self_intersections(surface).empty()) {
    report.detail += fmt::format("; taken as the flow's crossing ({} face pairs where the surface was at most "
                                 "{:.3g} ℓ wide), its re-triangulation did not help: {}",
                                 crossed.pairs.size(), widest / ell, second.detail);
    return;
  }
  second.detail = fmt::format("the last resort: stage 1 crossed itself in {} face pairs where the surface was at most "
                              "{:.3g} ℓ wide, below the finest edge {:.3g} ℓ, so the crossing is the flow's: {}",
                              crossed.pairs.size(), widest / ell, finest / ell, second.detail);
  // The refused pipeline's seconds count with the ones it handed on.
  second.check_seconds += report.check_seconds;
  second.volume_seconds += report.volume_seconds;
  second.pipeline_seconds.add_stages(report.pipeline_seconds);
  second.pipeline_seconds.side_by_side += report.pipeline_seconds.side_by_side;
  mesh = std::move(surface);
  report = std::move(second);
}

} // namespace

RetriangulationHook make_retriangulation_hook(const RetriangulationSchedule& schedule)
{
  if (!(schedule.pipeline.edge_length > 0))
    throw InvalidParameter("the re-triangulation hook needs a resolved target edge length (> 0)");
  auto watch = std::make_shared<IntersectionWatch>();
  // `crossed`, when given, gets the remeshing that a refusal for its own crossings (remeshing_crossed)
  // did not keep.
  const auto look = [schedule, watch](Mesh& mesh, const RetriangulationContext& context,
                                      std::optional<CrossedRemeshing>* crossed) {
    RetriangulationReport report;
    if (!context.force && !context.remeshed_across_gaps && context.step % schedule.every != 0)
      return report;
    Stopwatch stopwatch;
    Verdict verdict;
    if (context.force)
      verdict.reason = "no step could be taken";
    else
      verdict = look_at_surface(mesh, schedule, context.tolerated_degraded, *watch);
    report.check_seconds = stopwatch.restart();
    if (verdict.reason.empty())
      return report;
    if (context.changing)
      context.changing();
    // A rebuild refused or failed where the surface crosses itself: the crossings capped instead.
    const auto capped_if_crossed = [&](RetriangulationReport& refused) {
      if (verdict.intersecting && verdict.watched && schedule.local_surgery && schedule.pipeline.refinement_rounds > 0)
        cap_crossings_instead(mesh, watch->pairs(), verdict.reason, schedule, context, refused);
      return refused;
    };
    std::string fallback;
    if (context.force && schedule.local && schedule.pipeline.remesh_iterations > 0 && !context.failed_vertices.empty()) {
      if (std::optional<Mesh> remeshed =
              remesh_where_step_failed(mesh, context.failed_vertices, schedule, *watch, report, fallback)) {
        mesh = std::move(*remeshed);
        return report;
      }
    }
    if (verdict.local) {
      if (std::optional<Mesh> remeshed = remesh_degraded_region(mesh, verdict, schedule, *watch, report, fallback)) {
        mesh = std::move(*remeshed);
        return report;
      }
    }
    // At a crossing, the surgery around it first (the watch's pairs are this surface's).
    std::optional<RetriangulationResult> surgery;
    if (schedule.local_surgery && verdict.intersecting) {
      LocalSurgery attempt = local_surgery(mesh, watch->pairs(), schedule.pipeline);
      surgery = std::move(attempt.result);
      if (!surgery)
        fallback = fmt::format("the local surgery declined or failed ({}), so the whole pipeline ran; ", attempt.failure);
    }
    // The watch's pairs are this surface's unless a local remeshing gave it another one to count;
    // so are the look's curvature targets, found when it does not intersect.
    const bool pairs_known = verdict.watched;
    // A pipeline that leaves no surface to keep (every component debris, a rebuild that is not a
    // valid surface) or whose stage refuses what it is given (fewer points than a neighbourhood).
    const auto nothing_kept = [&](const char* why) {
      refuse(report, RefusalReason::nothing_kept, mesh, schedule,
             fmt::format("{}: {}refused: the re-triangulation left no surface to keep ({}), so the surface "
                         "keeps its triangles",
                         verdict.reason, fallback, why));
      return capped_if_crossed(report);
    };
    RetriangulationResult r;
    try {
      r = surgery       ? std::move(*surgery)
          : pairs_known ? retriangulate(mesh, schedule.pipeline, watch->pairs(), verdict.degraded.targets)
                        : retriangulate(mesh, schedule.pipeline);
    } catch (const InvalidMesh& e) {
      return nothing_kept(e.what());
    } catch (const InvalidParameter& e) {
      return nothing_kept(e.what());
    }
    const RetriangulationResult::Seconds local = report.pipeline_seconds; // of a local remeshing given up
    report.pipeline_seconds = r.seconds;
    report.pipeline_seconds.remesh += local.remesh;
    report.pipeline_seconds.intersections += local.intersections;
    stopwatch.restart();
    // A topology change is the flow's only where its sheets crossed (a neck pinched through, a gap
    // closed) and the crossing cannot be undone without it. Anywhere else it is the pipeline's (a
    // remeshing or a rebuild that tore a thin part), and refused.
    const TopologyCount topology_before = count_topology(mesh), topology_after = count_topology(r.mesh);
    RetriangulationMeasures& measured = report.measures;
    measured.crossing_pairs = verdict.pairs;
    measured.before = topology_before;
    measured.after = topology_after;
    measured.faces_before = static_cast<long>(mesh.n_faces());
    measured.faces_after = static_cast<long>(r.mesh.n_faces());
    // A local surgery rebuilt its patch; the whole pipeline, every face it remeshed or rebuilt.
    measured.faces_rebuilt = r.patch_faces > 0 ? r.patch_faces : measured.faces_before;
    std::string topology_note;
    if (!(topology_before == topology_after) && !only_debris_dropped(topology_before, topology_after, r)) {
      const std::vector<FacePair> crossings =
          verdict.intersecting && verdict.watched ? watch->pairs() : self_intersections(mesh);
      // refinement_rounds = 0 asks for the paper's pipeline, whose remeshing may make a pinch's
      // crossing itself: its change is then taken as it comes.
      if (crossings.empty() && schedule.pipeline.refinement_rounds > 0) {
        refuse(report, RefusalReason::topology_without_crossing, mesh, schedule,
               fmt::format("{}: {}{}; refused: it would change the topology ({}) where the surface does not "
                           "cross itself, so the surface keeps its triangles",
                           verdict.reason, fallback, retriangulation_summary(r),
                           describe_change(topology_before, topology_after)));
        return report;
      }
      // Where it crossed, the change is the flow's only if the crossing needs it: a surgery in a
      // small patch around the crossings is tried first, and when it undoes them with the topology
      // kept, the crossing was a fold of a few triangles in a part as thick as ever, and the change
      // the wider rebuild made is the pipeline's (CGAL's elephant.off lost a handle so at
      // t = 3.5e-9: its trunk, about 1.1 ℓ thick, cut through by a rebuild of radius 3 ℓ). A neck
      // drawn through its axis or a gap closed cannot be undone so: cutting out the crossing walls
      // parts them whatever the patch.
      const double ell = schedule.pipeline.edge_length;
      const CrossingSize width = crossing_size(mesh, crossings, ell, context);
      measured.crossing_pairs = static_cast<long>(crossings.size());
      measured.crossing_size = width.size;
      const std::string& measured_width = width.text;
      std::optional<LocalSurgery> fold;
      if (schedule.pipeline.refinement_rounds > 0 && !crossings.empty())
        fold = local_surgery(mesh, crossings, schedule.pipeline,
                             {.patch_radius = kFoldPatchRadius, .attempts = kFoldAttempts});
      if (fold && fold->result && count_topology(fold->result->mesh) == topology_before) {
        fallback += fmt::format("the rebuild would change the topology ({}) at {} face pairs crossed ({}), but a "
                                "surgery within {:.3g} ℓ of them undoes them keeping it: a fold, not a neck or gap the "
                                "flow closed; ",
                                describe_change(topology_before, topology_after), crossings.size(), measured_width,
                                fold->patch_radius / ell);
        r = std::move(*fold->result);
        measured.after = topology_before;
        measured.faces_after = static_cast<long>(r.mesh.n_faces());
        measured.faces_rebuilt = r.patch_faces;
        measured.crossing_size = std::numeric_limits<double>::quiet_NaN();
      } else {
        // The change must also be located at the crossings and no larger than they explain: a
        // remeshing or a rebuild that tears a thin part or seals handles elsewhere in the same pass
        // is the pipeline's (CGAL's turbine.off went from genus 11 to 0 with 4 pairs crossed).
        if (schedule.pipeline.refinement_rounds > 0) {
          if (const TopologyGuardVerdict located = explain_topology_change(
                  mesh, r.mesh, crossings, ell,
                  {.min_faces = schedule.pipeline.min_component_faces,
                   .min_thickness = schedule.pipeline.min_component_thickness * ell});
              !located.explained) {
            refuse(report, RefusalReason::topology_beyond_crossings, mesh, schedule,
                   fmt::format("{}: {}{}; refused: it would change the topology ({}) beyond what the {} face "
                               "pairs crossed explain ({}), so the surface keeps its triangles",
                               verdict.reason, fallback, retriangulation_summary(r),
                               describe_change(topology_before, topology_after), crossings.size(),
                               located.reason));
            return capped_if_crossed(report);
          }
        }
        const std::string needed =
            !fold                ? std::string{}
            : fold->result       ? fmt::format("; a surgery within {:.3g} ℓ of them changes it too", fold->patch_radius / ell)
                                 : fmt::format("; no surgery within {:.3g} ℓ of them: {}", kFoldPatchRadius * 2,
                                               fold->failure);
        topology_note = fmt::format("; topology changed ({}) where the flow's surface crossed itself ({} face pairs, {}{})",
                                    describe_change(topology_before, topology_after), crossings.size(), measured_width,
                                    needed);
      }
    }
    if (r.remeshing_refused && !r.rebuilt && r.dropped_components == 0 && r.merged_components == 0) {
      // Stage 1 refused and nothing else to do: the surface keeps its triangles, and the run says so.
      if (crossed)
        *crossed = std::move(r.crossed_remeshing);
      refuse(report, RefusalReason::remeshing_crossed, mesh, schedule,
             fmt::format("{}: {}{}; refused: nothing was rebuilt, so the surface keeps its triangles",
                         verdict.reason, fallback, retriangulation_summary(r)));
      return capped_if_crossed(report);
    }
    const double volume_before = verdict.intersecting ? material_volume(mesh) : 0;
    const double rebuilt_volume = verdict.intersecting ? material_volume(r.mesh) : 0;
    std::string volume_note;
    try {
      volume_note =
          schedule.restore_volume ? restore_volume(volume_source(mesh, context), r.mesh, report.measures) : std::string{};
    } catch (const InvalidMesh& e) {
      report.measures = {};
      return nothing_kept(e.what());
    }
    report.volume_seconds += stopwatch.seconds();
    // Bodies that overlapped and were joined lose the overlap's volume, which they counted twice.
    if (verdict.intersecting && schedule.pipeline.refinement_rounds > 0 && r.merged_components == 0 &&
        std::abs(rebuilt_volume + report.measures.debris_volume - volume_before) >
            kMaxVolumeChangeAtCrossing * std::abs(volume_before)) {
      refuse(report, RefusalReason::volume_not_kept, mesh, schedule,
             fmt::format("{}: {}{}{}; refused: the rebuild changed the material volume from {:.6g} to {:.6g} "
                         "(debris included), more than a surgery at the crossings does, so the surface keeps "
                         "its triangles",
                         verdict.reason, fallback, retriangulation_summary(r), topology_note, volume_before,
                         rebuilt_volume + report.measures.debris_volume));
      return capped_if_crossed(report);
    }
    report.remeshed = schedule.pipeline.remesh_iterations > 0 && !r.remeshing_refused;
    report.surgery = r.rebuilt;
    report.split = r.components_after > r.components_before - r.merged_components;
    report.merged = r.merged_components > 0;
    report.cleaned = r.dropped_components > 0;
    report.degraded_left = degraded_elements(r.mesh, schedule).total();
    report.detail = fmt::format("{}: {}{}{}{}; {} degraded elements left", verdict.reason, fallback,
                                retriangulation_summary(r), topology_note, volume_note, report.degraded_left);
    mesh = std::move(r.mesh);
    return report;
  };
  return [look, schedule](Mesh& mesh, const RetriangulationContext& context) {
    const Stopwatch whole;
    std::optional<CrossedRemeshing> crossed;
    RetriangulationReport report = look(mesh, context, context.close_unresolved_gaps ? &crossed : nullptr);
    if (crossed)
      close_unresolved_gaps(mesh, std::move(*crossed), schedule, context, report,
                            [&look](Mesh& m, const RetriangulationContext& c) { return look(m, c, nullptr); });
    report.other_seconds = unreported_seconds(report, whole.seconds());
    return report;
  };
}

} // namespace sdflow
