#pragma once
//! \file retriangulation.h
//! \brief The hook that re-triangulates a run's surface between steps (paper §3.2.1) when its
//! RetriangulationSchedule (below) says so. The paper chose the moments by hand or ran the
//! pipeline after every step; the schedule's triggers make the choice automatic.

#include "sdflow/geometry/topology.h"
#include "sdflow/mesh.h"
#include "sdflow/parameter_range.h"
#include "sdflow/retri/pipeline.h"

#include <functional>
#include <limits>
#include <optional>
#include <string>
#include <string_view>

namespace sdflow {

//! When a run re-triangulates: every `every` steps the surface is looked at, and
//! the pipeline of retri/pipeline.h runs when it intersects itself (a pinch-off, a hole sealing,
//! bodies touching), or every time with `always` (the paper's practice). When its triangles have
//! degraded (more than `degraded_fraction` of the triangle count are triangles with an angle below
//! `min_angle_deg` or edges outside [ℓ/r, r·ℓ] with r = `edge_ratio` and ℓ the local target of the
//! pipeline's curvature-adapted sizing, and more than the last re-triangulation left behind, by
//! more than `degraded_variation` of it), the
//! region around them is remeshed (`local`), or the whole pipeline runs.
struct RetriangulationSchedule {
  //! On by default: re-triangulation is what carries the method through topology changes. Off, a
  //! flow stops at the first self-intersection (intersection_guard.h).
  bool enabled = true;
  long every = 1;             //!< look at the surface after every k-th step (≥ 1)
  double min_angle_deg = 15;  //!< re-triangulate when a triangle's smallest angle is below this
  double edge_ratio = 2;      //!< ... or an edge is longer than r·ℓ or shorter than ℓ/r (r > 1)
  //! ... counting such triangles and edges: more than this fraction of the triangle count. The
  //! default 0 reacts to a single one: a thinning neck shows only a few, and without remeshing it
  //! stalls instead of pinching off. Elements the remesher could not fix are tolerated until more
  //! appear; larger values save remeshings on large surfaces.
  double degraded_fraction = 0;
  //! ... and more than the last re-triangulation left by more than this fraction of that count:
  //! how much the count a remeshing leaves varies from one remeshing of a surface to the next (on
  //! CGAL's fandisk_large.off five in a row left 6659, 6573, 6259, 5950 and 6242), so that
  //! thousands the remesher cannot fix at a CAD part's sharp edges do not call the whole pipeline
  //! after every step. From 20 left on, the margin is at least twice their square root, the scatter
  //! of such counts (flow/retriangulation.cpp, degraded_slack). Not a run parameter: 0 gives the
  //! rule before it, any increase calling it (the fixtures of tests made by such runs).
  double degraded_variation = 0.05;
  bool always = false;        //!< run the whole pipeline after every k-th step (the paper's practice)
  //! When only degraded elements call for it (nothing intersects), remesh just the regions around
  //! them (remesh/local_remesh.h) instead of running the whole pipeline; the whole pipeline still
  //! runs when that fails or the worn regions hold more than a tenth of the surface. Same outcomes
  //! and event times as the whole pipeline at a lower cost per remeshing (docs/design.md §3). Off
  //! in the paper's preset.
  bool local = true;
  //! When the surface intersects itself, do the pipeline's surgery only around the crossing
  //! (retri/local_surgery.h): same events and outcomes as the whole pipeline for a tenth of its
  //! cost (docs/design.md §3). The whole pipeline runs when it declines (components intersecting
  //! each other, a patch reaching a true boundary) or fails, with `always`, and when a step could
  //! not be taken. Off in the paper's preset.
  bool local_surgery = true;
  //! Give each component (or group of components that split or fused) back the material volume the
  //! re-triangulation took or added (flow/volume.h, restore_volumes_from).
  bool restore_volume = true;
  //! The pipeline; its ℓ (0 = automatic) is fixed when the run starts, to the initial surface's
  //! mean edge length, so that it stays the same for the whole run and its resumption.
  RetriangulationOptions pipeline;
};

//! The allowed values of a RetriangulationSchedule's numbers, stated here only: the flow's check
//! (validate_flow_options, flow_options.h) reads them and the run schema's `retriangulation.*`
//! entries take them (run/schema_retriangulation.cpp).
struct RetriangulationScheduleRanges {
  ParameterRange every{.min = 1};
  ParameterRange min_angle{.min = 0, .max = 60, .max_open = true};  //!< degrees
  ParameterRange edge_ratio{.min = 1, .min_open = true};
  ParameterRange degraded_fraction{.min = 0, .max = 1, .max_open = true};
};
inline constexpr RetriangulationScheduleRanges retriangulation_schedule_ranges{};

//! Where a re-triangulation hook is called: after step `step` reached `time`.
struct RetriangulationContext {
  long step = 0;
  double time = 0;
  //! Degraded elements (short or long edges, sharp triangles) that the last re-triangulation could
  //! not remove: the hook tolerates that many until more appear (kept in checkpoints).
  long tolerated_degraded = 0;
  //! Re-triangulate now, whatever the schedule says: the step from this surface could not be taken.
  bool force = false;
  //! If set, called once the hook has decided to change the surface, before it starts to (the flow
  //! then stops the next step's trial it took ahead, surface_diffusion.h).
  std::function<void()> changing;
  //! The positions at the start of the step that moved the surface here (same vertices), when the
  //! flow gives them: where a crossing's neck or gap is measured as it was before the flow closed it.
  const VertexVectors* step_start = nullptr;
  //! With `force`: the vertices where the step that could not be taken failed (a triangle turned
  //! over, a vertex moved beyond the displacement bound, at every τ). The hook remeshes around them
  //! alone first, and runs the whole pipeline only when that does not give a surface to go on from.
  std::vector<int> failed_vertices;
  //! With `force`: the flow's last resort before it stops (surface_diffusion.h). When the whole
  //! pipeline is refused because stage 1 kept making crossings of its own (remeshing_crossed), and
  //! each of them lies where the surface is narrower than the finest edge a refinement makes
  //! (finest_refinement_edge: a gap or neck the flow closed below anything the run resolves), the
  //! crossed remeshing is taken as the flow's crossing and re-triangulated as one; the change is
  //! logged with the widest of those widths, measured before the remeshing.
  bool close_unresolved_gaps = false;
  //! Set by that last resort on the crossed remeshing it hands on (a look whatever the schedule
  //! says): the surface it remeshed, whose volumes the outcome is given back, and the width logged
  //! as the trigger of a topology change there.
  struct Remeshed {
    const Mesh* from = nullptr;
    double width = 0;
  };
  std::optional<Remeshed> remeshed_across_gaps;
};

//! What a re-triangulation measured: what called for it and what came of it (the numbers of its
//! events, step_event.h).
struct RetriangulationMeasures {
  //! Face pairs in which the surface crossed itself before it: the flow's sheets meeting (0 when
  //! degraded elements or a step that could not be taken called for it).
  long crossing_pairs = 0;
  //! The narrowest neck or gap within 2 ℓ of those crossings (flow/crossing_width.h), measured when
  //! the topology changed there, on the surface at the start of the step that crossed when the
  //! context gives it (else on the crossed surface): the size at which the flow brought the change. For a
  //! substrate's change (flow/substrate_topology.h) the film's height above the plane or the gap
  //! between the contact lines that triggered it. NaN otherwise.
  double crossing_size = std::numeric_limits<double>::quiet_NaN();
  TopologyCount before, after; //!< the surface's topology before and after
  long faces_before = 0, faces_after = 0;
  //! Faces cut out and made anew: a local remeshing's or surgery's patches, else every face.
  long faces_rebuilt = 0;
  //! Relative change of the material volume that the volume restoration made (0: none ran).
  double volume_restored = 0;
  //! Σ material volume of the components dropped whole as debris, which no component was given
  //! back (VolumeRestoration::dropped_volumes; 0 without volume restoration).
  double debris_volume = 0;
};

//! Why a re-triangulation was refused and the surface kept as it was.
enum class RefusalReason {
  none,
  //! It would have changed the topology where the surface did not cross itself (no neck or gap
  //! of the flow had closed).
  topology_without_crossing,
  //! It would have changed the topology more than, or away from, what the regions where the
  //! surface crossed itself explain (flow/topology_guard.h).
  topology_beyond_crossings,
  //! Stage 1 kept making crossings of its own on a surface that did not cross itself, and nothing
  //! else was to be rebuilt: the re-triangulation did nothing (retri/pipeline.h).
  remeshing_crossed,
  //! The pipeline left no surface it could keep (every component dropped as debris, or a rebuild
  //! that is not a valid surface): the flow keeps each body's volume, so that is never its change.
  nothing_kept,
  //! Where the surface crossed itself, the rebuild changed the volume of the bodies it kept by more
  //! than a twentieth (before each was given its volume back): not a surgery at the crossings but
  //! a different body (CGAL's turbine.off, a thin bowl, was rebuilt solid, 1.9 times its volume).
  volume_not_kept,
};

//! The name events.log, metrics and Python use for `reason` ("topology-without-crossing", ...;
//! "" for none).
std::string_view refusal_name(RefusalReason reason);

//! What a re-triangulation hook did to the mesh (each flag becomes an event of the step's row).
struct RetriangulationReport {
  bool remeshed = false; //!< triangulation improved (same topology)
  bool local = false;    //!< ... only around the degraded elements (remesh/local_remesh.h)
  bool surgery = false;  //!< self-intersections removed and the surface rebuilt
  bool split = false;    //!< a component broke into several
  bool merged = false;   //!< components were joined
  //! components below the clean-up's size bounds were dropped as debris (retri/pipeline.h, stage 6)
  bool cleaned = false;
  bool touchdown = false; //!< a film reached its substrate and was cut there (substrate_topology.h)
  bool contact = false;   //!< two contact lines on the substrate met and were joined or cut
  //! The re-triangulation was refused and the surface kept as it was, for `refusal`.
  bool refused = false;
  RefusalReason refusal = RefusalReason::none;
  std::string detail;    //!< one line for events.log (also when `refused`)
  long degraded_left = -1; //!< degraded elements left by a re-triangulation (-1: none ran)
  double check_seconds = 0;  //!< wall time of the look at the surface (intersections, degraded elements)
  //! Of the pipeline's stages, when it ran; a local remeshing counts as `remesh`, and its check for
  //! self-intersections as `intersections`.
  RetriangulationResult::Seconds pipeline_seconds;
  double volume_seconds = 0; //!< of giving the components back their volume
  //! The rest of the call's wall time: local surgeries tried (and declined), the measures that
  //! judge a topology change, the stages of a pipeline that failed and was refused.
  double other_seconds = 0;
  RetriangulationMeasures measures; //!< when it ran (also when `refused`)
  bool changed() const { return remeshed || surgery || split || merged || cleaned || touchdown || contact; }
};

//! Called between steps; may change the mesh in place (positions and connectivity), returning what
//! it did. It must leave a valid mesh (no deleted elements, outward-oriented closed components) and
//! be deterministic for resumed runs to match uninterrupted ones.
using RetriangulationHook = std::function<RetriangulationReport(Mesh&, const RetriangulationContext&)>;

//! The hook a flow makes from its schedule (SurfaceDiffusion, surface_diffusion.h). The schedule is
//! checked with the flow's other options (validate_flow_options, against
//! retriangulation_schedule_ranges); `schedule.pipeline.edge_length` must be resolved (> 0). Deterministic: its only state is a cache of the self-intersection search
//! (refitted between steps), and what it reports in RetriangulationReport::degraded_left comes back
//! through the context (and the checkpoint), so a resumed run re-triangulates exactly as the original.
RetriangulationHook make_retriangulation_hook(const RetriangulationSchedule& schedule);

} // namespace sdflow
