//! The refinement factor (flow/refinement.h): the typical radius it is measured against, its
//! scaling with ℓ, and what a run does with it.
#include "sdflow/errors.h"
#include "sdflow/flow/refinement.h"
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/run/parameters.h"
#include "support/analytic_meshes.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <cmath>

namespace sdflow {
namespace {

//! The discrete curvature's error on the test meshes used here.
constexpr double kRadiusTolerance = 0.03;

Mesh scaled(Mesh mesh, double factor)
{
  for (auto v : mesh.vertices())
    mesh.set_point(v, mesh.point(v) * factor);
  return mesh;
}

TEST(Refinement, the_typical_radius_is_the_curved_parts_radius)
{
  for (const double radius : {1e-3, 1.0, 250.0}) {
    SCOPED_TRACE(fmt::format("sphere of radius {}", radius));
    EXPECT_NEAR(typical_curvature_radius(analytic::icosphere(4, radius)) / radius, 1, kRadiusTolerance);
  }
  // A torus R = 3, r = 1.5: its largest principal curvature is the tube's, 1/r, everywhere.
  EXPECT_NEAR(typical_curvature_radius(analytic::torus(120, 60, 3, 1.5)) / 1.5, 1, kRadiusTolerance);
  // A flat disk has none, and the flat part of a scene does not dilute the curved one.
  EXPECT_TRUE(std::isinf(typical_curvature_radius(analytic::disk(10))));
  EXPECT_EQ(automatic_refinement(analytic::disk(10), 0.01), 1);
}

TEST(Refinement, is_one_at_coarse_resolutions_and_grows_as_the_edge_length_shrinks)
{
  const Mesh sphere = analytic::icosphere(4);
  const double coarse = 1 / kReferenceEdgesPerRadius; // q edges per radius: the reference resolution
  EXPECT_EQ(automatic_refinement(sphere, 2 * coarse), 1);
  const double s = automatic_refinement(sphere, coarse / 2);
  EXPECT_NEAR(s, 2, 2 * kRadiusTolerance);
  EXPECT_NEAR(automatic_refinement(sphere, coarse / 4), 2 * s, 1e-12) << "s ∝ 1/ℓ";
  // Scale-free: the same surface and ℓ in other units give the same s.
  EXPECT_NEAR(automatic_refinement(scaled(sphere, 1e3), 1e3 * coarse / 4), 2 * s, 1e-9);
  EXPECT_THROW(automatic_refinement(sphere, 0), InvalidParameter);
}

TEST(Refinement, refines_the_sizing_by_its_square_root_and_the_step_bound_by_itself)
{
  const RetriangulationOptions pipeline{.edges_per_radius = 4};
  EXPECT_DOUBLE_EQ(refined(pipeline, 4).edges_per_radius, 8);
  EXPECT_EQ(refined(RetriangulationOptions{.edges_per_radius = 0}, 4).edges_per_radius, 0) << "uniform stays uniform";
  const AdaptiveOptions adaptive{.max_displacement = 0.05};
  EXPECT_DOUBLE_EQ(refined(adaptive, 5).max_displacement, 0.01);
  EXPECT_DOUBLE_EQ(refined(adaptive, 1).max_displacement, 0.05);
}

TEST(Refinement, a_flow_fixes_it_once_from_its_initial_surface_and_the_paper_preset_keeps_one)
{
  const Mesh sphere = analytic::icosphere(4, 2.0); // ℓ ≈ 0.1: q ℓ / R ≈ 0.27
  RunParameters p;
  p.steps = 1;
  p.retriangulation.enabled = true;
  const SurfaceDiffusion automatic(sphere, p);
  const double expected = 2.0 / (kReferenceEdgesPerRadius * mean_edge_length(sphere));
  EXPECT_NEAR(automatic.options().refinement, expected, kRadiusTolerance * expected);
  EXPECT_GT(automatic.options().refinement, 1.3);
  p.refinement = 2.5;
  EXPECT_EQ(SurfaceDiffusion(sphere, p).options().refinement, 2.5) << "a given s is kept";
  apply_preset("paper", p);
  EXPECT_EQ(SurfaceDiffusion(sphere, p).options().refinement, 1);
  p.refinement = -1;
  EXPECT_THROW(SurfaceDiffusion(sphere, p), InvalidParameter);
}

TEST(Refinement, measures_the_remeshers_target_only_when_the_run_remeshes)
{
  const Mesh sphere = analytic::icosphere(4, 2.0);
  RunParameters p;
  p.steps = 1;
  p.retriangulation.pipeline.edge_length = 0.02; // five times finer than the mesh
  p.retriangulation.enabled = true;
  const double remeshed = SurfaceDiffusion(sphere, p).options().refinement;
  EXPECT_NEAR(remeshed, 2.0 / (kReferenceEdgesPerRadius * 0.02), kRadiusTolerance * remeshed);
  // Without re-triangulation the mesh keeps its own resolution: the unused target does not count.
  p.retriangulation.enabled = false;
  const double own = SurfaceDiffusion(sphere, p).options().refinement;
  const double expected = 2.0 / (kReferenceEdgesPerRadius * mean_edge_length(sphere));
  EXPECT_NEAR(own, expected, kRadiusTolerance * expected);
}

} // namespace
} // namespace sdflow
