//! A run's input too coarse to re-triangulate at its mean edge length (run/coarse_input.h): a cube,
//! a tetrahedron and an octahedron as their 8, 4 and 6 vertices run with the defaults, refined
//! exactly (the same volume to rounding) to an ℓ that stays the run's, resumed runs included; the
//! cube relaxes to the sphere of its volume; a CAD part cut into slivers is refined for the flow;
//! an ℓ given too coarse is still refused; a small body beside a large one is refined within the
//! bound, or refused beyond it.
#include "io/temp_dir.h"
#include "sdflow/errors.h"
#include "sdflow/flow/refinement.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/limits.h"
#include "sdflow/retri/input_checks.h"
#include "sdflow/run/coarse_input.h"
#include "sdflow/run/run_input.h"
#include "sdflow/run/simulation.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <array>

#include <cmath>
#include <numbers>
#include <string>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

//! The refinement moves no point off the surface: the volume changes by rounding only.
constexpr double kRefinedVolume = 1e-13;
//! Relative volume drift of the default flow over these runs: the discrete flow's own at the
//! corners (measured 0.49% for the octahedron, 0.72% for the cube and 1.0% for the tetrahedron to
//! t = 0.01; halving ℓ about halves it), not the refinement's, which keeps the volume to rounding.
constexpr double kFlowVolumeDrift = 1.5e-2;

//! `input` through the checks of `sdflow run` with the defaults (re-triangulation on, ℓ not
//! given), as the run starts from it.
Mesh prepared(const Mesh& input, RunParameters p)
{
  Mesh mesh = input;
  check_run_input(mesh, p, "solid.off", FrontEnd::command_line, run_input_limits(FrontEnd::command_line, false));
  return mesh;
}

RunParameters defaults(const fs::path& out, double end_time)
{
  RunParameters p;
  p.output_dir = out;
  p.end_time = end_time;
  return p;
}

// The run's ℓ is the refined surface's mean edge length, written to run.toml with the refinement
// factor s that ℓ gives; the run reaches its end time with one body of genus 0 and its volume.
TEST(CoarseInput, a_tetrahedron_and_an_octahedron_run_to_the_end_time_keeping_volume_and_topology)
{
  constexpr double end_time = 2e-3;
  for (const Mesh& solid : {analytic::regular_tetrahedron(), analytic::regular_octahedron()}) {
    SCOPED_TRACE(solid.n_vertices());
    test::TempDir dir;
    const RunParameters p = defaults(dir / "run", end_time);
    const Mesh start = prepared(solid, p);
    EXPECT_GE(start.n_vertices(), static_cast<std::size_t>(kCoarseInputVertices));
    const double volume = enclosed_volume(solid);
    EXPECT_NEAR(enclosed_volume(start), volume, kRefinedVolume * volume);
    const SimulationResult result = run_simulation(start, {.parameters = p});
    EXPECT_NEAR(result.time, end_time, 1e-12 * end_time);
    EXPECT_EQ(count_topology(result.mesh), (TopologyCount{.components = 1, .genus = 0, .boundary_loops = 0}));
    EXPECT_NEAR(enclosed_volume(result.mesh), volume, kFlowVolumeDrift * volume);
    RunParameters written;
    read_run_parameters(dir / "run/run.toml", written);
    // The run sums the edge lengths in the order of its own copy of the mesh: rounding apart.
    const double ell = mean_edge_length(start);
    EXPECT_NEAR(written.retriangulation.pipeline.edge_length, ell, 1e-12 * ell);
    EXPECT_NEAR(written.refinement, automatic_refinement(start, ell), 1e-12);
  }
}

