//! The flow in memory (surface_diffusion.h): no files, the same states a run directory records,
//! its state restored bit for bit, its notes.
#include "io/temp_dir.h"
#include "sdflow/errors.h"
#include "sdflow/flow/surface_diffusion.h"
#include "sdflow/geometry/measures.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/run/simulation.h"
#include "sdflow/shapes/catalogue.h"
#include "sdflow/shapes/mesher.h"
#include "sdflow/spatial/intersect.h"
#include "support/analytic_meshes.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <vector>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> lines_of(const fs::path& file)
{
  std::ifstream in(file);
  std::vector<std::string> lines;
  for (std::string line; std::getline(in, line);)
    lines.push_back(line + '\n');
  return lines;
}

RunParameters adaptive_run(long steps)
{
  RunParameters p;
  p.steps = steps;
  p.retriangulation.enabled = false;
  return p;
}

TEST(SurfaceDiffusion, a_dumbbell_pinches_off_in_memory_exactly_as_its_recorded_run)
{
  // The paper's dumbbell at half size (1000 vertices), to its pinch-off.
  const Mesh start =
      mesh_implicit_surface(dumbbell_shape({.radius = 3, .separation = 9}), {.edge_length = 0.5}).mesh;
  RunParameters p;
  p.end_time = 1.0;
  p.stop_at_topology_change = true;
  p.retriangulation.enabled = true;

  SurfaceDiffusion flow(start, p);
  std::vector<std::string> rows{metrics_row(0, 0, 0, flow.metrics(), {})};
  std::vector<std::string> events;
  StepRecord last_step;
  long faces_before_last = 0;
  while (!flow.finished()) {
    faces_before_last = static_cast<long>(flow.mesh().n_faces());
    last_step = flow.step();
    rows.push_back(
        metrics_row(flow.steps(), flow.time(), last_step.tau, flow.metrics(), event_names(last_step.events)));
    events.push_back(event_names(last_step.events));
  }
  // (after the trials it rejected, if any)
  EXPECT_TRUE(events.back().ends_with("remeshed+surgery+split")) << "the last step's re-triangulation should cut the "
                                                                    "neck: "
                                                                 << events.back();
  // The events carry what the re-triangulation measured: one body into two where the flow's neck
  // crossed itself, thinner there than the run's ℓ; the faces it had, made and rebuilt.
  ASSERT_FALSE(last_step.events.empty());
  const StepEvent& split = last_step.events.back();
  ASSERT_EQ(split.kind, StepEventKind::split);
  EXPECT_EQ(split.step, flow.steps());
  EXPECT_EQ(split.time, flow.time());
  ASSERT_TRUE(split.retriangulation.has_value());
  const RetriangulationMeasures& m = *split.retriangulation;
  EXPECT_EQ(m.before, (TopologyCount{.components = 1}));
  EXPECT_EQ(m.after, (TopologyCount{.components = 2}));
  EXPECT_GT(m.crossing_pairs, 0);
  EXPECT_TRUE(std::isfinite(m.crossing_size));
  EXPECT_GE(m.crossing_size, 0.0);
  EXPECT_LT(m.crossing_size, flow.options().retriangulation.pipeline.edge_length);
  EXPECT_EQ(m.faces_before, faces_before_last);
  EXPECT_EQ(m.faces_after, static_cast<long>(flow.mesh().n_faces()));
  EXPECT_GT(m.faces_rebuilt, 0);
  EXPECT_LE(m.faces_rebuilt, m.faces_before);
  EXPECT_GT(std::abs(m.volume_restored), 0.0) << "the rebuilt neck's volume is given back";
  EXPECT_LT(std::abs(m.volume_restored), 1e-2);
  EXPECT_NE(split.detail.find("topology changed (components 1 → 2"), std::string::npos) << split.detail;
  for (const StepEvent& e : last_step.events) // one re-triangulation, the same measures on each of its events
    if (e.retriangulation) {
      EXPECT_EQ(e.retriangulation->faces_rebuilt, m.faces_rebuilt) << event_name(e.kind);
    }
  const auto parts = component_topology(flow.mesh());
  ASSERT_EQ(parts.size(), 2u);
  for (const auto& c : parts)
    EXPECT_TRUE(c.closed());

  // The same flow recorded in a run directory: the same rows, the same last surface.
  test::TempDir dir;
  p.output_dir = dir / "run";
  p.snapshot_every = 0;
  const SimulationResult recorded = run_simulation(start, {.parameters = p});
  const std::vector<std::string> written = lines_of(dir / "run/metrics.csv");
  ASSERT_EQ(written.size(), rows.size() + 1);
  EXPECT_EQ(written[0], std::string(metrics_header) + '\n');
  for (std::size_t i = 0; i < rows.size(); ++i)
    EXPECT_EQ(written[i + 1], rows[i]) << "row " << i;
  EXPECT_EQ(vertex_positions(recorded.mesh), vertex_positions(flow.mesh()));
  const Mesh last = read_mesh(dir / fmt::format("run/snapshots/step_{:06d}.ply", flow.steps())).mesh;
  EXPECT_EQ(vertex_positions(last), vertex_positions(flow.mesh()));
  EXPECT_EQ(face_indices(last), face_indices(flow.mesh()));
}

