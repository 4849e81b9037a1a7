#include "sdflow/retri/pipeline.h"

#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/soup.h"
#include "sdflow/io/validate.h"
#include "sdflow/log.h"
#include "sdflow/reconstruct/reconstruct_apart.h"
#include "sdflow/remesh/kept_boundary_sizing.h"
#include "sdflow/retri/components.h"
#include "sdflow/retri/curvature_targets.h"
#include "sdflow/retri/fixed_rim.h"
#include "sdflow/retri/open_orientation.h"
#include "sdflow/retri/remove_intersections.h"
#include "sdflow/retri/surface_union.h"
#include "sdflow/spatial/intersect.h"
#include "sdflow/spatial/local_thickness.h"
#include "sdflow/spatial/nearest_points.h"

#include <fmt/format.h>
#include <tbb/parallel_invoke.h>

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <exception>
#include <limits>
#include <optional>

namespace sdflow {
namespace {

using Clock = std::chrono::steady_clock;

double seconds_since(Clock::time_point start) { return std::chrono::duration<double>(Clock::now() - start).count(); }

} // namespace

void validate_retriangulation_options(const RetriangulationOptions& o)
{
  const RetriangulationRanges& r = retriangulation_ranges;
  if (!r.edge_length.contains(o.edge_length))
    throw InvalidParameter(fmt::format("re-triangulation: target edge length must be {} (0: automatic), got {}",
                                       r.edge_length.text(), o.edge_length));
  if (!r.remesh_iterations.contains(o.remesh_iterations))
    throw InvalidParameter(fmt::format("re-triangulation: remesh iterations must be {}, got {}",
                                       r.remesh_iterations.text(), o.remesh_iterations));
  if (!r.max_hole_length.contains(o.max_hole_length))
    throw InvalidParameter(fmt::format("re-triangulation: max hole length must be {} (0: automatic), got {}",
                                       r.max_hole_length.text(), o.max_hole_length));
  if (!r.neighbours.contains(o.normals.neighbours))
    throw InvalidParameter(fmt::format("re-triangulation: the jet normals need at least {} neighbours, got {}",
                                       r.neighbours.min, o.normals.neighbours));
  if (!r.min_component_thickness.contains(o.min_component_thickness))
    throw InvalidParameter(fmt::format("re-triangulation: min component thickness must be {}, got {}",
                                       r.min_component_thickness.text(), o.min_component_thickness));
  if (!r.edges_per_radius.contains(o.edges_per_radius))
    throw InvalidParameter(fmt::format("re-triangulation: edges per radius of curvature must be {} (0: uniform ℓ), "
                                       "got {}", r.edges_per_radius.text(), o.edges_per_radius));
  if (!r.min_edge_fraction.contains(o.min_edge_fraction))
    throw InvalidParameter(fmt::format("re-triangulation: the smallest edge fraction must be {}, got {}",
                                       r.min_edge_fraction.text(), o.min_edge_fraction));
  if (!r.crease_angle.contains(o.crease_angle_deg))
    throw InvalidParameter(fmt::format("re-triangulation: the crease angle must be {} degrees (0: no creases), got {}",
                                       r.crease_angle.text(), o.crease_angle_deg));
  if (!r.min_component_faces.contains(o.min_component_faces))
    throw InvalidParameter(fmt::format("re-triangulation: min component faces must be {}, got {}",
                                       r.min_component_faces.text(), o.min_component_faces));
}

namespace {

//! The bound for stage 5 (the paper's, with a margin): every hole of a closed surface, otherwise the
//! loops shorter than half the shortest true boundary loop of the remeshed surface. A rebuilt true
//! boundary comes out shorter than the input's (remeshing straightens it, the front cuts corners
//! where points were dropped) and must not be taken for a hole.
double automatic_hole_bound(const Mesh& remeshed)
{
  const std::vector<double> loops = boundary_loop_lengths(remeshed);
  if (loops.empty())
    return std::numeric_limits<double>::infinity();
  return 0.5 * *std::min_element(loops.begin(), loops.end());
}

//! Stage 0 (Appendix B): replace every set of mutually intersecting components by the surface they
//! merge into (merge_touching_surfaces: bodies join, a bubble opens through the wall or sheet it
//! reached). Returns the number of components merged away.
int merge_intersecting_components(Mesh& mesh)
{
  int count = 0;
  face_component_ids(mesh, &count);
  if (count < 2)
    return 0;
  std::vector<Mesh> parts = split_components(mesh);
  int merged = 0;
  bool changed = true;
  while (changed) {
    changed = false;
    for (std::size_t i = 0; i < parts.size() && !changed; ++i)
      for (std::size_t j = i + 1; j < parts.size() && !changed; ++j) {
        if (surface_intersections(parts[i], parts[j]).empty())
          continue;
        parts[i] = merge_touching_surfaces(parts[i], parts[j]).mesh;
        parts.erase(parts.begin() + static_cast<std::ptrdiff_t>(j));
        ++merged;
        changed = true;
      }
  }
  if (merged == 0)
    return 0;
  mesh = parts.front();
  for (std::size_t i = 1; i < parts.size(); ++i) {
    VertexVectors x(mesh.n_vertices() + parts[i].n_vertices(), 3);
    x << vertex_positions(mesh), vertex_positions(parts[i]);
    FaceIndices t(mesh.n_faces() + parts[i].n_faces(), 3);
    t << face_indices(mesh), (face_indices(parts[i]).array() + static_cast<int>(mesh.n_vertices())).matrix();
    mesh = make_mesh(x, t);
  }
  return merged;
}

//! The mesh rebuilt through validation: closed components oriented outward, degenerate faces and
//! non-manifold configurations reported as InvalidMesh.
Mesh validated(const Mesh& mesh);

//! validated(mesh) for the output of a remeshing alone (no rebuild from points), which is
//! manifold and keeps its input's orientation by construction: when it is one component, closed
//! with a positive volume or open, every vertex on a face and no triangle degenerate, the mesh
//! build_mesh would assemble from it (the same vertices and corners), without its soup and its
//! checks (0.08 s of the 1.6 s of a re-triangulating step of the spheres scene, 94k vertices). In
//! any other case, validated(mesh), which reports what is wrong.
Mesh validated_remeshing(const Mesh& mesh)
{
  int count = 0;
  face_component_ids(mesh, &count);
  const bool one_body = count == 1 && (component_topology(mesh).front().closed() ? enclosed_volume(mesh) > 0 : true);
  const bool every_vertex_used = std::all_of(mesh.vertices_begin(), mesh.vertices_end(),
                                             [&](Mesh::VertexHandle v) { return !mesh.is_isolated(v); });
  if (!one_body || !every_vertex_used)
    return validated(mesh);
  try {
    check_geometry(mesh, "re-triangulated surface");
  } catch (const InvalidMesh&) {
    return validated(mesh);
  }
  // Corners in the order build_mesh takes them (the face's vertex circulator).
  FaceIndices corners(static_cast<Eigen::Index>(mesh.n_faces()), 3);
  for (const auto f : mesh.faces()) {
    int k = 0;
    for (const auto v : mesh.fv_range(f))
      corners(f.idx(), k++) = v.idx();
  }
  return make_mesh(vertex_positions(mesh), corners);
}

Mesh validated(const Mesh& mesh)
{
  PolygonSoup soup;
  soup.points.reserve(mesh.n_vertices());
  for (const auto v : mesh.vertices())
    soup.points.push_back(to_eigen(mesh.point(v)));
  soup.polygons.reserve(mesh.n_faces());
  for (const auto f : mesh.faces()) {
    std::vector<long long> polygon;
    for (const auto v : mesh.fv_range(f))
      polygon.push_back(v.idx());
    soup.polygons.push_back(std::move(polygon));
  }
  return build_mesh(soup, "re-triangulated surface").mesh;
}

//! Rings around intersecting faces where stage 1 keeps the mesh's own scale.
constexpr int kLocalScaleRings = 4;

//! Stage 1's curvature-adapted sizing (curvature_targets), except within kLocalScaleRings of the faces
//! that intersect others, where the target is the local mean edge length: sheets that crossed are
//! not a curvature to resolve (refining where they cross leaves the rebuild slivers of enclosed
//! space), and coarsening a neck that pinched through would tear it before the surgery. With the
//! boundary kept, no finer beside it than its edges (kept_boundary_sizing.h).
//! `known_targets`, when given, are the curvature targets of `clean`.
std::vector<double> adapted_targets(const Mesh& clean, const std::vector<FacePair>& crossings,
                                    const RetriangulationOptions& options, double ell,
                                    const std::vector<double>* known_targets)
{
  const double min_length = options.min_edge_fraction * ell;
  std::vector<double> target = known_targets ? *known_targets : curvature_targets(clean, options, ell);
  std::vector<bool> near(clean.n_vertices(), false);
  for (const FacePair& pair : crossings)
    for (const int f : {pair.first, pair.second})
      for (const auto v : clean.fv_range(clean.face_handle(f)))
        near[v.idx()] = true;
  for (int ring = 0; ring < kLocalScaleRings; ++ring) {
    std::vector<bool> grown = near;
    for (const auto v : clean.vertices())
      if (near[v.idx()])
        for (const auto w : clean.vv_range(v))
          grown[w.idx()] = true;
    near.swap(grown);
  }
  for (const auto v : clean.vertices())
    if (near[v.idx()])
      target[v.idx()] = std::clamp(clean.valence(v) > 0 ? mean_edge_length_at(clean, v) : ell, min_length, ell);
  if (rim_kept_in_stage_one(options))
    floor_targets_beside_kept_boundary(clean, target);
  return target;
}

//! Around a crossing the remeshing made, the input's vertices within this many ℓ get finer targets.
constexpr double kRefinementRadius = 2;

//! The finest target a refinement asks for, as a fraction of the sizing's finest edge
//! (min_edge_fraction · ℓ): half of it, two edges across the thinnest part a run admits. The run
//! checks before step 1 that every part and every gap between bodies is at least that finest edge
//! wide (run/resolution_check.h); a smaller local thickness is a concave crease's outward gap or a
//! sharp edge's wedge, which tends to 0 there and which no edge length resolves (the floor was ℓ/64,
//! a fraction of ℓ alone, 64 times the vertices where it applied).
constexpr double kFinestRefinement = 0.5;

//! A refinement round is not run when its targets ask for more than refinement_bound vertices
//! (estimated_vertices), and is stopped when it makes more (RemeshOptions::max_vertices): stage 1
//! is skipped. The refinements it is for are local (the band along a crease), a few tens of percent
//! more vertices: the bound is this many times the vertices of stage 1's first remeshing...
constexpr double kMaxRefinementGrowth = 4;

//! ... or this many vertices, when more. A small surface needs more than 4× its first remeshing
//! when a band of ℓ/2-to-ℓ/8 edges is a large share of it: CGAL's mpi_triang.off (90 vertices,
//! genus 1) made 65 vertices and 21 crossing pairs in its first remeshing and asked ~380 for the
//! next round, which the growth factor alone refused at every look until nothing was left. The
//! factor is there against a round that runs away in memory (rotor_small.off: 58k vertices and
//! more within one remeshing); a few thousand vertices cost milliseconds and a few megabytes.
constexpr double kSmallSurfaceVertices = 2000;

//! The vertices a refinement round may ask for or make, `first` those of the first remeshing.
double refinement_bound(std::size_t first)
{
  return std::max(kMaxRefinementGrowth * static_cast<double>(first), kSmallSurfaceVertices);
}

//! The vertices a remeshing of `mesh` to `targets` (one per vertex) makes, about: each vertex of
//! a regular triangulation with edges t owns an area of (√3/2) t²; each face's area is shared by
//! its three vertices at their targets.
double estimated_vertices(const Mesh& mesh, const std::vector<double>& targets)
{
  double count = 0;
  for (const auto f : mesh.faces()) {
    std::array<Eigen::Vector3d, 3> p;
    double per_area = 0;
    int k = 0;
    for (const auto v : mesh.fv_range(f)) {
      p[k++] = to_eigen(mesh.point(v));
      const double t = targets[static_cast<std::size_t>(v.idx())];
      per_area += 1.0 / (3.0 * (std::sqrt(3.0) / 2.0) * t * t);
    }
    count += 0.5 * (p[1] - p[0]).cross(p[2] - p[0]).norm() * per_area;
  }
  return count;
}

//! The vertices of the faces of `remeshed` in `pairs`: where the remeshing made it cross itself.
std::vector<Eigen::Vector3d> crossing_points(const Mesh& remeshed, const std::vector<FacePair>& pairs)
{
  std::vector<Eigen::Vector3d> points;
  for (const FacePair& pair : pairs)
    for (const int f : {pair.first, pair.second})
      for (const auto v : remeshed.fv_range(remeshed.face_handle(f)))
        points.push_back(to_eigen(remeshed.point(v)));
  return points;
}

//! Stage 1 as it is kept: the remeshed surface (and its intersecting pairs, as stage 2 needs them),
//! or the input itself when the remeshing was refused.
struct StageOne {
  Mesh mesh;
  std::vector<FacePair> pairs;
};

//! `targets` (one per vertex of `input`, garbage-collected) made finer around `own`, the crossing
//! points of the last remeshing: halved within kRefinementRadius ℓ of them and kept below half the
//! local thickness, never below the floor kFinestRefinement · min_edge_fraction · ℓ.
void refine_targets(const Mesh& input, const std::vector<Eigen::Vector3d>& own, const LocalThickness& thickness,
                    double ell, double floor, std::vector<double>& targets)
{
  const VertexVectors sites = point_rows(own), positions = vertex_positions(input);
  const std::vector<int> nearest = nearest_points(sites, positions);
  for (const auto v : input.vertices()) {
    const auto i = static_cast<std::size_t>(v.idx());
    if ((positions.row(v.idx()) - sites.row(nearest[i])).norm() > kRefinementRadius * ell)
      continue;
    targets[i] = std::max(std::min(0.5 * targets[i], 0.5 * thickness.feature_size(v.idx())), floor);
  }
}

//! Stage 1 refused where it makes crossings of its own (RetriangulationOptions::refinement_rounds):
//! remesh `input` (garbage-collected; `crossings` its own intersecting pairs) with `targets` at its
//! vertices (empty: the uniform ℓ of `remesh`); when the input does not cross itself and the result
//! does, again with the targets around the crossings made finer (refine_targets), until it does not;
//! the input is kept when the rounds are spent, a round leaves as many crossings as the one before
//! or more, or it would ask for, or makes, more vertices than refinement_bound allows (the first
//! round: of its own estimate).
StageOne remesh_without_own_crossings(const Mesh& input, const std::vector<FacePair>& crossings,
                                      std::vector<double> targets, RemeshOptions remesh,
                                      const RetriangulationOptions& options, double ell, RetriangulationResult& r)
{
  // The last remeshing that crossed itself, which the refusal hands on (RetriangulationResult::crossed_remeshing).
  std::optional<CrossedRemeshing> crossed;
  const auto refuse = [&] {
    r.remeshing_refused = true;
    r.remesh = {};
    r.remesh.edge_length = ell;
    r.crossed_remeshing = std::move(crossed);
    return StageOne{input, crossings};
  };
  std::optional<LocalThickness> thickness;
  std::size_t first_vertices = 0, last_pairs = 0;
  for (int round = 0;; ++round) {
    if (!targets.empty()) {
      logger().debug("stage 1, round {}: targets down to {:.3g} ℓ, about {:.0f} vertices", round,
                     *std::min_element(targets.begin(), targets.end()) / ell, estimated_vertices(input, targets));
      remesh.sizing = nearest_vertex_sizing(input, targets);
    }
    // The first remeshing is bounded by its own estimate as a refinement is by the first: on
    // CGAL's elk.off (ℓ = 6.7, t = 635) one estimated at 5.3k vertices made 114k in its third
    // iteration and went on for minutes.
    if (round == 0 && options.refinement_rounds > 0)
      remesh.max_vertices = static_cast<std::size_t>(refinement_bound(static_cast<std::size_t>(
          estimated_vertices(input, targets.empty() ? std::vector<double>(input.n_vertices(), ell) : targets))));
    RemeshResult remeshed = isotropic_remesh(input, remesh);
    r.remeshed_vertices = std::max(r.remeshed_vertices, static_cast<long>(remeshed.mesh.n_vertices()));
    if (remeshed.statistics.stopped) {
      logger().debug("stage 1, round {}: stopped at {} vertices, the bound of a remeshing", round,
                     remeshed.mesh.n_vertices());
      return refuse();
    }
    StageOne s{std::move(remeshed.mesh), {}};
    // A guarded remeshing that crossed itself more often than it has faces crumpled, nowhere a
    // thin part to refine: it is refused without its crossings listed in full. On camel.off (step
    // 70 of a volume-restoring run) one of 69k vertices crossed itself in 78 million pairs, and
    // the refinement's search around them ran out of memory.
    const bool guarded = options.refinement_rounds > 0 && crossings.empty();
    s.pairs = self_intersections(s.mesh, {.stop_after = guarded ? s.mesh.n_faces() : 0});
    if (guarded && s.pairs.size() > s.mesh.n_faces()) {
      logger().debug("stage 1, round {}: {} vertices crossing themselves in more pairs than their {} faces: refused",
                     round, s.mesh.n_vertices(), s.mesh.n_faces());
      return refuse();
    }
    r.remesh = remeshed.statistics;
    if (round == 0)
      first_vertices = s.mesh.n_vertices();
    logger().debug("stage 1, round {}: {} vertices, {} crossing face pairs", round, s.mesh.n_vertices(),
                   s.pairs.size());
    // Only a surface that does not cross itself is guarded: where the flow's sheets crossed, the
    // surgery's remeshing around them is the paper's (the local surgery and the tests of its
    // outcome against this pipeline rely on it), and the hook checks the outcome.
    if (options.refinement_rounds == 0 || s.pairs.empty() || !crossings.empty())
      return s;
    if (round == 0)
      r.remeshing_crossings = static_cast<int>(s.pairs.size());
    // A round that did not reduce the crossings will not be helped by the next one: on
    // rotor_small.off the first made 663 crossing pairs where there were 79 to remove.
    crossed = CrossedRemeshing{s.mesh, s.pairs};
    if (round == options.refinement_rounds || (round > 0 && s.pairs.size() >= last_pairs))
      return refuse();
    last_pairs = s.pairs.size();
    if (!thickness)
      thickness = local_thickness(input, {.max_distance = 4 * ell});
    if (targets.empty())
      targets.assign(input.n_vertices(), ell);
    refine_targets(input, crossing_points(s.mesh, s.pairs), *thickness, ell,
                   finest_refinement_edge(options, ell), targets);
    if (rim_kept_in_stage_one(options))
      floor_targets_beside_kept_boundary(input, targets);
    if (const double estimate = estimated_vertices(input, targets); estimate > refinement_bound(first_vertices)) {
      logger().debug("stage 1: the next round would remesh into about {:.0f} vertices, more than {:.0f} (the "
                     "first remeshing made {}): not run",
                     estimate, refinement_bound(first_vertices), first_vertices);
      return refuse();
    }
    // The estimate holds for a remesher that meets its targets (within 30% on the rounds measured);
    // on a thin part with sharp edges it did not: rotor_small.off's second refinement round, at
    // targets down to ℓ/16 and estimated at 9.1k vertices, made 58k in its second iteration and
    // ran out of memory in its third.
    remesh.max_vertices = static_cast<std::size_t>(refinement_bound(first_vertices));
    ++r.refinements;
  }
}

//! How far from the intersecting faces, in units of ℓ, a piece stage 2 left must reach not to be
//! taken for surface between crossings (the local surgery's first patch radius).
constexpr double kBetweenCrossingsReach = 3;

//! The rows of `oriented` (points of removal.mesh, what stage 2 left of `remeshed`) grouped by the
//! piece of removal.mesh (component through edges) they lie on, in piece order. Left out, as the
//! local surgery leaves them out: pieces of fewer than `min_faces` triangles, which stage 6 would
//! drop, and pieces with no vertex farther than `reach` from every vertex of a removed face,
//! surface between crossings (the spindle between the two points where a neck's walls crossed its
//! axis, the part of a torus's inner wall that crossed the axis); then groups of fewer than
//! `min_points` points, too few to sample a surface at the normals' scale. A vertex where pieces
//! meet at it alone goes with the piece of its first face. No group when fewer than two pieces have
//! `min_faces` triangles: there is nothing to keep apart.
std::vector<std::vector<int>> points_by_piece(const Mesh& remeshed, const RemovalResult& removal,
                                              const OrientedPoints& oriented, double reach, int min_faces,
                                              int min_points)
{
  const Mesh& remaining = removal.mesh;
  int count = 0;
  const std::vector<int> piece = face_component_ids(remaining, &count);
  std::vector<int> faces(static_cast<std::size_t>(count), 0);
  for (const int p : piece)
    ++faces[static_cast<std::size_t>(p)];
  if (std::count_if(faces.begin(), faces.end(), [min_faces](int n) { return n >= min_faces; }) < 2)
    return {};
  std::vector<char> reaches_out(static_cast<std::size_t>(count), removal.removed_faces.empty());
  if (!removal.removed_faces.empty()) {
    std::vector<Eigen::Vector3d> crossing;
    for (const int f : removal.removed_faces)
      for (const auto v : remeshed.fv_range(remeshed.face_handle(f)))
        crossing.push_back(to_eigen(remeshed.point(v)));
    const VertexVectors sites = point_rows(crossing), points = vertex_positions(remaining);
    const std::vector<int> nearest = nearest_points(sites, points);
    for (const auto f : remaining.faces())
      for (const auto v : remaining.fv_range(f))
        if ((points.row(v.idx()) - sites.row(nearest[static_cast<std::size_t>(v.idx())])).norm() > reach)
          reaches_out[static_cast<std::size_t>(piece[static_cast<std::size_t>(f.idx())])] = 1;
  }
  std::vector<std::vector<int>> groups(static_cast<std::size_t>(count));
  for (std::size_t row = 0; row < oriented.source.size(); ++row) {
    const auto v = remaining.vertex_handle(oriented.source[row]);
    const auto p = static_cast<std::size_t>(piece[static_cast<std::size_t>(remaining.vf_range(v).begin()->idx())]);
    if (faces[p] >= min_faces && reaches_out[p])
      groups[p].push_back(static_cast<int>(row));
  }
  std::erase_if(groups,
                [min_points](const std::vector<int>& group) { return static_cast<int>(group.size()) < min_points; });
  return groups;
}

//! The signed volumes of the closed components `selection` dropped from `mesh`.
std::vector<double> dropped_volumes(const Mesh& mesh, const ComponentSelection& selection)
{
  if (selection.dropped.empty())
    return {};
  const std::vector<double> volumes = component_volumes(mesh);
  const std::vector<ComponentTopology> topology = component_topology(mesh);
  std::vector<double> dropped;
  for (int c : selection.dropped)
    if (topology[c].closed())
      dropped.push_back(volumes[c]);
  return dropped;
}

//! Stage 4's outcome: the surface without its debris, validated, with its counts.
struct CleanedUp {
  Mesh mesh;
  std::vector<double> dropped_volumes; //!< of the closed components dropped
  int dropped = 0;    //!< components dropped as debris
  int components = 0; //!< left
  int open_holes = 0; //!< boundary loops left
};

//! Stage 4: drop the debris, validate what is left (a remeshing's output by the cheaper test,
//! validated_remeshing, unless it was `rebuilt` from points) and count its components and holes.
CleanedUp clean_up(const Mesh& mesh, const ComponentOptions& debris, bool rebuilt)
{
  ComponentSelection selection = keep_components(mesh, debris);
  if (selection.mesh.n_faces() == 0)
    throw InvalidMesh(fmt::format("re-triangulation: nothing is left: every component has fewer than {} triangles "
                                  "or encloses almost no volume",
                                  debris.min_faces));
  CleanedUp c;
  c.dropped = static_cast<int>(selection.dropped.size());
  c.dropped_volumes = dropped_volumes(mesh, selection);
  c.mesh = rebuilt ? validated(selection.mesh) : validated_remeshing(selection.mesh);
  face_component_ids(c.mesh, &c.components);
  c.open_holes = static_cast<int>(boundary_loop_lengths(c.mesh).size());
  return c;
}

//! What a caller found of the input already, when it did: its self-intersections and stage 1's
//! curvature targets (retriangulate's second overload).
struct KnownFindings {
  const std::vector<FacePair>* crossings = nullptr;
  const std::vector<double>* targets = nullptr;
};

//! Stage 1 on `mesh` (stage 0's output, garbage-collected here): the remeshing, curvature-adapted
//! when `edges_per_radius` > 0, refused where it makes crossings of its own
//! (remesh_without_own_crossings). Returns the remeshed surface's intersecting pairs, which stage
//! 2 then needs not search again.
std::vector<FacePair> remeshed_stage(Mesh& mesh, const RetriangulationOptions& options, KnownFindings known,
                                     RetriangulationResult& r)
{
  const auto start = Clock::now();
  RemeshOptions remesh;
  remesh.edge_length = r.edge_length;
  remesh.iterations = options.remesh_iterations;
  remesh.area_weighted_relaxation = options.graded_remeshing;
  // A resampled rim is a contact line: a curve in the plane with no corners of its own. A kink a
  // cut left is blunted by the remeshing, not kept as a corner whose flat tip the flow turns over.
  if (rim_kept_in_stage_one(options))
    remesh.boundary = BoundaryMode::keep;
  else if (options.resample_boundary)
    remesh.boundary_corner_angle_deg = 180;
  collect_garbage(mesh);
  // Where sheets cross, their normals describe no smooth surface: project onto the flat triangles.
  // Stage 0 left the input as it was unless it joined components.
  const bool looked_for = options.curved_projection || options.edges_per_radius > 0 || options.refinement_rounds > 0;
  const std::vector<FacePair> crossings = !looked_for ? std::vector<FacePair>{}
                                          : known.crossings && r.merged_components == 0 ? *known.crossings
                                                                                         : self_intersections(mesh);
  remesh.curved_projection = options.curved_projection && crossings.empty();
  // Nor are the sharp turns where sheets cross creases of a shape.
  remesh.crease_angle_deg = crossings.empty() ? options.crease_angle_deg : 0;
  std::vector<double> targets;
  if (options.edges_per_radius > 0)
    targets = adapted_targets(mesh, crossings, options, r.edge_length, r.merged_components == 0 ? known.targets : nullptr);
  StageOne remeshed =
      remesh_without_own_crossings(mesh, crossings, std::move(targets), remesh, options, r.edge_length, r);
  mesh = std::move(remeshed.mesh);
  r.seconds.remesh = seconds_since(start);
  return std::move(remeshed.pairs);
}

//! Stage 2's search, and beside it stage 4's clean-up of the surface as it is: the search usually
//! finds nothing to cut, and the clean-up is then the result.
struct SearchedSurface {
  std::vector<FacePair> pairs;        //!< the surface's intersecting face pairs
  std::optional<CleanedUp> unrebuilt; //!< the clean-up (not run with always_rebuild)
  std::exception_ptr failure;         //!< what the clean-up threw, raised only if it is kept
};

//! Search `mesh` for intersecting pairs (or take stage 1's, `remeshed_pairs`) while it is cleaned
//! up (clean_up) on the other core.
SearchedSurface searched_beside_clean_up(const Mesh& mesh, std::optional<std::vector<FacePair>> remeshed_pairs,
                                         const RetriangulationOptions& options, const ComponentOptions& debris,
                                         RetriangulationResult& r)
{
  SearchedSurface s;
  const auto side_by_side = Clock::now();
  tbb::parallel_invoke(
    [&] {
      const auto begun = Clock::now();
      s.pairs = remeshed_pairs ? std::move(*remeshed_pairs) : self_intersections(mesh);
      r.seconds.intersections = seconds_since(begun);
    },
    [&] {
      if (options.always_rebuild)
        return;
      const auto begun = Clock::now();
      try {
        s.unrebuilt = clean_up(mesh, debris, false);
      } catch (...) {
        s.failure = std::current_exception();
      }
      r.seconds.components = seconds_since(begun);
    });
  r.seconds.side_by_side =
      std::max(0.0, r.seconds.intersections + r.seconds.components - seconds_since(side_by_side));
  r.intersecting_pairs = static_cast<int>(s.pairs.size());
  return s;
}

//! Stages 2–5 with a fixed rim: the band along it kept, the rest rebuilt inside it (fixed_rim.h).
Mesh rebuilt_inside_rim(const Mesh& mesh, const std::vector<FacePair>& pairs, const RetriangulationOptions& options,
                        double hole_bound, RetriangulationResult& r)
{
  const auto start = Clock::now();
  RetriangulationResult inside = rebuild_keeping_rim(mesh, pairs, options, r.edge_length, hole_bound);
  r.removed_faces = inside.removed_faces;
  r.removed_points = inside.removed_points;
  r.unused_points = inside.unused_points;
  r.filled_holes = inside.filled_holes;
  r.dropped_components += inside.dropped_components;
  r.remesh.splits += inside.remesh.splits;
  r.remesh.collapses += inside.remesh.collapses;
  r.remesh.flips += inside.remesh.flips;
  r.rebuilt = r.rim_kept = true;
  r.seconds.reconstruction = seconds_since(start);
  return std::move(inside.mesh);
}

//! Stage 4: the surface rebuilt from `oriented` (the points of removal.mesh, what stage 2 left of
//! `mesh`). A rebuild that joins two pieces stage 2 left apart bridged a cut (the two ends of a neck
//! pinched through its axis, less than ℓ apart, whose rims' normals admit a tube between them):
//! then each piece is rebuilt on its own (reconstruct_apart).
Reconstruction reconstructed(const Mesh& mesh, const RemovalResult& removal, const OrientedPoints& oriented,
                             const RetriangulationOptions& options, RetriangulationResult& r)
{
  if (oriented.points.rows() < 3)
    throw InvalidMesh(fmt::format("re-triangulation: nothing is left to rebuild: removing the crossings and the "
                                  "points without a usable normal left {} points",
                                  oriented.points.rows()));
  Reconstruction rebuilt = reconstruct_surface(oriented.points, oriented.normals, options.reconstruction);
  const std::vector<std::vector<int>> removal_pieces =
      points_by_piece(mesh, removal, oriented, kBetweenCrossingsReach * r.edge_length, options.min_component_faces,
                      options.normals.neighbours);
  if (removal_pieces.size() > 1 && joins_groups(rebuilt, removal_pieces, static_cast<int>(oriented.points.rows()))) {
    rebuilt = reconstruct_apart(oriented.points, oriented.normals, removal_pieces, options.reconstruction);
    r.rebuilt_apart = true;
  }
  r.unused_points = static_cast<int>(rebuilt.unused.size());
  return rebuilt;
}

//! Stage 5: the holes of `mesh` shorter than `hole_bound` filled (fill_holes).
Mesh with_holes_filled(Mesh mesh, double hole_bound, RetriangulationResult& r)
{
  const auto start = Clock::now();
  HoleFillingOptions holes;
  holes.max_loop_length = hole_bound;
  FilledHoles filled = fill_holes(mesh, holes);
  r.filled_holes = static_cast<int>(std::count_if(filled.loops.begin(), filled.loops.end(), [](const HoleReport& loop) {
    return loop.outcome == LoopOutcome::filled;
  }));
  r.seconds.holes = seconds_since(start);
  return std::move(filled.mesh);
}

//! Stages 2–5: the faces in `pairs` removed, the rest's points given oriented normals, the surface
//! rebuilt from them, its debris dropped (first, so that no hole of a stray piece is filled) and its
//! holes filled.
Mesh rebuilt_from_points(const Mesh& mesh, std::vector<FacePair> pairs, const RetriangulationOptions& options,
                         const ComponentOptions& debris, double hole_bound, RetriangulationResult& r)
{
  auto start = Clock::now();
  RemovalResult removal = remove_self_intersections(mesh, std::move(pairs));
  r.removed_faces = static_cast<int>(removal.removed_faces.size());
  r.seconds.intersections += seconds_since(start);
  r.rebuilt = true;
  start = Clock::now();
  const OrientedPoints oriented = oriented_point_normals(removal.mesh, options.normals);
  r.removed_points = static_cast<int>(oriented.removed.size());
  r.seconds.normals = seconds_since(start);

  start = Clock::now();
  const Reconstruction rebuilt = reconstructed(mesh, removal, oriented, options, r);
  r.seconds.reconstruction = seconds_since(start);
  ComponentSelection pieces = keep_components(rebuilt.mesh, debris);
  r.dropped_components += static_cast<int>(pieces.dropped.size());
  r.dropped_volumes = dropped_volumes(rebuilt.mesh, pieces);
  if (!options.fill_holes)
    return std::move(pieces.mesh);
  return with_holes_filled(std::move(pieces.mesh), hole_bound, r);
}

//! The pipeline with the given options, once: stage 0, stage 1 (remeshed_stage), stage 2's search
//! beside the clean-up, and when something crosses (or always_rebuild) stages 2–5 with the rim kept
//! or not, then stage 6 (clean_up) on the rebuild.
RetriangulationResult retriangulate_once(const Mesh& input, const RetriangulationOptions& options,
                                         KnownFindings known)
{
  if (input.n_faces() == 0)
    throw InvalidMesh("re-triangulation: the surface has no triangles");

  RetriangulationResult r;
  int count = 0;
  face_component_ids(input, &count);
  r.components_before = count;
  r.edge_length = options.edge_length > 0 ? options.edge_length : mean_edge_length(input);

  const ComponentOptions debris{.min_faces = options.min_component_faces,
                                .min_thickness = options.min_component_thickness * r.edge_length};
  Mesh mesh = input;
  const auto start = Clock::now();
  r.merged_components = merge_intersecting_components(mesh);
  r.seconds.merge = seconds_since(start);

  std::optional<std::vector<FacePair>> remeshed_pairs; // stage 1's, when it found them
  if (options.remesh_iterations > 0)
    remeshed_pairs = remeshed_stage(mesh, options, known, r);

  const double hole_bound = options.max_hole_length > 0 ? options.max_hole_length : automatic_hole_bound(mesh);
  SearchedSurface searched = searched_beside_clean_up(mesh, std::move(remeshed_pairs), options, debris, r);
  std::optional<CleanedUp> cleaned = std::move(searched.unrebuilt);
  if (!searched.pairs.empty() || options.always_rebuild) {
    mesh = options.keep_boundary && !boundary_loops(mesh).empty()
               ? rebuilt_inside_rim(mesh, searched.pairs, options, hole_bound, r)
               : rebuilt_from_points(mesh, std::move(searched.pairs), options, debris, hole_bound, r);
    const auto cleaning = Clock::now();
    cleaned = clean_up(mesh, debris, true);
    r.seconds.components = seconds_since(cleaning);
  } else if (searched.failure) {
    std::rethrow_exception(searched.failure);
  }
  r.dropped_components += cleaned->dropped;
  r.dropped_volumes.insert(r.dropped_volumes.end(), cleaned->dropped_volumes.begin(), cleaned->dropped_volumes.end());
  r.components_after = cleaned->components;
  r.open_holes = cleaned->open_holes;
  r.mesh = std::move(cleaned->mesh);
  if (r.rebuilt)
    r.turned_open_components = orient_open_components_like(input, r.mesh);

  logger().debug("re-triangulated: {}", retriangulation_summary(r));
  return r;
}

} // namespace

std::string retriangulation_summary(const RetriangulationResult& r)
{
  std::string s = fmt::format("{} splits, {} collapses, {} flips", r.remesh.splits, r.remesh.collapses, r.remesh.flips);
  if (r.merged_components > 0)
    s += fmt::format("; {} intersecting components joined", r.merged_components);
  if (r.rebuilt)
    s += fmt::format("; {} intersecting pairs, {} faces removed, {} points dropped, rebuilt{}, {} holes filled",
                     r.intersecting_pairs, r.removed_faces, r.removed_points,
                     r.rim_kept        ? " inside the band kept along the fixed boundary"
                     : r.rebuilt_apart ? " (each piece apart: together they bridged a cut)"
                                       : "",
                     r.filled_holes);
  if (r.patch_faces > 0)
    s += fmt::format(" (locally: a patch of {} faces)", r.patch_faces);
  if (r.remeshing_crossings > 0)
    s += r.remeshing_refused
             ? fmt::format("; the remeshing made {} face pairs of a surface that did not cross itself cross, and {} "
                           "rounds finer there did not help: refused, the surface kept its triangles",
                           r.remeshing_crossings, r.refinements)
             : fmt::format("; the remeshing made {} face pairs of a surface that did not cross itself cross: redone "
                           "{} times finer there",
                           r.remeshing_crossings, r.refinements);
  if (r.turned_open_components > 0)
    s += fmt::format("; {} open components the rebuild returned turned over turned back", r.turned_open_components);
  if (r.uniform_fallback)
    s += "; uniform ℓ (the adapted one left crossing sheets)";
  s += fmt::format("; components {} → {}", r.components_before, r.components_after);
  if (r.dropped_components > 0) {
    s += fmt::format(" ({} debris dropped", r.dropped_components);
    if (!r.dropped_volumes.empty()) {
      s += ", closed ones of volume";
      for (double v : r.dropped_volumes)
        s += fmt::format(" {:.3g}", v);
    }
    s += ")";
  }
  return s;
}

namespace {

RetriangulationResult retriangulate_with(const Mesh& input, const RetriangulationOptions& options,
                                         KnownFindings known)
{
  validate_retriangulation_options(options);
  if (options.edges_per_radius == 0)
    return retriangulate_once(input, options, {known.crossings});
  // Adapted edge lengths help a pinch or a seal through; where they leave the rebuild with
  // sheets that still cross, or with nothing, the uniform ℓ is tried instead.
  RetriangulationOptions uniform = options;
  uniform.edges_per_radius = 0;
  try {
    RetriangulationResult r = retriangulate_once(input, options, known);
    if (!r.rebuilt || self_intersections(r.mesh).empty())
      return r;
  } catch (const InvalidMesh&) {
  }
  RetriangulationResult r = retriangulate_once(input, uniform, {known.crossings});
  r.uniform_fallback = true;
  return r;
}

} // namespace

double finest_refinement_edge(const RetriangulationOptions& options, double edge_length)
{
  return kFinestRefinement * options.min_edge_fraction * edge_length;
}

RetriangulationResult retriangulate(const Mesh& input, const RetriangulationOptions& options)
{
  return retriangulate_with(input, options, {});
}

RetriangulationResult retriangulate(const Mesh& input, const RetriangulationOptions& options,
                                    const std::vector<FacePair>& crossings, const std::vector<double>& targets)
{
  const auto faces = input.all_faces();
  if (std::any_of(faces.begin(), faces.end(), [&](Mesh::FaceHandle f) { return input.status(f).deleted(); }))
    throw InvalidMesh("re-triangulation: the surface given with its crossings has deleted faces; garbage-collect it "
                      "and find its crossings again");
  if (!targets.empty() && targets.size() != input.n_vertices())
    throw InvalidParameter(fmt::format("re-triangulation: {} curvature targets given for {} vertices", targets.size(),
                                       input.n_vertices()));
  return retriangulate_with(input, options, {&crossings, targets.empty() ? nullptr : &targets});
}

} // namespace sdflow