// A cube of 8 vertices runs until it is nearly round: the distances of its vertices from the
// solid's centroid approach the radius R = (3V/4π)^⅓ of the sphere of its volume, from a spread of
// 0.6 R (corners at √3/2, face centres at ½) to 0.65% of R at t = 0.01 (measured), their mean 0.6%
// above R (vertices of a polyhedron around the sphere).
TEST(CoarseInput, a_cube_relaxes_to_the_sphere_of_its_volume)
{
  test::TempDir dir;
  const RunParameters p = defaults(dir / "run", 1e-2);
  const Mesh start = prepared(analytic::cube(), p);
  EXPECT_NEAR(enclosed_volume(start), 1.0, kRefinedVolume);
  struct Distances {
    double spread = 0, mean = 0; // relative to R
  };
  const auto distances = [](const Mesh& mesh) {
    // About the solid's centroid: the vertices' mean follows where the remeshing put more of them.
    const VertexVectors x = vertex_positions(mesh);
    Eigen::RowVector3d centre = Eigen::RowVector3d::Zero();
    double six_volume = 0;
    for (const auto f : mesh.faces()) {
      std::array<Eigen::RowVector3d, 3> p;
      int k = 0;
      for (const auto v : mesh.fv_range(f))
        p[k++] = x.row(v.idx());
      const double tetrahedron = p[0].dot(p[1].cross(p[2]));
      six_volume += tetrahedron;
      centre += tetrahedron * (p[0] + p[1] + p[2]) / 4;
    }
    centre /= six_volume;
    const double radius = std::cbrt(3 * enclosed_volume(mesh) / (4 * std::numbers::pi));
    Distances d;
    for (Eigen::Index v = 0; v < x.rows(); ++v) {
      const double r = (x.row(v) - centre).norm() / radius;
      d.spread = std::max(d.spread, std::abs(r - 1));
      d.mean += r / static_cast<double>(x.rows());
    }
    return d;
  };
  EXPECT_GT(distances(start).spread, 0.3);
  const SimulationResult result = run_simulation(start, {.parameters = p});
  EXPECT_NEAR(result.time, 1e-2, 1e-14);
  EXPECT_EQ(count_topology(result.mesh), (TopologyCount{.components = 1, .genus = 0, .boundary_loops = 0}));
  EXPECT_NEAR(enclosed_volume(result.mesh), 1.0, kFlowVolumeDrift);
  const Distances end = distances(result.mesh);
  EXPECT_LT(end.spread, 0.015);
  EXPECT_NEAR(end.mean, 1.0, 0.01);
}

// A CAD part cut into slivers (like CGAL's mpi.off) is re-triangulable at its mean edge length but
// gets only a few dozen vertices there: run at it, the first remeshing flattened the frame's
// section into a few triangles and its area grew (1024 → 1090) under a flow that lowers it. It is
// refined to the flow's few hundred vertices instead, and runs with its genus, its area falling.
TEST(CoarseInput, a_cad_part_cut_into_slivers_is_refined_for_the_flow)
{
  const Mesh frame = analytic::fanned_frame(4);
  RetriangulationOptions options;
  EXPECT_GE(estimated_vertices(surface_area(frame), mean_edge_length(frame)), retriangulation_vertex_need(options));
  test::TempDir dir;
  const RunParameters p = defaults(dir / "run", 0.1);
  const Mesh start = prepared(frame, p);
  EXPECT_GE(start.n_vertices(), static_cast<std::size_t>(kCoarseInputVertices));
  const double area = surface_area(frame), volume = enclosed_volume(frame);
  EXPECT_NEAR(area, 1024, 1e-9);
  EXPECT_NEAR(enclosed_volume(start), volume, kRefinedVolume * volume);
  const SimulationResult result = run_simulation(start, {.parameters = p});
  EXPECT_EQ(count_topology(result.mesh), (TopologyCount{.components = 1, .genus = 1, .boundary_loops = 0}));
  EXPECT_LT(surface_area(result.mesh), area);
  EXPECT_NEAR(enclosed_volume(result.mesh), volume, kFlowVolumeDrift * volume);
}