//! A unit icosphere (642 vertices) whose vertices are moved radially by uniform noise of ±a fifth
//! of its mean edge length: noise the mesh does not resolve (|ΔH| h³ of order 20).
Mesh noisy_sphere()
{
  Mesh sphere = analytic::icosphere(3, 1.0);
  const double ell = mean_edge_length(sphere);
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> noise(-0.2 * ell, 0.2 * ell);
  for (const auto v : sphere.vertices()) {
    const Eigen::Vector3d p = to_eigen(sphere.point(v));
    sphere.set_point(v, to_point(p * (1 + noise(rng))));
  }
  return sphere;
}

//! Root-mean-square over the vertices of the difference between a vertex's distance to the origin
//! and the mean of its neighbours': the roughness at the scale of the edges, which a sphere's own
//! radius, or a smooth change of it, does not have.
double edge_scale_roughness(const Mesh& mesh)
{
  double squares = 0;
  for (const auto v : mesh.vertices()) {
    double sum = 0;
    int count = 0;
    for (const auto w : mesh.vv_range(v)) {
      sum += to_eigen(mesh.point(w)).norm();
      ++count;
    }
    const double d = to_eigen(mesh.point(v)).norm() - sum / count;
    squares += d * d;
  }
  return std::sqrt(squares / static_cast<double>(mesh.n_vertices()));
}

TEST(SurfaceDiffusion, start_steps_damp_noise_keep_the_volume_and_free_the_pace)
{
  const Mesh start = noisy_sphere();
  const double volume = enclosed_volume(start);
  // The same flow without start steps: the noise holds τ down step after step.
  RunParameters without = adaptive_run(12);
  without.time_step.adaptive.start_steps = 0;
  SurfaceDiffusion slow(start, without);
  double slow_tau = 0;
  while (!slow.finished())
    slow_tau = std::max(slow_tau, slow.step().tau);

  SurfaceDiffusion flow(start, adaptive_run(12));
  int start_steps = 0;
  double largest_tau = 0, roughness_after_start = 0;
  while (!flow.finished()) {
    const StepRecord step = flow.step();
    largest_tau = std::max(largest_tau, step.tau);
    if (step.start) {
      ++start_steps;
      ASSERT_FALSE(step.events.empty());
      EXPECT_EQ(step.events.front().kind, StepEventKind::start) << event_names(step.events);
      // Each start step gives every closed component its volume back.
      EXPECT_NEAR(enclosed_volume(flow.mesh()), volume, 1e-9 * volume) << "step " << flow.steps();
      roughness_after_start = edge_scale_roughness(flow.mesh());
    }
  }
  EXPECT_GE(start_steps, 1);
  EXPECT_LE(start_steps, flow.options().time_step.adaptive.start_steps);
  // The start steps take most of the noise at the scale of the edges away (measured: 0.0189 to
  // 0.0056), and the pace is then freer: τ reached 2.8e-4 against 7.1e-5 without them.
  EXPECT_LT(roughness_after_start, 0.5 * edge_scale_roughness(start));
  EXPECT_GT(largest_tau, 3 * slow_tau);
  EXPECT_NEAR(enclosed_volume(flow.mesh()), volume, 1e-3 * volume);
}

