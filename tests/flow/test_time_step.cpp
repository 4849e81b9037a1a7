//! Time-step control (time_step.h): schedules and the adaptive controller's rule.
#include "io/temp_dir.h"
#include "sdflow/errors.h"
#include "sdflow/flow/time_step.h"

#include <gtest/gtest.h>

#include <cmath>

namespace sdflow {
namespace {

TEST(TauSchedule, table_ranges_map_steps_to_tau_and_the_last_tau_continues)
{
  // The paper's Table 1, which starts at step 0.
  const TauSchedule table({{0, 50, 0.01}, {51, 100, 0.02}, {101, 150, 0.05}, {151, 1000, 0.1}});
  EXPECT_EQ(table.tau_for_step(1), 0.01);
  EXPECT_EQ(table.tau_for_step(50), 0.01);
  EXPECT_EQ(table.tau_for_step(51), 0.02);
  EXPECT_EQ(table.tau_for_step(1000), 0.1);
  EXPECT_EQ(table.tau_for_step(5000), 0.1);
}

TEST(TauSchedule, gaps_overlaps_and_bad_tau_are_rejected)
{
  EXPECT_THROW(TauSchedule({{1, 10, 0.1}, {12, 20, 0.2}}), InvalidParameter);
  EXPECT_THROW(TauSchedule({{1, 10, 0.1}, {10, 20, 0.2}}), InvalidParameter);
  EXPECT_THROW(TauSchedule({{1, 10, -0.1}}), InvalidParameter);
  EXPECT_THROW(TauSchedule({{5, 1, 0.1}}), InvalidParameter);
  EXPECT_THROW(TauSchedule(std::vector<ScheduleEntry>{}), InvalidParameter);
}

TEST(TauSchedule, csv_and_toml_files_read_alike_and_errors_name_the_line)
{
  test::TempDir dir;
  test::write_file(dir / "t.csv", "first_step,last_step,tau\n# Table 2\n1,30,0.001\n31,60,0.002\n");
  test::write_file(dir / "t.toml", "schedule = [[1, 30, 0.001], [31, 60, 0.002]]\n");
  test::write_file(dir / "bad.csv", "1,30,0.001\n31,sixty,0.002\n");
  const TauSchedule csv = read_schedule(dir / "t.csv"), toml = read_schedule(dir / "t.toml");
  ASSERT_EQ(csv.entries().size(), 2u);
  for (long step : {1L, 30L, 31L, 60L})
    EXPECT_EQ(csv.tau_for_step(step), toml.tau_for_step(step));
  try {
    read_schedule(dir / "bad.csv");
    FAIL() << "a malformed line was accepted";
  } catch (const IoError& e) {
    EXPECT_NE(std::string(e.what()).find("bad.csv:2"), std::string::npos) << e.what();
  }
}

TEST(TimeStepController, adaptive_tau_grows_when_calm_and_shrinks_on_rejection)
{
  TimeStepOptions options;
  options.adaptive.initial_tau = 1e-3;
  TimeStepController controller(options);
  const double tau = controller.propose(1, 0.0, 1.0);
  EXPECT_EQ(tau, 1e-3);
  StepCheck calm;
  calm.displacement_ratio = 1e-6;
  EXPECT_TRUE(controller.judge(1, tau, calm));
  const double grown = controller.propose(2, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(grown, tau * options.adaptive.growth);

  StepCheck inverted;
  inverted.inverted_triangles = 3;
  EXPECT_FALSE(controller.judge(2, grown, inverted));
  EXPECT_DOUBLE_EQ(controller.propose(2, 0.0, 1.0), grown * options.adaptive.shrink);
  EXPECT_EQ(controller.propose(2, 0.0, 1e-5), 1e-5) << "the last step must land on the end time";
}

TEST(TimeStepController, triangles_turning_over_step_after_step_collapse_tau_and_say_so)
{
  // One triangle turning over in the first trial of each step, the second trial accepted: τ halves
  // every step, as on the 27-sphere packing, until it is kTurningCollapse times the τ it began at.
  TimeStepOptions options;
  options.adaptive.initial_tau = 1e-6;
  TimeStepController controller(options);
  StepCheck turned, calm;
  turned.inverted_triangles = 1;
  calm.displacement_ratio = 0.9 * options.adaptive.safety * options.adaptive.max_displacement;
  int steps = 0;
  for (; steps < 40 && !controller.turning_collapsed(); ++steps) {
    EXPECT_FALSE(controller.judge(steps + 1, controller.propose(steps + 1, 0.0, 1.0), turned));
    if (controller.turning_collapsed())
      break;
    ASSERT_TRUE(controller.judge(steps + 1, controller.propose(steps + 1, 0.0, 1.0), calm));
  }
  EXPECT_TRUE(controller.turning_collapsed()) << "after " << steps << " steps";
  EXPECT_EQ(controller.state().turning_since_tau, 1e-6) << "the τ of the first trial that turned one over";
  EXPECT_LT(controller.state().next_tau, kTurningCollapse * 1e-6);
  EXPECT_GE(steps, 5) << "a few halvings are τ's to take, not the triangulation's";
  controller.forget_turning();
  EXPECT_FALSE(controller.turning_collapsed());

  // τ back at the size it began at: the triangles that turned over then are forgotten.
  TimeStepController recovering(options);
  EXPECT_FALSE(recovering.judge(1, recovering.propose(1, 0.0, 1.0), turned));
  StepCheck still;
  still.displacement_ratio = 1e-9;
  for (int step = 1; recovering.state().turning_since_tau > 0 && step < 20; ++step)
    ASSERT_TRUE(recovering.judge(step, recovering.propose(step, 0.0, 1.0), still));
  EXPECT_EQ(recovering.state().turning_since_tau, 0);
  EXPECT_GE(recovering.state().next_tau, 1e-6);

  // Constant τ never collapses: a turned triangle stops it at once (the rule's other branch).
  TimeStepOptions constant;
  constant.mode = TimeStepMode::constant;
  constant.tau = 1e-6;
  TimeStepController fixed(constant);
  EXPECT_FALSE(fixed.turning_collapsed());
}

TEST(TimeStepController, displacement_bound_predicts_the_next_tau)
{
  TimeStepOptions options;
  options.adaptive.initial_tau = 1.0;
  TimeStepController controller(options);
  StepCheck big;
  big.displacement_ratio = 4 * options.adaptive.max_displacement;
  big.displacement_exceeded = true;
  EXPECT_FALSE(controller.judge(1, 1.0, big));
  EXPECT_DOUBLE_EQ(controller.propose(1, 0.0, 10.0), options.adaptive.safety / 4);
}

TEST(TimeStepController, endless_rejections_stop_with_solver_failure)
{
  TimeStepOptions options;
  options.adaptive.initial_tau = 1.0;
  TimeStepController controller(options);
  StepCheck nan;
  nan.non_finite = true;
  EXPECT_THROW(
      {
        for (int i = 0; i < 1000; ++i)
          controller.judge(1, controller.propose(1, 0.0, 10.0), nan);
      },
      SolverFailure);
}

// Where a trial failed is what a forced re-triangulation remeshes (RetriangulationContext::
// failed_vertices): the corners of the turned-over triangles, and in adaptive mode the vertices
// beyond the displacement bound; the controller's final failure carries them.
TEST(TimeStepController, a_failed_trial_names_the_vertices_where_it_failed)
{
  const AdaptiveOptions bounds; // max_displacement 0.1 of h
  VertexVectors now(5, 3);
  now << 0, 0, 0, 1, 0, 0, 0, 1, 0, 1, 1, 0, 3, 3, 0;
  FaceIndices triangles(2, 3);
  triangles << 0, 1, 2, 1, 3, 2;
  VertexVectors next = now;
  next(3, 0) = -1; // the second triangle turns over
  Eigen::VectorXd w = Eigen::VectorXd::Zero(5);
  w[4] = 0.5; // τ|w| = 0.5 h at vertex 4
  const Eigen::VectorXd h = Eigen::VectorXd::Ones(5);
  const VertexVectors no_error(0, 3);
  const auto check = [&](bool adaptive) {
    return check_trial({.tau = 1, .now = now, .next = next, .w = w, .error = no_error, .triangles = triangles,
                        .edge_lengths = h},
                       bounds, adaptive);
  };
  EXPECT_EQ(check(true).failed_vertices, (std::vector<int>{1, 2, 3, 4}));
  EXPECT_EQ(check(false).failed_vertices, (std::vector<int>{1, 2, 3}));
  next = now;
  EXPECT_EQ(check(true).failed_vertices, (std::vector<int>{4}));
  w[4] = 0;
  EXPECT_TRUE(check(true).failed_vertices.empty());

  TimeStepOptions options;
  options.adaptive.initial_tau = 1.0;
  TimeStepController controller(options);
  StepCheck turned;
  turned.inverted_triangles = 1;
  turned.failed_vertices = {7, 8, 9};
  try {
    for (int i = 0; i < 1000; ++i)
      controller.judge(1, controller.propose(1, 0.0, 10.0), turned);
    FAIL() << "expected UnacceptableStep";
  } catch (const UnacceptableStep& e) {
    EXPECT_EQ(e.vertices, turned.failed_vertices);
  }
}

TEST(TimeStepController, constant_tau_stops_at_the_first_unstable_step)
{
  TimeStepOptions options{.mode = TimeStepMode::constant, .tau = 0.5};
  TimeStepController controller(options);
  StepCheck inverted;
  inverted.inverted_triangles = 1;
  EXPECT_THROW(controller.judge(3, 0.5, inverted), SolverFailure);
  EXPECT_THROW(TimeStepController({.mode = TimeStepMode::constant, .tau = 0}), InvalidParameter);
}

TEST(TimeStepController, schedule_retries_halve_the_tables_tau_then_return_to_it)
{
  TimeStepOptions options{.mode = TimeStepMode::schedule,
                          .schedule = TauSchedule({{1, 10, 0.2}}),
                          .schedule_retries = 2};
  TimeStepController controller(options);
  StepCheck inverted;
  inverted.inverted_triangles = 3;
  EXPECT_DOUBLE_EQ(controller.propose(4, 0.0, 100.0), 0.2);
  EXPECT_FALSE(controller.judge(4, 0.2, inverted));
  EXPECT_DOUBLE_EQ(controller.propose(4, 0.0, 100.0), 0.1);
  EXPECT_FALSE(controller.judge(4, 0.1, inverted));
  EXPECT_DOUBLE_EQ(controller.propose(4, 0.0, 100.0), 0.05);
  EXPECT_TRUE(controller.judge(4, 0.05, StepCheck{}));
  EXPECT_EQ(controller.state().rejections, 0);
  EXPECT_DOUBLE_EQ(controller.propose(5, 0.0, 100.0), 0.2); // back to the table

  // A third failure in a row is one more than allowed: the run stops, naming the halvings.
  EXPECT_FALSE(controller.judge(5, 0.2, inverted));
  EXPECT_FALSE(controller.judge(5, 0.1, inverted));
  try {
    controller.judge(5, 0.05, inverted);
    FAIL() << "expected SolverFailure";
  } catch (const SolverFailure& e) {
    EXPECT_NE(std::string(e.what()).find("after 2 halvings"), std::string::npos) << e.what();
  }
}

// Issue 33: τ = 1e300 lost 8% of a sphere's volume and exited 0. A step that breaks the volume
// bound is refused in every mode, and the failure says by how much τ is too large.
TEST(TimeStepController, constant_and_tabled_steps_that_break_the_volume_bound_are_too_large)
{
  const AdaptiveOptions bounds; // max_volume_change 1e-3
  const VertexVectors x = VertexVectors::Zero(3, 3);
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(3), h = Eigen::VectorXd::Ones(3);
  const FaceIndices no_faces(0, 3);
  const VertexVectors no_error(0, 3);
  const auto check = [&](double volume_change, bool adaptive) {
    return check_trial({.tau = 1, .now = x, .next = x, .w = w, .error = no_error, .triangles = no_faces,
                        .edge_lengths = h, .volume_change = volume_change},
                       bounds, adaptive);
  };
  EXPECT_FALSE(check(0.9e-3, false).volume_exceeded);
  EXPECT_TRUE(check(1.1e-3, false).volume_exceeded);
  EXPECT_TRUE(check(1.1e-3, true).volume_exceeded);

  StepCheck lost = check(0.08, false);
  lost.adaptive_tau = 1e-3;
  TimeStepController constant({.mode = TimeStepMode::constant, .tau = 1e300});
  try {
    constant.judge(1, 1e300, lost);
    FAIL() << "expected TimeStepTooLarge";
  } catch (const TimeStepTooLarge& e) {
    const std::string text = e.what();
    EXPECT_NE(text.find("too large for the scheme"), std::string::npos) << text;
    EXPECT_NE(text.find("80 times the bound"), std::string::npos) << text;
    EXPECT_NE(text.find("1e+303 times smaller"), std::string::npos) << text;
  }
  // A table with retries halves its τ first, as for any failed step, and then gives up the same way.
  TimeStepController table({.mode = TimeStepMode::schedule, .schedule = TauSchedule({{1, 10, 0.2}}),
                            .schedule_retries = 1});
  EXPECT_FALSE(table.judge(1, 0.2, lost));
  EXPECT_DOUBLE_EQ(table.propose(1, 0.0, 100.0), 0.1);
  EXPECT_THROW(table.judge(1, 0.1, lost), TimeStepTooLarge);
  // Inverted triangles keep their own failure (SolverFailure, which a table covers by adaptive steps).
  StepCheck inverted = lost;
  inverted.inverted_triangles = 2;
  TimeStepController plain({.mode = TimeStepMode::constant, .tau = 0.5});
  try {
    plain.judge(1, 0.5, inverted);
    FAIL() << "expected SolverFailure";
  } catch (const TimeStepTooLarge&) {
    FAIL() << "turned-over triangles are not reported as a volume failure";
  } catch (const SolverFailure&) {
  }
}

// The adaptive rule keeps W_h from rising (time_step.h): a trial that raises it beyond round-off is
// rejected and τ shrunk; constant and tabled steps take their τ as given.
TEST(TimeStepController, an_adaptive_trial_that_raises_the_energy_is_rejected_and_tau_shrunk)
{
  const AdaptiveOptions bounds;
  const VertexVectors x = VertexVectors::Zero(3, 3);
  const Eigen::VectorXd w = Eigen::VectorXd::Zero(3), h = Eigen::VectorXd::Ones(3);
  const FaceIndices no_faces(0, 3);
  const VertexVectors no_error(0, 3);
  const auto check = [&](double energy_change, bool adaptive) {
    return check_trial({.tau = 1, .now = x, .next = x, .w = w, .error = no_error, .triangles = no_faces,
                        .edge_lengths = h, .energy_change = energy_change},
                       bounds, adaptive);
  };
  EXPECT_FALSE(check(-1e-3, true).failed()) << "a fall is what the flow does";
  EXPECT_FALSE(check(0.5 * kEnergyRoundOff, true).failed()) << "round-off";
  const StepCheck rose = check(2e-9, true);
  EXPECT_TRUE(rose.energy_rose);
  EXPECT_TRUE(rose.failed());
  EXPECT_NE(rose.describe().find("the energy rose by 2e-09"), std::string::npos) << rose.describe();
  EXPECT_FALSE(check(2e-9, false).failed()) << "a constant τ is taken as given";

  TimeStepController adaptive({.mode = TimeStepMode::adaptive, .adaptive = {.initial_tau = 0.1}});
  const double tau = adaptive.propose(1, 0.0, 100.0);
  EXPECT_FALSE(adaptive.judge(1, tau, rose));
  EXPECT_DOUBLE_EQ(adaptive.propose(1, 0.0, 100.0), tau * bounds.shrink);
  // A rise that falls like τ² with τ is the time step's: rejected again.
  EXPECT_FALSE(adaptive.judge(1, tau * bounds.shrink, check(2e-9 * bounds.shrink * bounds.shrink, true)));
  EXPECT_FALSE(adaptive.energy_stood_aside());
  // One that falls only like τ is not (β = ½ flips the modes the mesh does not resolve rather than
  // damping them, whatever τ above their scale): accepted, said so, and the next step goes on from
  // what the first trial would have proposed (here τ · growth) instead of creeping down.
  const double smaller = adaptive.propose(1, 0.0, 100.0);
  EXPECT_TRUE(adaptive.judge(1, smaller, check(2e-9 * smaller / tau, true)));
  ASSERT_TRUE(adaptive.energy_stood_aside());
  EXPECT_DOUBLE_EQ(adaptive.energy_stood_aside()->rejected_tau, tau);
  EXPECT_DOUBLE_EQ(adaptive.energy_stood_aside()->accepted_tau, smaller);
  const double next = adaptive.propose(2, 0.0, 100.0);
  EXPECT_DOUBLE_EQ(next, tau * bounds.growth);
  // The next step starts afresh: its first rise is rejected. A rate whose rise at the halved τ is
  // below round-off is still a rate: without standing aside, τ would settle where τ · rate meets
  // kEnergyRoundOff (3·10⁻¹² on a ridge near its break-up, for tens of thousands of steps).
  EXPECT_FALSE(adaptive.judge(2, next, check(1.6 * kEnergyRoundOff, true)));
  EXPECT_FALSE(adaptive.energy_stood_aside());
  EXPECT_TRUE(adaptive.judge(2, next * bounds.shrink, check(0.8 * kEnergyRoundOff, true)));
  EXPECT_TRUE(adaptive.energy_stood_aside());
  EXPECT_DOUBLE_EQ(adaptive.propose(3, 0.0, 100.0), next * bounds.growth);
}

TEST(TimeStepController, schedule_retries_apply_to_schedules_only_and_are_bounded)
{
  // Without retries a schedule stops at the first unstable step, as the paper's tables would.
  TimeStepController strict({.mode = TimeStepMode::schedule, .schedule = TauSchedule({{1, 10, 0.2}})});
  StepCheck nan;
  nan.non_finite = true;
  EXPECT_THROW(strict.judge(1, 0.2, nan), SolverFailure);
  // A displacement beyond the adaptive bound is not a failure of a table's step.
  StepCheck far;
  far.displacement_ratio = 10;
  far.displacement_exceeded = true;
  EXPECT_TRUE(strict.judge(1, 0.2, far));
  EXPECT_THROW(TimeStepController({.mode = TimeStepMode::schedule, .schedule = TauSchedule({{1, 10, 0.2}}),
                                   .schedule_retries = -1}),
               InvalidParameter);
}

TEST(TimeStepController, a_failed_table_step_is_covered_by_adaptive_steps_then_the_table_resumes)
{
  const TauSchedule table({{1, 3, 0.2}, {4, 5, 0.4}, {6, 100, 0.05}});
  TimeStepController controller({.mode = TimeStepMode::schedule, .schedule = table});
  EXPECT_FALSE(controller.adaptive());
  controller.fall_back_to_adaptive(2);
  ASSERT_TRUE(controller.adaptive());
  StepCheck calm;
  calm.displacement_ratio = 1e-6; // τ grows by the growth bound, 1.25, per step
  StepCheck far;
  far.displacement_ratio = 1;
  far.displacement_exceeded = true;

  long step = 2;
  double covered = 0;
  int rejected = 0;
  while (controller.adaptive()) {
    const double tau = controller.propose(step, 0.01, 1e9);
    if (step == 5 && rejected == 0) { // a rejection inside the stretch shrinks τ and keeps the count
      const long lag = controller.state().table_lag;
      EXPECT_FALSE(controller.judge(step, tau, far));
      EXPECT_EQ(controller.state().table_lag, lag);
      ++rejected;
      continue;
    }
    ASSERT_TRUE(controller.judge(step, tau, calm));
    covered += tau;
    ++step;
    ASSERT_LT(step, 200) << "the adaptive stretch never ended";
  }
  // The adaptive steps covered whole table steps, 2 to k − 1, and no more: the time follows the table.
  const long k = controller.table_step(step);
  ASSERT_GT(k, 2);
  double table_time = 0;
  for (long s = 2; s < k; ++s)
    table_time += table.tau_for_step(s);
  EXPECT_NEAR(covered, table_time, 1e-14);
  EXPECT_EQ(controller.state().table_lag, step - k);
  // The table resumes where the adaptive τ had caught up with it.
  EXPECT_GE(controller.state().next_tau, table.tau_for_step(k));
  EXPECT_EQ(controller.propose(step, 0.0, 1e9), table.tau_for_step(k));
  EXPECT_THROW(TimeStepController({.mode = TimeStepMode::constant, .tau = 0.1}).fall_back_to_adaptive(1),
               InvalidParameter);
}

TEST(TimeStepController, error_tolerance_rejects_and_predicts_the_next_tau)
{
  // The step-doubling estimate is O(τ²): an estimate 4 ε calls for τ · safety · √(1/4).
  TimeStepOptions options;
  options.adaptive.initial_tau = 1.0;
  options.adaptive.tolerance = 1e-3;
  TimeStepController controller(options);
  StepCheck large;
  large.error_estimate = 4e-3;
  large.error_exceeded = true;
  EXPECT_FALSE(controller.judge(1, 1.0, large));
  EXPECT_DOUBLE_EQ(controller.propose(1, 0.0, 10.0), options.adaptive.safety / 2);
  StepCheck small;
  small.error_estimate = 0.25e-3;
  EXPECT_TRUE(controller.judge(1, 0.4, small));
  EXPECT_DOUBLE_EQ(controller.propose(2, 0.0, 10.0), 0.4 * options.adaptive.growth) << "growth stays bounded";
  StepCheck near;
  near.error_estimate = 0.9e-3;
  EXPECT_TRUE(controller.judge(2, 0.5, near));
  EXPECT_DOUBLE_EQ(controller.propose(3, 0.0, 10.0), 0.5 * options.adaptive.safety * std::sqrt(1 / 0.9));
}
} // namespace
} // namespace sdflow