// A resumed run continues with the ℓ chosen at the start (run.toml holds it as a number): stopped
// at step 10 and resumed to step 20, it ends bit for bit where an uninterrupted run does.
TEST(CoarseInput, a_resumed_run_keeps_the_chosen_edge_length)
{
  test::TempDir dir;
  RunParameters p = defaults(dir / "whole", std::numeric_limits<double>::infinity());
  p.steps = 20;
  const Mesh start = prepared(analytic::cube(), p);
  const SimulationResult whole = run_simulation(start, {.parameters = p});
  p.output_dir = dir / "stopped";
  p.steps = 10;
  run_simulation(start, {.parameters = p});
  RunParameters resumed;
  read_run_parameters(dir / "stopped/run.toml", resumed);
  resumed.output_dir = dir / "stopped";
  resumed.steps = 20;
  const SimulationResult second = resume_simulation({.parameters = resumed});
  EXPECT_EQ(second.steps, 20);
  EXPECT_EQ(vertex_positions(second.mesh), vertex_positions(whole.mesh));
  EXPECT_EQ(face_indices(second.mesh), face_indices(whole.mesh));
}

// An ℓ the user gave is the user's: too coarse, the run is refused as before (exit 2 in the
// command line) and the surface is left as it was. For a single body the size check refuses it
// first; a small body beside a large one gets the re-triangulation's message with the ℓ that does.
TEST(CoarseInput, an_edge_length_given_too_coarse_is_still_refused)
{
  const auto refusal = [](Mesh& mesh, RunParameters p) -> std::string {
    try {
      check_run_input(mesh, p, "solid.off", FrontEnd::command_line, run_input_limits(FrontEnd::command_line, false));
    } catch (const Error& e) {
      return e.what();
    }
    return "";
  };
  RunParameters p = defaults("unused", 1e-2);
  Mesh cube = analytic::cube();
  p.retriangulation.pipeline.edge_length = mean_edge_length(cube);
  const std::string message = refusal(cube, p);
  EXPECT_NE(message.find("fewer than the 20 it needs to keep its shape"), std::string::npos) << message;
  EXPECT_EQ(cube.n_vertices(), 8u);
  Mesh scene = analytic::disjoint_union(analytic::icosphere(3), analytic::cube(0.1, {5, 0, 0}));
  p.retriangulation.pipeline.edge_length = mean_edge_length(scene);
  const std::string small = refusal(scene, p);
  EXPECT_NE(small.find("solid.off: component 1 (area 0.06) is too coarse to re-triangulate"), std::string::npos)
      << small;
  EXPECT_NE(small.find("Give --edge-length "), std::string::npos) << small;
  EXPECT_EQ(scene.n_vertices(), 650u);
  // Without re-triangulation the flow needs no neighbourhoods: the cube is taken as it is.
  p.retriangulation.enabled = false;
  EXPECT_EQ(refusal(cube, p), "");
  EXPECT_EQ(cube.n_vertices(), 8u);
}

// A unit cube beside a sphere of radius 10: refining for the cube's 300 vertices would give the
// scene some 63 000, so ℓ is set by the bound and the cube gets fewer, still twice what the
// re-triangulation needs. Beside a sphere of radius 100 even that is out of reach: refused.
TEST(CoarseInput, a_small_body_beside_a_large_one_is_refined_within_the_bound_or_refused)
{
  const RetriangulationOptions options;
  const Mesh scene = analytic::disjoint_union(analytic::icosphere(2, 10), analytic::cube(1, {20, 0, 0}));
  const std::optional<double> ell = coarse_input_edge_length(scene, options, "scene.off");
  ASSERT_TRUE(ell);
  EXPECT_LE(estimated_vertices(surface_area(scene), *ell), kCoarseInputMaxVertices * (1 + 1e-12));
  EXPECT_GE(estimated_vertices(6, *ell), 2 * retriangulation_vertex_need(options));
  EXPECT_LT(estimated_vertices(6, *ell), kCoarseInputVertices);
  const Mesh far = analytic::disjoint_union(analytic::icosphere(2, 100), analytic::cube(1, {200, 0, 0}));
  try {
    coarse_input_edge_length(far, options, "scene.off");
    ADD_FAILURE() << "refused no scene beyond the bound";
  } catch (const InvalidMesh& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("component 1 (area 6) is too coarse"), std::string::npos) << message;
    EXPECT_NE(message.find("more than the 50000 a run refines to by itself"), std::string::npos) << message;
  }
  // A surface fine enough at its mean edge length is left to the run as it is.
  EXPECT_FALSE(coarse_input_edge_length(analytic::icosphere(3), options, "sphere.off"));
}

} // namespace
} // namespace sdflow