TEST(SurfaceDiffusion, the_runs_start_steps_damp_noise_beside_smooth_parts_at_once)
{
  // Noise of ±0.45 of an edge on the upper half only: damping it moves the smooth vertices beside
  // it too, by more than the displacement bound, which made start trials fail and shrink τ (as on
  // CGAL's bunny00.off, whose start steps then gave way to τ ≈ 10⁻¹² and a crawl).
  Mesh start = analytic::icosphere(3, 1.0);
  const double ell = mean_edge_length(start);
  std::mt19937 rng(32);
  std::uniform_real_distribution<double> noise(-0.45 * ell, 0.45 * ell);
  for (const auto v : start.vertices())
    if (const Eigen::Vector3d p = to_eigen(start.point(v)); p.z() > 0)
      start.set_point(v, to_point(p * (1 + noise(rng))));
  const double roughness = edge_scale_roughness(start);
  SurfaceDiffusion flow(start, adaptive_run(3));
  while (!flow.finished()) {
    const StepRecord step = flow.step();
    EXPECT_TRUE(step.start) << "step " << step.step;
    EXPECT_EQ(step.rejections, 0) << "step " << step.step;
  }
  EXPECT_LT(edge_scale_roughness(flow.mesh()), 0.5 * roughness); // measured: 0.32 of it
}

//! A re-triangulation that leaves edge-scale noise on a smooth surface at step `at` (the vertices
//! moved along their direction from the origin by up to 20% of the mean edge length), as a fresh patch of triangles does.
RetriangulationHook roughening_at(long at)
{
  return [at](Mesh& mesh, const RetriangulationContext& context) {
    RetriangulationReport report;
    if (context.step != at)
      return report;
    const double ell = mean_edge_length(mesh);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> noise(-0.2 * ell, 0.2 * ell);
    for (const auto v : mesh.vertices()) {
      const Eigen::Vector3d p = to_eigen(mesh.point(v));
      mesh.set_point(v, to_point(p * (1 + noise(rng) / p.norm())));
    }
    report.remeshed = true;
    report.detail = "roughened";
    return report;
  };
}

TEST(SurfaceDiffusion, the_first_step_on_a_new_triangulation_damps_what_it_does_not_resolve)
{
  // Four steps on a smooth ellipsoid, then a "re-triangulation" that roughens it at the edges'
  // scale, as fresh triangles around a closing neck are. The next step is a backward-Euler start
  // step (time_step.h), no longer than the adaptive rule's, with the volume given back after it;
  // without start steps (the paper's preset has none) it is a regular step, whose β = ½ flips the
  // noise: its displacement bound rejects the rule's τ (measured: τ 0.222 with the start step,
  // 0.0234 without, after a rejection).
  double tau_after[2] = {0, 0};
  for (const int start_steps : {3, 0}) {
    SCOPED_TRACE(fmt::format("start_steps = {}", start_steps));
    RunParameters p = adaptive_run(6);
    p.retriangulation.enabled = true;
    p.time_step.adaptive.start_steps = start_steps;
    SurfaceDiffusion flow(analytic::ellipsoid(2, 5, 4, 3), p, roughening_at(4));
    double tau_before = 0, roughened_volume = 0, roughness = 0;
    while (!flow.finished()) {
      const StepRecord record = flow.step();
      if (record.step < 4) {
        EXPECT_FALSE(record.start) << "the smooth ellipsoid is resolved: no start step at step " << record.step;
      } else if (record.step == 4) {
        tau_before = record.tau;
        roughened_volume = enclosed_volume(flow.mesh()); // after the hook ran
        roughness = edge_scale_roughness(flow.mesh());
      } else if (record.step == 5) {
        EXPECT_EQ(record.start, start_steps > 0) << event_names(record.events);
        tau_after[start_steps > 0 ? 0 : 1] = record.tau;
        if (record.start) {
          EXPECT_LE(record.tau, 1.25 * tau_before) << "a start step mid-run takes no more than the rule would";
          EXPECT_NEAR(enclosed_volume(flow.mesh()), roughened_volume, 1e-9 * roughened_volume);
          EXPECT_LT(edge_scale_roughness(flow.mesh()), roughness) << "the step damps the noise";
        }
      }
    }
  }
  EXPECT_GT(tau_after[0], 3 * tau_after[1]) << "the start step keeps the pace the rule had";
}

