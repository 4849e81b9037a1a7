#pragma once
//! \file pipeline.h
//! \brief The re-triangulation of paper §3.2.1 (with Appendix B), composed from the toolbox:
//! 0. components that intersect each other are merged: bodies into the boundary of their union, a
//!    bubble opened through the wall or sheet it reached (surface_union.h, merge_touching_surfaces);
//! 1. isotropic remeshing to the target edge length ℓ, finer where the curvature is large (remesh/remesh.h);
//! 2. the self-intersecting faces are removed, then the vertices left without a face (remove_intersections.h);
//! 3. jet normals oriented by a minimum spanning tree; inconsistently oriented points are dropped (reconstruct/point_normals.h);
//! 4. the surface is rebuilt from the oriented points by advancing front (reconstruct/advancing_front.h);
//!    when that joins two pieces stage 2 left apart (a bridge across the cut at a pinch), each piece
//!    is rebuilt on its own (reconstruct/reconstruct_apart.h);
//! 5. holes shorter than a bound are filled (reconstruct/holes.h);
//!    with a fixed boundary (keep_boundary), stages 2–5 keep a band of faces along it and rebuild
//!    the surface inside the band (fixed_rim.h);
//! 6. debris is dropped: components with fewer triangles than a bound, and closed components that
//!    enclose almost no volume (a collapsed double sheet), both before and after stage 5 (components.h).
//! Stages 3–5 run only when stage 2 found something to remove (or when asked to always run):
//! on a surface without singularities they would only re-triangulate the same points.

#include "sdflow/geometry/anisotropy.h"
#include "sdflow/mesh.h"
#include "sdflow/parameter_range.h"
#include "sdflow/reconstruct/advancing_front.h"
#include "sdflow/reconstruct/holes.h"
#include "sdflow/reconstruct/point_normals.h"
#include "sdflow/remesh/remesh.h"
#include "sdflow/spatial/intersect.h"

#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace sdflow {

