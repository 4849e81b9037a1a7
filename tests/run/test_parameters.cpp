//! Run parameters (parameters.h): scenario files, run.toml round trip, clear errors.
#include "io/temp_dir.h"
#include "run/scenario_errors.h"
#include "sdflow/errors.h"
#include "sdflow/run/parameters.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

TEST(RunParameters, resolved_toml_reads_back_to_the_same_parameters)
{
  test::TempDir dir;
  RunParameters p;
  p.input = dir / "in.ply";
  p.output_dir = dir / "out";
  p.steps = 1600;
  p.end_time = 774.5;
  p.time_step.mode = TimeStepMode::schedule;
  p.time_step.schedule = TauSchedule({{1, 50, 0.01}, {51, 100, 0.02}});
  p.time_step.schedule_retries = 3;
  p.time_step.adaptive.max_displacement = 0.1;
  p.scheme.beta = 0.75;
  p.scheme.boundary = BoundaryCondition::paper; // not the default, so that the round trip shows
  p.scheme.curvature.method = CurvatureMethod::cotangent;
  p.scheme.mass = VertexMass::volume_gradient;
  p.scheme.extrapolate = true;
  p.solver.kind = SolverKind::qr;
  p.conserve_volume = true;
  p.snapshot_every = 7;
  p.reference_centre = {1, 2, 3};
  p.reference_radius = 3;
  p.retriangulation.enabled = true;
  p.retriangulation.every = 3;
  p.retriangulation.min_angle_deg = 12.5;
  p.retriangulation.edge_ratio = 1.8;
  p.retriangulation.degraded_fraction = 0.02;
  p.retriangulation.always = true;
  p.retriangulation.pipeline.edge_length = 0.25;
  p.retriangulation.pipeline.remesh_iterations = 5;
  p.retriangulation.pipeline.normals.neighbours = 24;
  p.retriangulation.pipeline.fill_holes = false;
  p.retriangulation.pipeline.max_hole_length = 7.5;
  p.retriangulation.pipeline.min_component_faces = 40;
  p.retriangulation.pipeline.min_component_thickness = 0.125;
  test::write_file(dir / "run.toml", run_parameters_toml(p));

  RunParameters q;
  read_run_parameters(dir / "run.toml", q);
  EXPECT_EQ(q.input, p.input);
  EXPECT_EQ(q.output_dir, p.output_dir);
  EXPECT_EQ(q.steps, p.steps);
  EXPECT_EQ(q.end_time, p.end_time);
  EXPECT_EQ(q.time_step.mode, TimeStepMode::schedule);
  EXPECT_EQ(q.time_step.schedule.tau_for_step(60), 0.02);
  EXPECT_EQ(q.time_step.schedule_retries, 3);
  EXPECT_EQ(q.time_step.adaptive.max_displacement, 0.1);
  EXPECT_EQ(q.scheme.beta, 0.75);
  EXPECT_EQ(q.scheme.boundary, BoundaryCondition::paper);
  EXPECT_EQ(q.scheme.curvature.method, CurvatureMethod::cotangent);
  EXPECT_EQ(q.scheme.mass, VertexMass::volume_gradient);
  EXPECT_TRUE(q.scheme.extrapolate);
  EXPECT_EQ(q.solver.kind, SolverKind::qr);
  EXPECT_TRUE(q.conserve_volume);
  EXPECT_EQ(q.snapshot_every, 7);
  EXPECT_EQ(q.reference_centre, Eigen::Vector3d(1, 2, 3));
  EXPECT_EQ(q.reference_radius, 3);
  const RetriangulationSchedule& r = q.retriangulation;
  EXPECT_TRUE(r.enabled);
  EXPECT_EQ(r.every, 3);
  EXPECT_EQ(r.min_angle_deg, 12.5);
  EXPECT_EQ(r.edge_ratio, 1.8);
  EXPECT_EQ(r.degraded_fraction, 0.02);
  EXPECT_TRUE(r.always);
  EXPECT_EQ(r.pipeline.edge_length, 0.25);
  EXPECT_EQ(r.pipeline.remesh_iterations, 5);
  EXPECT_EQ(r.pipeline.normals.neighbours, 24);
  EXPECT_FALSE(r.pipeline.fill_holes);
  EXPECT_EQ(r.pipeline.max_hole_length, 7.5);
  EXPECT_EQ(r.pipeline.min_component_faces, 40);
  EXPECT_EQ(r.pipeline.min_component_thickness, 0.125);
}

TEST(RunParameters, every_curvature_name_reads_back_to_its_options)
{
  test::TempDir dir;
  for (const char* name : {"normal_integral", "normal_integral_angle_sum", "cotangent"}) {
    SCOPED_TRACE(name);
    RunParameters p;
    p.scheme.curvature = curvature_options(name);
    EXPECT_EQ(curvature_name(p.scheme.curvature), name);
    test::write_file(dir / "run.toml", run_parameters_toml(p));
    RunParameters q;
    q.scheme.curvature = {.method = CurvatureMethod::cotangent, .normalisation = AngleNormalisation::angle_sum};
    read_run_parameters(dir / "run.toml", q);
    EXPECT_EQ(q.scheme.curvature.method, p.scheme.curvature.method);
    EXPECT_EQ(q.scheme.curvature.normalisation, p.scheme.curvature.normalisation);
  }
  const RunParameters defaults;
  EXPECT_EQ(curvature_name(defaults.scheme.curvature), "cotangent") << "the default must converge off spheres";
  EXPECT_THROW(curvature_options("Cotangent"), InvalidParameter);
  EXPECT_EQ(mass_name(defaults.scheme.mass), "voronoi") << "eq. (10)'s areas stay the default";
  EXPECT_EQ(vertex_mass(mass_name(VertexMass::volume_gradient)), VertexMass::volume_gradient);
  EXPECT_THROW(vertex_mass("Voronoi"), InvalidParameter);
}