// At rest nothing bounded adaptive τ: on a unit sphere it grew 1.25 times a step to 10¹¹ by step
// 500, where the β = ½ scheme damps no mode; the volume drifted by 0.2% (1.8% by step 1000) and the
// factorisation failed at step 1027 (issue 33). τ now stops at D⁴, and the sphere stays as it is.
TEST(SurfaceDiffusion, a_surface_at_rest_keeps_its_volume_and_tau_stops_at_its_time_scale)
{
  const Mesh sphere = analytic::icosphere(3);
  RunParameters p;
  p.retriangulation.enabled = false;
  SurfaceDiffusion flow(sphere, p);
  const double volume = enclosed_volume(sphere), largest = std::pow(2 * std::sqrt(3.0), 4); // D = 2√3
  for (int k = 0; k < 600; ++k)
    ASSERT_LE(flow.step().tau, largest * (1 + 1e-9)) << "step " << k + 1;
  EXPECT_GT(flow.time(), 100 * largest); // it did reach the bound, and stepped on at it
  EXPECT_NEAR(enclosed_volume(flow.mesh()), volume, 1e-6 * volume);
}

TEST(SurfaceDiffusion, a_restored_state_continues_bit_for_bit)
{
  for (const bool extrapolate : {false, true}) {
    SCOPED_TRACE(extrapolate ? "extrapolated steps" : "plain steps");
    RunParameters p = adaptive_run(24);
    p.scheme.extrapolate = extrapolate;
    SurfaceDiffusion whole(analytic::ellipsoid(2, 5, 4, 3), p);
    for (int s = 0; s < 12; ++s)
      whole.step();
    const FlowState middle = whole.state();
    while (!whole.finished())
      whole.step();

    SurfaceDiffusion resumed(middle, whole.options());
    EXPECT_EQ(resumed.steps(), 12);
    while (!resumed.finished())
      resumed.step();
    EXPECT_EQ(resumed.time(), whole.time());
    EXPECT_EQ(vertex_positions(resumed.mesh()), vertex_positions(whole.mesh()));
    EXPECT_EQ(resumed.velocity(), whole.velocity());
  }
}

TEST(SurfaceDiffusion, without_retriangulation_a_step_into_a_self_intersection_stops_the_flow_before_it)
{
  // A torus whose hole (radius 0.25) seals within t ≈ 0.013: without re-triangulation its surface
  // would cross itself and go on; the flow stops on the step that would do it, naming the option.
  const Mesh torus = mesh_implicit_surface(torus_shape({.major = 1, .minor = 0.75}), {.vertices = 800}).mesh;
  RunParameters p;
  p.retriangulation.enabled = false;
  p.end_time = 1;
  SurfaceDiffusion flow(torus, p);
  std::string message;
  try {
    while (!flow.finished())
      flow.step();
  } catch (const SolverFailure& e) {
    message = e.what();
  }
  ASSERT_FALSE(message.empty()) << "reached t = " << flow.time() << " without a self-intersection";
  EXPECT_NE(message.find(fmt::format("step {} ", flow.steps() + 1)), std::string::npos) << message;
  EXPECT_NE(message.find("run with --retriangulate"), std::string::npos) << message;
  EXPECT_TRUE(self_intersections(flow.mesh()).empty()) << "the flow keeps the last surface that did not cross itself";
  EXPECT_LT(flow.time(), 0.1);
}