struct RetriangulationOptions {
  //! ℓ, the target edge length of stage 1; 0 takes the input's mean edge length.
  double edge_length = 0;
  //! Rounds of stage 1; 0 skips it.
  int remesh_iterations = 3;
  //! Stage 1 adapts ℓ to the curvature (remesh.h, radius_targets): this many edges per radius of
  //! curvature where that asks for edges shorter than ℓ, so a closing neck or hole stays resolved;
  //! 0 remeshes to the uniform ℓ (the paper's practice).
  double edges_per_radius = 4;
  //! The floor of the adapted edge length, as a fraction of ℓ (in (0, 1]).
  double min_edge_fraction = 0.25;
  //! The γ of an anisotropic surface energy, set by a run that has one: stage 1 then adapts ℓ to
  //! the weighted curvature of γ instead of the geometric one (curvature_targets.h). Empty: the
  //! geometric curvature (radius_targets).
  std::shared_ptr<const Anisotropy> anisotropy;
  //! Stage 1 projects new vertices onto the smooth surface the triangles sample, not onto the flat
  //! triangles (remesh.h, RemeshOptions::curved_projection), so a remeshing does not thin a neck;
  //! onto the flat ones when the surface intersects itself (no smooth surface to lift onto there).
  bool curved_projection = true;
  //! Stage 1 keeps the creases, edges turning by more than this angle (degrees) between flat
  //! triangles (remesh.h, RemeshOptions::crease_angle_deg), where the flow has not rounded them
  //! yet: smoothed across, a crease reads as a curvature the next remeshing resolves with finer
  //! edges, and so on at every one. None are kept where the surface crosses itself (the turns
  //! there are the crossing's). 0 (the default) keeps none; 45 suits CAD parts (docs/design.md §3
  //! says what it gains and costs).
  double crease_angle_deg = 0;
  //! Graded remeshing (docs/design.md §3, stage 1): the curvature targets grow by at most
  //! kCurvatureTargetGrowth per unit length (retri/curvature_targets.h) and stage 1 and the local
  //! remeshings relax by area / target² (RemeshOptions::area_weighted_relaxation). Where the targets
  //! drop fourfold at a neck or a crease between particles, the default leaves slivers (the first
  //! remeshing of samples/compact_27: angles 0.9°–178°, 24% obtuse; graded: 10.9°–154°, 5.8%) and
  //! the first steps crawl; graded, that run reached t = 0.01 in 143 steps instead of 329, but
  //! t = 3 in 365 s instead of 280 (more vertices later on). Off by default until that is understood.
  bool graded_remeshing = false;
  //! The boundary loops stay as they are, vertex for vertex, as a flow with a fixed rim needs
  //! (flow/boundary_condition.h): stage 1 keeps their vertices (BoundaryMode::keep), and stages 2–5
  //! keep a band of faces along them and rebuild only the surface inside it (fixed_rim.h). Off,
  //! stage 1 remeshes them along the loops and the rebuild re-triangulates them.
  bool keep_boundary = false;
  //! With keep_boundary: stage 1 remeshes the boundary loops too, splitting, collapsing and sliding
  //! their vertices along the loops themselves (a loop in a plane stays in it exactly), and stages
  //! 2–5 keep the loops stage 1 left; no vertex of theirs is kept as a corner (a contact line is a
  //! curve in its plane: a kink a cut left is blunted). A contact line (flow/substrate_boundary.h)
  //! is resampled so; a fixed rim is not.
  bool resample_boundary = false;
  //! Stage 1 must not make a surface that does not cross itself cross (a thin part collapsed, two
  //! close sheets pulled through each other, a crease): stage 2 would cut it and the rebuild change
  //! the topology where the flow did not. Stage 1 is then done again with the targets there halved and
  //! kept below half the local thickness (spatial/local_thickness.h), never below half the finest edge
  //! min_edge_fraction · ℓ, up to this many times; if it still crosses there, or a round does not
  //! reduce the crossings, or a round would make more than 4 times the vertices of the first
  //! remeshing, it is refused: the surface keeps its triangles (stage 1 skipped).
  //! 0: the remeshing's own crossings are cut like the flow's (the paper's pipeline).
  int refinement_rounds = 2;
  //! Run stages 3–5 even when nothing intersects (the paper's "after every step" application).
  bool always_rebuild = false;
  PointNormalsOptions normals;
  ReconstructionOptions reconstruction;
  //! Stage 5 on or off.
  bool fill_holes = true;
  //! Holes whose boundary is longer than this stay open; 0: automatic, i.e. every hole of a
  //! closed input, and on an input with boundary only the loops shorter than half the shortest
  //! boundary loop after remeshing (the paper's bound, "a new hole is shorter than the true
  //! boundary", with a margin: a rebuilt true boundary comes out somewhat shorter).
  double max_hole_length = 0;
  //! Stage 6: components with fewer triangles are dropped (debris of a surgery).
  int min_component_faces = 16;
  //! Stage 6: closed components whose volume is below this fraction of ℓ times their area are
  //! dropped (a sphere of radius ℓ has 1/3).
  double min_component_thickness = 0.01;
};

//! Whether stage 1 keeps the boundary vertices where they are (keep_boundary without
//! resample_boundary): then the remeshing beside them aims no finer than their edges.
inline bool rim_kept_in_stage_one(const RetriangulationOptions& options)
{
  return options.keep_boundary && !options.resample_boundary;
}

//! The finest edge a refinement round of stage 1 aims at: half the sizing's finest edge,
//! min_edge_fraction · ℓ / 2 for the pipeline's ℓ `edge_length` (RetriangulationOptions::refinement_rounds).
//! A gap or a neck narrower than it is one no remeshing of the run resolves.
double finest_refinement_edge(const RetriangulationOptions& options, double edge_length);

//! A stage-1 remeshing refused because it crossed itself where its input did not: the surface it
//! made and its intersecting face pairs.
struct CrossedRemeshing {
  Mesh mesh;
  std::vector<FacePair> pairs;
};

