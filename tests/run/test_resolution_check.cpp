//! The resolution check before step 1 (resolution_check.h, check_run_input): a part thinner than
//! the finest edge of the run's sizing is named with where it is, how thin, and the edge length that
//! resolves it in each front end's words; a part the run resolves is evolved, not cut off.
#include "io/temp_dir.h"
#include "sdflow/errors.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/run/resolution_check.h"
#include "sdflow/run/run_input.h"
#include "sdflow/run/simulation.h"
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <string>

namespace sdflow {
namespace {

//! The tail's radius, its axis along x from the unit sphere to x = kTailEnd.
constexpr double kTailRadius = 0.04;
constexpr double kTailEnd = 2.2;

double largest_x(const Mesh& mesh)
{
  double x = -1e300;
  for (const auto v : mesh.vertices())
    x = std::max(x, static_cast<double>(mesh.point(v)[0]));
  return x;
}

//! A unit sphere with a thin straight tail (radius 0.04, to x = 2.2), meshed with edges of 0.1
//! refined where the surface curves (four edges per radius, down to 0.025 on the tail), from a
//! marching grid fine enough for the tail (feature size 0.02: with 0.05 the mesh crosses itself).
//! Read from tests/data, where this made it (meshing it takes a minute and a half):
//!   sdflow shape --expr "min(sqrt(x^2+y^2+z^2)-1, sqrt((x<0.9)*(x-0.9)^2+(x>2.2)*(x-2.2)^2+y^2+z^2)-0.04)"
//!     --box -1.2,-1.2,-1.2,2.4,1.2,1.2 --feature-size 0.02 --edge-length 0.1 --edges-per-radius 4
//!     -o tests/data/body-with-thin-tail.off
Mesh body_with_thin_tail()
{
  Mesh body = read_mesh(std::filesystem::path(SDFLOW_SOURCE_DIR) / "tests/data/body-with-thin-tail.off").mesh;
  // One closed body of genus 0 with its tail: the mesh's tip is at x = 1.96, the remeshing having
  // rounded off the last quarter of the level set's thin end.
  const std::vector<ComponentTopology> parts = component_topology(body);
  EXPECT_EQ(parts.size(), 1u);
  EXPECT_EQ(parts.front().genus, 0);
  EXPECT_GT(largest_x(body), kTailEnd - 0.25);
  return body;
}

TEST(ResolutionCheck, names_a_tail_thinner_than_the_finest_edge_and_the_edge_length_that_resolves_it)
{
  const Mesh body = body_with_thin_tail();
  // Resolved: the finest edge of ℓ = 0.2 is 0.05, below the tail's diameter 0.08.
  EXPECT_FALSE(thinnest_unresolved_part(body, {.edge_length = 0.2}));
  // Not resolved: ℓ = 0.4 makes no edge shorter than 0.1.
  const std::optional<ThinPart> thin = thinnest_unresolved_part(body, {.edge_length = 0.4});
  ASSERT_TRUE(thin);
  EXPECT_FALSE(thin->gap);
  // The diameter along the tail; rays near the tip's cap leave through the cap, a little shorter.
  EXPECT_LE(thin->size, 2 * kTailRadius * 1.05);
  EXPECT_GE(thin->size, 2 * kTailRadius * 0.7);
  EXPECT_GT(thin->where.x(), 0.9); // on the tail, not on the sphere
  EXPECT_NEAR(thin->finest_edge, 0.1, 1e-12);
  // The ℓ it proposes resolves it, and is not needlessly fine.
  EXPECT_LE(0.25 * thin->resolving_edge_length, thin->size);
  EXPECT_GT(0.25 * thin->resolving_edge_length, 0.9 * thin->size);
  EXPECT_FALSE(thinnest_unresolved_part(body, {.edge_length = thin->resolving_edge_length}));
  // A uniform ℓ (the paper's practice) makes no edge much shorter than ℓ: 0.2 does not resolve the
  // tail, and the ℓ proposed passes the check, although sampled that finely the tail's root shows
  // thinner (0.051 against 0.060 at ℓ = 0.2).
  const std::optional<ThinPart> uniform = thinnest_unresolved_part(body, {.edge_length = 0.2, .edges_per_radius = 0});
  ASSERT_TRUE(uniform);
  EXPECT_NEAR(uniform->finest_edge, 0.2, 1e-12);
  EXPECT_LT(uniform->resolving_edge_length, uniform->size);
  EXPECT_FALSE(thinnest_unresolved_part(body, {.edge_length = uniform->resolving_edge_length, .edges_per_radius = 0}));
  const std::string message = describe_thin_part(*thin, 0.4);
  EXPECT_NE(message.find(fmt::format("--edge-length {:.2g}", thin->resolving_edge_length)), std::string::npos)
      << message;
}

// A spike pulled out to one far vertex has no vertex where it is thin: its long edges are sampled
// (the fuzzer's mesh that passed the check and left nothing after the second re-triangulation).
TEST(ResolutionCheck, finds_a_spike_between_the_vertices_of_its_long_edges)
{
  Mesh sphere = analytic::icosphere(2); // 162 vertices, edges about 0.3
  const auto tip = sphere.vertex_handle(0);
  sphere.set_point(tip, sphere.point(tip) * 10);
  const double ell = mean_edge_length(sphere);
  for (const auto v : sphere.vertices()) {
    if (v != tip) {
      ASSERT_LT(sphere.point(v).norm(), 1 + 1e-9) << "the spike's only vertex off the sphere is its tip";
    }
  }
  const std::optional<ThinPart> thin = thinnest_unresolved_part(sphere, {.edge_length = ell});
  ASSERT_TRUE(thin) << "the spike is thinner than the finest edge along most of its length";
  EXPECT_LT(thin->size, thin->finest_edge);
  EXPECT_GT(thin->where.norm(), 1.5) << "found on the spike";
  // Thin along its length, where the input has no vertex: measured at the points sampled there.
  EXPECT_GE(thin->vertices, 10);
  // The ℓ it proposes makes the sizing fine enough where it measured.
  EXPECT_LE(0.25 * thin->resolving_edge_length, thin->size);
}

// Issue 32: a thin part is resolved, not refused, when the run can afford it. With the automatic
// ℓ the run takes the ℓ that resolves the part (set in the parameters, so the flow and run.toml
// use it); a part so thin that resolving it would outgrow what a run takes by itself is refused
// before step 1, in each front end's words, with that ℓ; an ℓ the user gave is kept, with a warning.
TEST(ResolutionCheck, a_run_takes_the_edge_length_that_resolves_a_thin_part_within_its_size_bound)
{
  const Mesh body = body_with_thin_tail();
  RunParameters p;
  p.steps = 2;
  p.snapshot_every = 0;
  // A sizing that never refines below 0.7 ℓ (ℓ the mean edge, about 0.1) cannot resolve the tail,
  // which asks for an ℓ less than 1.5 times finer.
  p.retriangulation.pipeline.min_edge_fraction = 0.7;
  RetriangulationOptions at_mean = p.retriangulation.pipeline;
  at_mean.edge_length = mean_edge_length(body);
  const std::optional<ThinPart> thin = thinnest_unresolved_part(body, at_mean);
  ASSERT_TRUE(thin);
  const std::pair<FrontEnd, std::string> words[] = {
      {FrontEnd::command_line, "--edge-length"},
      {FrontEnd::python, "retriangulation={\"edge_length\": "},
      {FrontEnd::meshlab, "(EdgeLength) = "}};
  for (const auto& [front_end, setting] : words) {
    RunParameters q = p;
    Mesh mesh = body;
    check_run_input(mesh, q, "body.off", front_end, run_input_limits(front_end, false));
    EXPECT_DOUBLE_EQ(q.retriangulation.pipeline.edge_length, thin->resolving_edge_length);
    EXPECT_LT(q.retriangulation.pipeline.edge_length, at_mean.edge_length);
  }
  test::TempDir dir;
  {
    RunParameters q = p;
    Mesh mesh = body;
    check_run_input(mesh, q, "body.off", FrontEnd::command_line, run_input_limits(FrontEnd::command_line, false));
    q.output_dir = dir / "resolved";
    const SimulationResult r = run_simulation(mesh, {.parameters = q});
    EXPECT_EQ(r.steps, 2);
    EXPECT_NE(test::read_file(dir / "resolved/run.toml").find(fmt::format("edge_length = {}", thin->resolving_edge_length)),
              std::string::npos)
        << "run.toml keeps the ℓ the check chose";
  }
  // The same coarser ℓ given explicitly: kept, and the run goes on.
  RunParameters asked = p;
  asked.retriangulation.pipeline.edge_length = at_mean.edge_length;
  Mesh mesh = body;
  EXPECT_NO_THROW(check_run_input(mesh, asked, "body.off", FrontEnd::command_line,
                                  run_input_limits(FrontEnd::command_line, false)));
  EXPECT_EQ(asked.retriangulation.pipeline.edge_length, at_mean.edge_length);
  asked.output_dir = dir / "asked";
  EXPECT_EQ(run_simulation(mesh, {.parameters = asked}).steps, 2);

  // A sheet 1 × 1 and 0.003 thick on edges of about 0.1: resolving it takes an ℓ of about 0.003,
  // 35 times finer, more than a run refines by itself.
  const Mesh sheet = test::cad_plate(1, 1, 0.003, 10, 10);
  for (const auto& [front_end, setting] : words) {
    RunParameters q = p;
    Mesh plate = sheet;
    try {
      check_run_input(plate, q, "sheet.off", front_end, run_input_limits(front_end, false));
      ADD_FAILURE() << "the run should have refused the sheet";
    } catch (const InvalidParameter& e) {
      const std::string text = e.what();
      EXPECT_NE(text.find(setting), std::string::npos) << text;
      EXPECT_NE(text.find("only 0.003"), std::string::npos) << "how thin: " << text;
      EXPECT_NE(text.find("more than a run refines by itself"), std::string::npos) << text;
    }
  }
  // A sheet 1 × 1.25, 0.0052 thick on a fine grid (edges of about 0.01): resolving it is less than
  // 1.5 times finer, but the sheet would then have some 55 000 vertices, more than a run takes by
  // itself.
  RunParameters q = p;
  Mesh fine_sheet = test::cad_plate(1, 1.25, 0.0052, 120, 150);
  try {
    check_run_input(fine_sheet, q, "sheet.off", FrontEnd::command_line, run_input_limits(FrontEnd::command_line, false));
    ADD_FAILURE() << "the run should have refused the sheet";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("more than a run takes by itself (50000)"), std::string::npos) << e.what();
  }
}

// A run refines its ℓ by itself up to 2.5 times its mean edge (CGAL's femur.off, asked 2.1 times,
// reaches T; the bound was 1.5 before): a sheet 1 × 1, 0.012 thick on edges of about 0.1, asks for
// about twice, and is run at that ℓ; five times as thin it asks for more and is refused.
TEST(ResolutionCheck, a_run_refines_its_edge_length_up_to_two_and_a_half_times_by_itself)
{
  const Mesh sheet = test::cad_plate(1, 1, 0.012, 10, 10);
  const double mean = mean_edge_length(sheet);
  RunParameters q;
  Mesh mesh = sheet;
  ASSERT_NO_THROW(check_run_input(mesh, q, "sheet.off", FrontEnd::command_line,
                                  run_input_limits(FrontEnd::command_line, false)));
  const double refinement = mean / q.retriangulation.pipeline.edge_length;
  EXPECT_GT(refinement, 1.5) << "the fixture no longer asks for more than the old bound";
  EXPECT_LE(refinement, 2.5);
  EXPECT_FALSE(thinnest_unresolved_part(sheet, q.retriangulation.pipeline)) << "the ℓ taken resolves the sheet";

  RunParameters thinner;
  Mesh thin_sheet = test::cad_plate(1, 1, 0.0024, 10, 10);
  EXPECT_THROW(check_run_input(thin_sheet, thinner, "sheet.off", FrontEnd::command_line,
                               run_input_limits(FrontEnd::command_line, false)),
               InvalidParameter);
}

TEST(ResolutionCheck, a_thin_tail_the_run_resolves_is_evolved_not_cut_off)
{
  const Mesh body = body_with_thin_tail();
  test::TempDir dir;
  RunParameters p;
  p.steps = 8;
  p.snapshot_every = 0;
  p.output_dir = dir / "run";
  const SimulationResult r = run_simulation(body, {.parameters = p});
  const std::vector<ComponentTopology> parts = component_topology(r.mesh);
  ASSERT_EQ(parts.size(), 1u) << "the tail came off";
  EXPECT_EQ(parts.front().genus, 0);
  // The tail is still there, 1.3 long: its tip retracts as the flow rounds it (by 0.24 in these
  // steps, measured), but nothing cut it off.
  EXPECT_GT(largest_x(r.mesh), kTailEnd - 0.5);
}

} // namespace
} // namespace sdflow