TEST(RunParameters, scenario_errors_name_the_file_line_and_key)
{
  test::TempDir dir;
  const test::ScenarioRefusal<> expect_error{dir.path()};
  expect_error("steps = 10\nstpes = 20\n", "s.toml:2: unknown key `stpes`");
  expect_error("beta = \"half\"\n", "`beta` has the wrong type");
  expect_error("solver = \"lu\"\n", "solver must be");
  expect_error("steps = 1\ncurvature = \"laplacian\"\n", "s.toml:2: curvature must be \"normal_integral\"");
  expect_error("mass = \"barycentric\"\n", "s.toml:1: mass must be \"voronoi\" or \"volume_gradient\"");
  expect_error("[adaptive]\ngrowht = 2\n", "unknown key `adaptive.growht`");
  expect_error("steps = [\n", "s.toml:");
  expect_error("[retriangulation]\neverey = 2\n", "s.toml:2: unknown key `retriangulation.everey`");
  expect_error("retriangulation = true\n", "`retriangulation` must be a table");
}

TEST(RunParameters, validation_requires_a_stop_condition_and_sane_values)
{
  RunParameters p;
  EXPECT_THROW(validate_run_parameters(p), InvalidParameter);
  p.steps = 10;
  EXPECT_NO_THROW(validate_run_parameters(p));
  p.scheme.beta = -1;
  EXPECT_THROW(validate_run_parameters(p), InvalidParameter);
  p.scheme.beta = 0.5;
  p.time_step.mode = TimeStepMode::constant;
  EXPECT_THROW(validate_run_parameters(p), InvalidParameter) << "constant mode without τ";
  p.time_step.mode = TimeStepMode::adaptive;
  p.retriangulation.every = 0;
  EXPECT_THROW(validate_run_parameters(p), InvalidParameter);
  p.retriangulation.every = 1;
  p.retriangulation.edge_ratio = 1;
  EXPECT_THROW(validate_run_parameters(p), InvalidParameter);
  p.retriangulation.edge_ratio = 2;
  p.retriangulation.degraded_fraction = 1;
  EXPECT_THROW(validate_run_parameters(p), InvalidParameter);
  p.retriangulation.degraded_fraction = 0;
  p.retriangulation.pipeline.normals.neighbours = 2;
  EXPECT_THROW(validate_run_parameters(p), InvalidParameter);
}

TEST(RunParameters, paper_preset_selects_the_papers_scheme_and_keys_override_it)
{
  test::TempDir dir;
  RunParameters paper;
  apply_preset("paper", paper);
  EXPECT_EQ(curvature_name(paper.scheme.curvature), "normal_integral");
  EXPECT_EQ(paper.scheme.mass, VertexMass::voronoi);
  EXPECT_FALSE(paper.scheme.extrapolate);
  EXPECT_EQ(paper.retriangulation.pipeline.edges_per_radius, 0);
  EXPECT_FALSE(paper.retriangulation.restore_volume);
  EXPECT_FALSE(paper.retriangulation.pipeline.curved_projection);
  EXPECT_FALSE(paper.retriangulation.local);
  EXPECT_FALSE(paper.retriangulation.local_surgery);
  RunParameters back = paper;
  apply_preset("default", back);
  EXPECT_EQ(curvature_name(back.scheme.curvature), "cotangent");
  EXPECT_TRUE(back.retriangulation.local);
  EXPECT_TRUE(back.retriangulation.local_surgery);
  EXPECT_EQ(back.retriangulation.pipeline.edges_per_radius, RunParameters{}.retriangulation.pipeline.edges_per_radius);
  EXPECT_TRUE(back.retriangulation.restore_volume);
  EXPECT_THROW(apply_preset("Paper", back), InvalidParameter);

  // In a scenario the preset comes first, whatever the order of the keys.
  test::write_file(dir / "s.toml", "curvature = \"cotangent\"\npreset = \"paper\"\nsteps = 1\n");
  RunParameters p;
  read_run_parameters(dir / "s.toml", p);
  EXPECT_EQ(curvature_name(p.scheme.curvature), "cotangent");
  EXPECT_FALSE(p.retriangulation.restore_volume);
  // The resolved parameters read back to the same scheme without the preset key.
  test::write_file(dir / "run.toml", run_parameters_toml(p));
  RunParameters q;
  read_run_parameters(dir / "run.toml", q);
  EXPECT_EQ(curvature_name(q.scheme.curvature), "cotangent");
  EXPECT_FALSE(q.retriangulation.restore_volume);
  EXPECT_EQ(q.retriangulation.pipeline.edges_per_radius, 0);
  test::write_file(dir / "bad.toml", "steps = 1\npreset = \"fast\"\n");
  try {
    read_run_parameters(dir / "bad.toml", p);
    FAIL() << "accepted";
  } catch (const InvalidParameter& e) {
    EXPECT_NE(std::string(e.what()).find("bad.toml:2: preset must be"), std::string::npos) << e.what();
  }
  RunParameters tolerance_alone;
  tolerance_alone.steps = 1;
  tolerance_alone.time_step.adaptive.tolerance = 1e-3;
  EXPECT_THROW(validate_run_parameters(tolerance_alone), InvalidParameter) << "needs extrapolated steps";
}
} // namespace
} // namespace sdflow