//! What each stage did, and how long it took (seconds of wall time).
struct RetriangulationResult {
  Mesh mesh; //!< valid, closed components oriented outward, garbage-collected
  double edge_length = 0;
  int merged_components = 0;    //!< stage 0: components joined into others
  RemeshStatistics remesh;      //!< stage 1 (the remeshing kept)
  //! Stage 1: face pairs its first remeshing made cross away from the input's crossings (0: none).
  int remeshing_crossings = 0;
  int refinements = 0;            //!< stage 1: remeshings redone finer where they made crossings
  bool remeshing_refused = false; //!< stage 1 kept making crossings: skipped, the input's triangles kept
  //! Stage 1 refused: the last of its remeshings that crossed itself (none when none did), which a
  //! run's last resort may take as the flow's crossing (flow/retriangulation.h).
  std::optional<CrossedRemeshing> crossed_remeshing;
  long remeshed_vertices = 0;     //!< stage 1: vertices of the largest remeshing it made, its rounds included
  int intersecting_pairs = 0;   //!< stage 2
  int removed_faces = 0;        //!< stage 2
  bool rebuilt = false;         //!< stages 3–5 ran
  bool rim_kept = false;        //!< stages 2–5 kept a band along a fixed boundary and rebuilt inside it (fixed_rim.h)
  //! Stage 4 rebuilt each piece stage 2 left apart: rebuilt together, two were joined across a cut.
  bool rebuilt_apart = false;
  int removed_points = 0;       //!< stage 3: inconsistently oriented (local surgery: or crossed over)
  int unused_points = 0;        //!< stage 4: points no triangle uses
  int filled_holes = 0;         //!< stage 5
  //! Open components the rebuild returned turned over against the input, turned back
  //! (open_orientation.h); closed ones are oriented by validation.
  int turned_open_components = 0;
  int open_holes = 0;           //!< stage 5: boundary loops left open (true boundaries included)
  int components_before = 0;    //!< components of the input
  int components_after = 0;     //!< components of the result
  int dropped_components = 0;   //!< stage 6
  //! Stage 6: the signed volume of each closed component dropped (open ones enclose none).
  std::vector<double> dropped_volumes;
  //! The curvature-adapted edge lengths left sheets that cross, or nothing, after a rebuild: the
  //! result is the pipeline's with the uniform ℓ.
  bool uniform_fallback = false;
  //! Faces cut out and rebuilt by a local surgery (local_surgery.h); 0: the whole surface was.
  int patch_faces = 0;
  struct Seconds {
    double merge = 0, remesh = 0, intersections = 0, normals = 0, reconstruction = 0, holes = 0, components = 0;
    //! Of the stages above, the seconds two of them ran at once (stage 4's clean-up beside stage
    //! 2's search), which both count: their sum exceeds the wall time by this much.
    double side_by_side = 0;
    //! Add `other`'s seven stages (side_by_side apart) to these.
    void add_stages(const Seconds& other)
    {
      merge += other.merge;
      remesh += other.remesh;
      intersections += other.intersections;
      normals += other.normals;
      reconstruction += other.reconstruction;
      holes += other.holes;
      components += other.components;
    }
  } seconds;
};

//! The allowed values of the options a caller sets, stated here only: validate_retriangulation_options
//! checks them, and the run schema's [retriangulation] entries take them (run/schema_retriangulation.cpp).
struct RetriangulationRanges {
  ParameterRange edge_length{.min = 0};                          //!< 0: automatic
  ParameterRange remesh_iterations{.min = 0};                    //!< 0: no remeshing
  ParameterRange edges_per_radius{.min = 0};                     //!< 0: uniform ℓ
  ParameterRange min_edge_fraction{.min = 0, .max = 1, .min_open = true};
  ParameterRange crease_angle{.min = 0, .max = 180, .max_open = true}; //!< degrees; 0: no creases
  ParameterRange neighbours{.min = 6};                           //!< a degree-2 jet needs 6
  ParameterRange max_hole_length{.min = 0, .infinite_allowed = true}; //!< 0: automatic; ∞: every hole
  ParameterRange min_component_faces{.min = 1};
  ParameterRange min_component_thickness{.min = 0};
};
inline constexpr RetriangulationRanges retriangulation_ranges{};

//! Throws InvalidParameter for options out of retriangulation_ranges.
void validate_retriangulation_options(const RetriangulationOptions& options);

//! One line saying what a re-triangulation did (the operations of each stage that ran, the
//! components before and after), as runs write it to events.log.
std::string retriangulation_summary(const RetriangulationResult& result);

//! Re-triangulate `mesh` by the pipeline above. Throws InvalidParameter for options out of range,
//! InvalidMesh when nothing is left (every component dropped) or the result is not a valid mesh.
RetriangulationResult retriangulate(const Mesh& mesh, const RetriangulationOptions& options = {});

//! The same, for a caller that has found the self-intersections of `mesh` already (`crossings`,
//! as self_intersections(mesh) gives them; `mesh` without deleted faces) and, when `targets` is
//! not empty, stage 1's curvature targets too (curvature_targets(mesh, options, ℓ), as
//! degraded_elements finds them): stage 1 does not compute them again.
//! The result is the one retriangulate(mesh, options) gives.
RetriangulationResult retriangulate(const Mesh& mesh, const RetriangulationOptions& options,
                                    const std::vector<FacePair>& crossings, const std::vector<double>& targets = {});

} // namespace sdflow
