//! Surgery only around the intersecting faces (retri/local_surgery.h) against the whole-surface
//! pipeline (retri/pipeline.h): same components and genera, the faces far from the crossing kept
//! bit for bit, and a clear refusal where it cannot work.
#include "sdflow/errors.h"
#include "sdflow/flow/retriangulation.h"
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/retri/local_surgery.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/expression.h"
#include "sdflow/shapes/mesher.h"
#include "sdflow/spatial/intersect.h"
#include "support/analytic_meshes.h"
#include "support/mesh_checks.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>
#include <set>
#include <string>

namespace sdflow {
namespace {

//! Components as (closed, genus) pairs, sorted: what the topology outcome is.
std::vector<std::pair<bool, int>> outcome(const Mesh& mesh)
{
  std::vector<std::pair<bool, int>> parts;
  for (const auto& c : component_topology(mesh))
    parts.emplace_back(c.closed(), c.genus);
  std::sort(parts.begin(), parts.end());
  return parts;
}

//! Input faces with every corner farther than `distance` from every corner of a crossing face,
//! and how many of them the result holds unchanged (same coordinates, same orientation).
struct FarFaces {
  int far = 0, kept = 0;
};

FarFaces far_faces_kept(const Mesh& input, const std::vector<FacePair>& crossings, const Mesh& result, double distance)
{
  std::vector<Eigen::Vector3d> seeds;
  for (const FacePair& pair : crossings)
    for (const int f : {pair.first, pair.second})
      for (const auto v : input.fv_range(input.face_handle(f)))
        seeds.push_back(to_eigen(input.point(v)));
  std::set<test::TriangleKey> after;
  for (const auto f : result.faces())
    after.insert(test::triangle_key(result, f));
  FarFaces counts;
  for (const auto f : input.faces()) {
    bool far = true;
    for (const auto v : input.fv_range(f))
      for (const Eigen::Vector3d& s : seeds)
        far = far && (to_eigen(input.point(v)) - s).norm() > distance;
    if (!far)
      continue;
    ++counts.far;
    counts.kept += after.count(test::triangle_key(input, f)) > 0;
  }
  return counts;
}

//! A surface of revolution about the x axis pinched through the axis around x = centre: the
//! radius drops by `depth` (1 - ((x - centre)/width)²) there, so where it was smaller than that the
//! walls pass through each other, as in a neck pinching off between two steps.
Eigen::Vector3d pinched(const Eigen::Vector3d& p, double centre, double width, double depth)
{
  const double rho = std::hypot(p.y(), p.z()), u = (p.x() - centre) / width;
  if (std::abs(u) >= 1 || rho == 0)
    return p;
  const double scale = (rho - depth * (1 - u * u)) / rho;
  return {p.x(), p.y() * scale, p.z() * scale};
}

//! A capsule of radius 1 and length-to-diameter ratio `ratio` along x, meshed with edges of `edge`.
Mesh capsule(double ratio, double edge = 0.3)
{
  const double half = ratio - 1;
  const std::string expression = "sqrt(max(abs(x)-" + std::to_string(half) + ",0)^2+y^2+z^2)-1";
  const ExpressionParameters shape{
      expression, Eigen::AlignedBox3d(Eigen::Vector3d(-half - 1.5, -1.5, -1.5), Eigen::Vector3d(half + 1.5, 1.5, 1.5))};
  return mesh_implicit_surface(expression_surface(shape), {.edge_length = edge}).mesh;
}

//! The surface a run re-triangulating by the whole pipeline reaches at the first step that makes it
//! intersect itself (the one its hook then re-triangulates); when the crossing first arises inside
//! the pipeline (which of the two happens depends on rounding), the surface handed to that
//! pipeline with its thinnest neck pushed through the axis; an empty mesh when neither happens
//! before `end_time`: the fixture the flow itself makes.
Mesh first_crossing(const Mesh& start, double end_time)
{
  FlowOptions p;
  p.end_time = end_time;
  p.retriangulation.pipeline.edge_length = mean_edge_length(start);
  p.retriangulation.local_surgery = false; // the whole pipeline between steps, whatever the default
  // The paper's stage 1, which may make the crossing of a pinch itself (the fixture's second case),
  // no start steps and no margin on degraded elements: the fixtures are the surfaces these runs
  // reached before any of them existed.
  p.retriangulation.pipeline.refinement_rounds = 0;
  p.time_step.adaptive.start_steps = 0;
  p.retriangulation.degraded_variation = 0;
  const RetriangulationHook retriangulate = make_retriangulation_hook(p.retriangulation);
  Mesh crossed, at_surgery;
  const RetriangulationHook capture = [&](Mesh& mesh, const RetriangulationContext& context) {
    if (crossed.n_faces() == 0 && !self_intersections(mesh).empty())
      crossed = mesh;
    const Mesh before = mesh;
    RetriangulationReport report = retriangulate(mesh, context);
    if (report.surgery && at_surgery.n_faces() == 0)
      at_surgery = before;
    return report;
  };
  SurfaceDiffusion flow(start, p, capture);
  while (crossed.n_faces() == 0 && at_surgery.n_faces() == 0 && !flow.finished())
    flow.step();
  if (crossed.n_faces() > 0 || at_surgery.n_faces() == 0)
    return crossed;
  // The crossing arose inside the pipeline (its remeshing moved the neck's last vertices through
  // each other), so the run never handed one over: push the neck the run left through the axis.
  double neck = std::numeric_limits<double>::infinity(), centre = 0;
  for (const auto v : at_surgery.vertices()) {
    const auto& q = at_surgery.point(v);
    if (const double rho = std::hypot(q[1], q[2]); rho < neck) {
      neck = rho;
      centre = q[0];
    }
  }
  const double ell = mean_edge_length(start);
  return test::mapped(at_surgery, [&](const Eigen::Vector3d& q) { return pinched(q, centre, 2 * ell, neck + ell / 4); });
}

//! The local surgery of one intersecting surface: its components and genera `expected`, a valid
//! surface, the far faces untouched, and the enclosed volume within 2% of `reference_volume`'s.
void expect_local_outcome(const Mesh& crossed, const RetriangulationOptions& options,
                          const std::vector<std::pair<bool, int>>& expected, double reference_volume)
{
  const std::vector<FacePair> crossings = self_intersections(crossed);
  ASSERT_FALSE(crossings.empty()) << "the fixture must intersect itself";
  const LocalSurgery local = local_surgery(crossed, crossings, options);
  ASSERT_TRUE(local.result.has_value()) << local.failure;
  const RetriangulationResult& r = *local.result;
  EXPECT_EQ(outcome(r.mesh), expected);
  EXPECT_TRUE(r.rebuilt);
  EXPECT_GT(r.patch_faces, 0);
  EXPECT_EQ(r.components_after, static_cast<int>(expected.size()));
  EXPECT_EQ(checks::self_intersecting_pairs(r.mesh), 0);
  EXPECT_TRUE(checks::is_two_manifold(r.mesh));
  // Faces beyond the largest patch radius tried (and a margin for the patch's regularisation)
  // are the input's, bit for bit; and the patch is a small part of the surface.
  const double ell = options.edge_length > 0 ? options.edge_length : mean_edge_length(crossed);
  const double reach = local.patch_radius + 3 * ell;
  const FarFaces far = far_faces_kept(crossed, crossings, r.mesh, reach);
  EXPECT_GT(far.far, static_cast<int>(crossed.n_faces()) / 2);
  EXPECT_EQ(far.kept, far.far);
  EXPECT_NEAR(enclosed_volume(r.mesh), reference_volume, 0.02 * std::abs(reference_volume));
}

//! The local and the global surgery of one intersecting surface, compared.
void expect_same_outcome_as_global(const Mesh& crossed, const RetriangulationOptions& options,
                                   const std::vector<std::pair<bool, int>>& expected)
{
  const RetriangulationResult global = retriangulate(crossed, options);
  EXPECT_EQ(outcome(global.mesh), expected);
  expect_local_outcome(crossed, options, expected, enclosed_volume(global.mesh));
}

//! The surface a run re-triangulating by the whole pipeline reaches at the last step before its
//! genus changes (empty when it does not before `end_time`).
Mesh last_before_genus_change(const Mesh& start, double end_time)
{
  FlowOptions p;
  p.end_time = end_time;
  p.retriangulation.pipeline.edge_length = mean_edge_length(start);
  p.retriangulation.local_surgery = false;
  // As in the fixture above: the surfaces these runs reached with the paper's stage 1, no start steps
  // and no margin on degraded elements.
  p.retriangulation.pipeline.refinement_rounds = 0;
  p.time_step.adaptive.start_steps = 0;
  p.retriangulation.degraded_variation = 0;
  const RetriangulationHook retriangulate = make_retriangulation_hook(p.retriangulation);
  Mesh before;
  bool changed = false;
  const RetriangulationHook capture = [&](Mesh& mesh, const RetriangulationContext& context) {
    const Mesh input = mesh;
    const RetriangulationReport report = retriangulate(mesh, context);
    if (!changed && component_topology(mesh)[0].genus != component_topology(input)[0].genus) {
      before = input;
      changed = true;
    }
    return report;
  };
  SurfaceDiffusion flow(start, p, capture);
  while (!changed && !flow.finished())
    flow.step();
  return before;
}

TEST(LocalSurgery, a_torus_whose_hole_crossed_becomes_a_sphere)
{
  // The torus R = 3, r = 1.5 (2000 vertices) as the flow brings it to the step before its hole
  // seals, the hole's wall then drawn in by the hole's radius and 0.1 more at its waist (fading
  // out over |z| < 0.6 and one unit outward), so it crosses the axis by about an edge: the crossing
  // a slightly longer step would have made.
  const Mesh start = mesh_implicit_surface(torus_shape({.major = 3, .minor = 1.5}), {.vertices = 2000}).mesh;
  const Mesh closing = last_before_genus_change(start, 10);
  ASSERT_GT(closing.n_faces(), 0u) << "the hole never sealed";
  double hole = std::numeric_limits<double>::infinity();
  for (const auto v : closing.vertices())
    if (std::abs(closing.point(v)[2]) < 0.6)
      hole = std::min(hole, std::hypot(closing.point(v)[0], closing.point(v)[1]));
  const Mesh crossed = test::mapped(closing, [hole](const Eigen::Vector3d& p) {
    const double rho = std::hypot(p.x(), p.y()), u = p.z() / 0.6;
    const double fade = 1 - (rho - hole);
    if (std::abs(u) >= 1 || fade <= 0)
      return p;
    const double scale = (rho - (hole + 0.1) * (1 - u * u) * fade) / rho;
    return Eigen::Vector3d(p.x() * scale, p.y() * scale, p.z());
  });
  expect_same_outcome_as_global(crossed, {.edge_length = mean_edge_length(start)}, {{true, 0}});
}

TEST(LocalSurgery, a_capsule_pinched_through_its_middle_breaks_in_two)
{
  const Mesh crossed =
      test::mapped(capsule(9), [](const Eigen::Vector3d& p) { return pinched(p, 0.1, 1.2, 1.3); });
  expect_same_outcome_as_global(crossed, {}, {{true, 0}, {true, 0}});
}

TEST(LocalSurgery, a_long_capsule_pinched_at_two_places_breaks_in_three)
{
  const Mesh crossed = test::mapped(capsule(12), [](const Eigen::Vector3d& p) {
    return pinched(pinched(p, -3.9, 1.2, 1.3), 4.1, 1.2, 1.3);
  });
  expect_same_outcome_as_global(crossed, {}, {{true, 0}, {true, 0}, {true, 0}});
}

TEST(LocalSurgery, declines_a_patch_that_holds_a_whole_component)
{
  // A small body folded through itself (one vertex pushed out through the far side), beside a
  // large one: the patch around its crossings, 3 ℓ across, holds all of it and has no cut loop.
  // Matching the rebuild's rim to the cut then read past an empty list (CGAL's elk.off, where a
  // run's surgery met a small body so, crashed).
  Mesh small = analytic::icosphere(2, 0.3);
  const auto v = *small.vertices().begin();
  small.set_point(v, -1.5 * small.point(v));
  const Mesh mesh = analytic::disjoint_union(analytic::icosphere(4, 1, {8, 0, 0}), small);
  const std::vector<FacePair> crossings = self_intersections(mesh);
  ASSERT_FALSE(crossings.empty());
  LocalSurgery surgery;
  ASSERT_NO_THROW(surgery = local_surgery(mesh, crossings, {.edge_length = 0.5}));
  if (surgery.result)
    EXPECT_EQ(checks::self_intersecting_pairs(surgery.result->mesh), 0);
  else
    EXPECT_FALSE(surgery.failure.empty());
}

TEST(LocalSurgery, the_dumbbell_at_its_pinch_in_a_run_splits_in_two)
{
  // The paper's dumbbell at half size (1000 vertices).
  const Mesh start = mesh_implicit_surface(dumbbell_shape({.radius = 3, .separation = 9}), {.edge_length = 0.5}).mesh;
  const Mesh crossed = first_crossing(start, 2);
  ASSERT_GT(crossed.n_faces(), 0u) << "the run never reached its pinch-off";
  expect_same_outcome_as_global(crossed, {.edge_length = mean_edge_length(start)}, {{true, 0}, {true, 0}});
}

// A crossing of the dumbbell's neck that the flow made with one rounding of its solves: removing
// the intersecting faces leaves the two ends of the neck, less than ℓ apart, and three scraps of
// the neck between them; rebuilt together, the advancing front bridged the ends through the
// scraps' points, one body where the local surgery makes two. The pipeline now sees the bridge
// and rebuilds each end on its own (docs/design.md §3, stage 4).
TEST(LocalSurgery, the_whole_pipeline_splits_the_dumbbell_crossed_at_its_pinch)
{
  const Mesh crossed = read_mesh(std::string(SDFLOW_SOURCE_DIR) + "/tests/data/dumbbell-crossed-at-its-pinch.ply").mesh;
  EXPECT_TRUE(retriangulate(crossed, {.edge_length = 0.5}).rebuilt_apart);
  expect_same_outcome_as_global(crossed, {.edge_length = 0.5}, {{true, 0}, {true, 0}});
}

TEST(LocalSurgery, a_capsule_drawn_through_its_axis_by_an_edge_splits_in_two)
{
  // The middle drawn in over |x| < 2.4 until the walls pass the axis by an edge: rebuilt
  // together, the whole pipeline bridged the ends the removal leaves (one body where there are
  // two, before it checked for bridges). (By half an edge, as before the remesher projected onto
  // the sheet facing each vertex, its first remeshing no longer leaves such a bridge.)
  const Mesh start = capsule(9);
  const double h = mean_edge_length(start);
  const Mesh crossed = test::mapped(start, [h](const Eigen::Vector3d& p) { return pinched(p, 0, 2.4, 1 + h); });
  EXPECT_TRUE(retriangulate(crossed, {}).rebuilt_apart);
  expect_same_outcome_as_global(crossed, {}, {{true, 0}, {true, 0}});
}

TEST(LocalSurgery, a_neck_drawn_in_without_remeshing_is_rebuilt_at_the_first_attempt)
{
  // A capsule's middle drawn in through its axis by a quarter of an edge over |x| < 0.6, the
  // bench's pinched dumbbell neck at 100k vertices scaled to 3000: the triangles of the slopes are
  // stretched into slivers (half an edge around, two along), which the first patch's cut crosses,
  // and between the two points where the walls pass through the axis lies an inside-out tube a
  // quarter of an edge wide. Neither may cost a rebuild.
  const Mesh start = capsule(2, 0.1);
  const double h = mean_edge_length(start);
  const Mesh crossed = test::mapped(start, [h](const Eigen::Vector3d& p) { return pinched(p, 0, 0.6, 1 + h / 4); });
  const std::vector<FacePair> crossings = self_intersections(crossed);
  ASSERT_FALSE(crossings.empty());
  const LocalSurgery local = local_surgery(crossed, crossings, {});
  ASSERT_TRUE(local.result.has_value()) << local.failure;
  EXPECT_EQ(local.attempts, 1) << "last failure: " << local.failure;
  const Mesh& result = local.result->mesh;
  EXPECT_EQ(outcome(result), (std::vector<std::pair<bool, int>>{{true, 0}, {true, 0}}));
  EXPECT_EQ(checks::self_intersecting_pairs(result), 0);
  EXPECT_TRUE(checks::is_two_manifold(result));
}

TEST(LocalSurgery, components_that_intersect_each_other_are_left_to_the_whole_pipeline)
{
  const Mesh touching = analytic::disjoint_union(analytic::icosphere(3, 1.0, {-0.6, 0, 0}),
                                                 analytic::icosphere(3, 1.0, {0.6, 0, 0}));
  const LocalSurgery local = local_surgery(touching, self_intersections(touching), {.edge_length = 0.1});
  EXPECT_FALSE(local.result.has_value());
  EXPECT_EQ(local.attempts, 0);
  EXPECT_NE(local.failure.find("components intersect"), std::string::npos) << local.failure;
}

TEST(LocalSurgery, a_patch_that_would_be_most_of_the_surface_is_declined)
{
  const Mesh crossed =
      test::mapped(capsule(9), [](const Eigen::Vector3d& p) { return pinched(p, 0.1, 1.2, 1.3); });
  const LocalSurgery local =
      local_surgery(crossed, self_intersections(crossed), {}, {.patch_radius = 3, .max_patch_fraction = 0.01});
  EXPECT_FALSE(local.result.has_value());
  EXPECT_NE(local.failure.find("the patch would hold"), std::string::npos) << local.failure;
}

TEST(LocalSurgery, a_rebuild_that_fails_every_time_gives_up_after_its_attempts_and_says_why)
{
  // More jet neighbours than any patch has points: every rebuild throws (remeshed and as it is),
  // the patch doubles twice, and the last reason is reported for the caller's fallback.
  const Mesh crossed =
      test::mapped(capsule(12), [](const Eigen::Vector3d& p) { return pinched(p, 0.1, 1.2, 1.3); });
  RetriangulationOptions options;
  options.normals.neighbours = 5000;
  const LocalSurgery local = local_surgery(crossed, self_intersections(crossed), options);
  EXPECT_FALSE(local.result.has_value());
  EXPECT_EQ(local.attempts, 2 * LocalSurgeryOptions{}.attempts);
  EXPECT_NE(local.failure.find("nearest_neighbours"), std::string::npos) << local.failure;
}

TEST(LocalSurgery, nothing_to_do_without_crossings_and_bad_options_are_refused)
{
  const Mesh sphere = analytic::icosphere(2);
  EXPECT_FALSE(local_surgery(sphere, {}, {}).result.has_value());
  EXPECT_THROW(local_surgery(sphere, {}, {}, {.patch_radius = 0}), InvalidParameter);
  EXPECT_THROW(local_surgery(sphere, {}, {}, {.attempts = 0}), InvalidParameter);
  EXPECT_THROW(local_surgery(sphere, {}, {}, {.max_patch_fraction = 1.5}), InvalidParameter);
}


//! The capped surgery of one intersecting surface (capped_surgery): components and genera
//! `expected`, a valid surface without crossings, far faces kept bit for bit, the caps' loops
//! counted, and the enclosed volume within `volume_tolerance` of the input's.
void expect_capped_outcome(const Mesh& crossed, const RetriangulationOptions& options,
                           const std::vector<std::pair<bool, int>>& expected, int cut_loops, double volume_tolerance)
{
  const std::vector<FacePair> crossings = self_intersections(crossed);
  ASSERT_FALSE(crossings.empty()) << "the fixture must intersect itself";
  const LocalSurgery capped = capped_surgery(crossed, crossings, options, {.patch_radius = 0.5});
  ASSERT_TRUE(capped.result.has_value()) << capped.failure;
  const RetriangulationResult& r = *capped.result;
  EXPECT_EQ(outcome(r.mesh), expected);
  EXPECT_EQ(r.filled_holes, cut_loops);
  EXPECT_EQ(r.intersecting_pairs, static_cast<int>(crossings.size()));
  EXPECT_EQ(checks::self_intersecting_pairs(r.mesh), 0);
  EXPECT_TRUE(checks::is_two_manifold(r.mesh));
  const double ell = options.edge_length > 0 ? options.edge_length : mean_edge_length(crossed);
  const FarFaces far = far_faces_kept(crossed, crossings, r.mesh, capped.patch_radius + 3 * ell);
  EXPECT_GT(far.far, static_cast<int>(crossed.n_faces()) / 2);
  EXPECT_EQ(far.kept, far.far);
  EXPECT_NEAR(enclosed_volume(r.mesh), enclosed_volume(crossed), volume_tolerance * enclosed_volume(crossed));
}

TEST(CappedSurgery, a_capsule_pinched_through_its_middle_is_capped_into_two_bodies)
{
  // The neck's band is cut by two loops; a cap on each is the pinch-off, whatever the points inside.
  const Mesh crossed =
      test::mapped(capsule(9), [](const Eigen::Vector3d& p) { return pinched(p, 0.1, 1.2, 1.3); });
  expect_capped_outcome(crossed, {}, {{true, 0}, {true, 0}}, 2, 0.02);
}

TEST(CappedSurgery, a_dent_pushed_through_the_far_side_is_flattened_into_one_body)
{
  // A sphere of radius 1 whose cap around the north pole is pushed down through the south pole's
  // sheet by 0.1: the crossing is a fold, cut by one loop on each sheet, and capping keeps one
  // body of genus 0.
  const Mesh sphere = analytic::icosphere(4, 1.0);
  const Mesh crossed = test::mapped(sphere, [](const Eigen::Vector3d& p) {
    const double r = std::hypot(p.x(), p.y());
    if (p.z() < 0 || r > 0.3)
      return p;
    const double depth = 2.1 * (1 - r * r / 0.09);
    return Eigen::Vector3d(p.x(), p.y(), p.z() - depth);
  });
  const LocalSurgery capped = capped_surgery(crossed, self_intersections(crossed), {}, {.patch_radius = 0.5});
  ASSERT_TRUE(capped.result.has_value()) << capped.failure;
  EXPECT_EQ(checks::self_intersecting_pairs(capped.result->mesh), 0);
  EXPECT_TRUE(checks::is_two_manifold(capped.result->mesh));
  EXPECT_EQ(outcome(capped.result->mesh), (std::vector<std::pair<bool, int>>{{true, 0}}));
  EXPECT_GE(capped.result->filled_holes, 1);
}

TEST(CappedSurgery, declines_as_the_local_surgery_does)
{
  const Mesh touching = analytic::disjoint_union(analytic::icosphere(3, 1.0, {-0.6, 0, 0}),
                                                 analytic::icosphere(3, 1.0, {0.6, 0, 0}));
  const LocalSurgery capped = capped_surgery(touching, self_intersections(touching), {.edge_length = 0.1});
  EXPECT_FALSE(capped.result.has_value());
  EXPECT_NE(capped.failure.find("components intersect"), std::string::npos) << capped.failure;
  EXPECT_FALSE(capped_surgery(analytic::icosphere(2), {}, {}).result.has_value());
}


TEST(CappedSurgery, a_small_body_crossing_itself_with_no_cut_is_dropped_as_debris)
{
  // A sphere of radius 1 beside a small one (radius 0.25) whose cap is pushed through its far side:
  // the patch takes the whole small body, which capping drops (its volume then goes to the debris).
  const Mesh small = test::mapped(analytic::icosphere(2, 0.25, {3, 0, 0}), [](const Eigen::Vector3d& p) {
    return p.x() > 3.1 ? Eigen::Vector3d(p.x() - 0.45, p.y(), p.z()) : p;
  });
  const Mesh crossed = analytic::disjoint_union(analytic::icosphere(3, 1.0), small);
  const std::vector<FacePair> crossings = self_intersections(crossed);
  ASSERT_FALSE(crossings.empty());
  const LocalSurgery capped = capped_surgery(crossed, crossings, {.edge_length = 0.2}, {.patch_radius = 0.5});
  ASSERT_TRUE(capped.result.has_value()) << capped.failure;
  EXPECT_EQ(capped.result->dropped_components, 1);
  EXPECT_EQ(outcome(capped.result->mesh), (std::vector<std::pair<bool, int>>{{true, 0}}));
  EXPECT_EQ(capped.result->mesh.n_faces(), analytic::icosphere(3, 1.0).n_faces());
}

} // namespace
} // namespace sdflow