TEST(SurfaceDiffusion, needs_no_stop_condition_but_a_run_does)
{
  RunParameters p; // no steps, no end time
  p.retriangulation.enabled = false;
  SurfaceDiffusion flow(analytic::icosphere(2), p);
  EXPECT_FALSE(flow.finished());
  const StepRecord first = flow.step();
  EXPECT_EQ(first.step, 1);
  EXPECT_GT(first.tau, 0);
  EXPECT_EQ(flow.time(), first.tau);
  EXPECT_THROW(validate_run_parameters(p), InvalidParameter);
  p.scheme.beta = -1;
  EXPECT_THROW(SurfaceDiffusion(analytic::icosphere(2), p), InvalidParameter);
}

TEST(SurfaceDiffusion, rejected_trials_are_noted_and_the_notes_outlive_a_failed_step)
{
  RunParameters p = adaptive_run(5);
  p.time_step.adaptive.max_volume_change = 1e-300; // no step of an ellipsoid keeps its volume that well
  p.time_step.adaptive.max_rejections = 3;         // the fourth rejection ends the flow
  SurfaceDiffusion flow(analytic::ellipsoid(2, 5, 4, 3), p);
  const Eigen::VectorXd before = vertex_positions(flow.mesh()).reshaped();
  EXPECT_THROW(flow.step(), SolverFailure);
  const std::vector<FlowNote> notes = flow.take_notes();
  ASSERT_EQ(notes.size(), 3u);
  for (const FlowNote& n : notes) {
    EXPECT_EQ(n.step, 1);
    EXPECT_EQ(n.time, 0);
    EXPECT_EQ(n.line().rfind("step 1 t=0: rejected τ = ", 0), 0u) << n.line();
  }
  EXPECT_TRUE(flow.take_notes().empty());
  EXPECT_EQ(flow.rejected_trials(), 3);
  EXPECT_EQ(flow.steps(), 0);
  EXPECT_EQ(vertex_positions(flow.mesh()).reshaped(), before) << "a failed step leaves the surface as it was";
}

TEST(SurfaceDiffusion, a_table_step_that_fails_is_covered_by_adaptive_steps_and_the_table_resumes)
{
  // The explicit scheme (β = 0) turns triangles over at τ = 0.3 within two steps. A run under a
  // table that asks for it used to stop there (exit 3); its failed step is now covered by adaptive
  // steps, which take exactly the table's time, and the table's small τ then takes over again.
  RunParameters p;
  p.retriangulation.enabled = false;
  p.scheme.beta = 0;
  p.time_step.mode = TimeStepMode::schedule;
  p.time_step.schedule = TauSchedule({{1, 2, 0.3}, {3, 1000, 0.0005}});
  p.steps = 80;
  SurfaceDiffusion flow(analytic::ellipsoid(3, 5, 4, 3), p);
  std::vector<StepRecord> steps;
  while (!flow.finished())
    ASSERT_NO_THROW(steps.push_back(flow.step())) << "at step " << flow.steps() + 1;

  const auto fell_back = std::find_if(steps.begin(), steps.end(),
                                      [](const StepRecord& s) { return has_event(s.events, StepEventKind::fallback); });
  ASSERT_NE(fell_back, steps.end()) << "τ = 0.3 did not fail: the test no longer exercises the fallback";
  const auto resumed = std::find_if(fell_back, steps.end(), [](const StepRecord& s) { return s.tau == 0.0005; });
  ASSERT_NE(resumed, steps.end()) << "the table never resumed";
  EXPECT_GT(resumed - fell_back, 3) << "the failed step should take several adaptive steps";
  // Time follows the table: both 0.3 steps were taken in full, one of them by adaptive steps.
  EXPECT_NEAR(resumed->time - resumed->tau, 0.6, 1e-12);
  for (auto s = fell_back; s != resumed; ++s)
    EXPECT_LT(s->tau, 0.3);
  const auto notes = flow.take_notes();
  EXPECT_TRUE(std::any_of(notes.begin(), notes.end(),
                          [](const FlowNote& n) { return n.text.find("the table resumes") != std::string::npos; }));
  EXPECT_TRUE(flow.operators().curvature.allFinite());
}

} // namespace
} // namespace sdflow
