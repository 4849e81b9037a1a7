//! The run driver's control of its directory (issue 13): a stop request between steps leaves a
//! checkpoint that resumes bit for bit, a run with no checkpoint yet resumes from step 0, and a
//! locked directory is refused.
#include "io/temp_dir.h"
#include "sdflow/errors.h"
#include "sdflow/run/checkpoint.h"
#include "sdflow/run/run_lock.h"
#include "sdflow/run/simulation.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

RunParameters parameters(const fs::path& out)
{
  RunParameters p;
  p.output_dir = out;
  p.steps = 12;
  p.checkpoint_every = 5;
  p.retriangulation.enabled = false;
  return p;
}

TEST(RunControl, stop_request_writes_a_checkpoint_of_the_last_step_and_resumes_bit_for_bit)
{
  test::TempDir dir;
  const Mesh start = analytic::ellipsoid(3, 5, 4, 3);
  run_simulation(start, {.parameters = parameters(dir / "whole")});

  long steps_seen = 0;
  const SimulationResult stopped =
      run_simulation(start, {.parameters = parameters(dir / "stopped"),
                             .progress = [&](const StepRecord& r) { steps_seen = r.step; },
                             .stop_requested = [&] { return steps_seen >= 7; }});
  EXPECT_TRUE(stopped.interrupted);
  EXPECT_EQ(stopped.steps, 7);
  EXPECT_EQ(read_checkpoint(dir / "stopped/checkpoint.bin").step, 7) << "not the step-5 checkpoint";
  const SimulationResult resumed = resume_simulation({.parameters = parameters(dir / "stopped")});
  EXPECT_FALSE(resumed.interrupted);
  EXPECT_FALSE(resumed.restarted);
  EXPECT_EQ(test::read_file(dir / "stopped/metrics.csv"), test::read_file(dir / "whole/metrics.csv"));
}

TEST(RunControl, a_run_stopped_while_adaptive_steps_cover_a_table_step_resumes_bit_for_bit)
{
  // The explicit scheme fails the table's τ = 0.3 (time_step.h): adaptive steps cover it, and the
  // run is stopped among them. The checkpoint keeps where the table stands.
  test::TempDir dir;
  const Mesh start = analytic::ellipsoid(3, 5, 4, 3);
  const auto table_run = [&](const fs::path& out) {
    RunParameters p = parameters(out);
    p.scheme.beta = 0;
    p.time_step.mode = TimeStepMode::schedule;
    p.time_step.schedule = TauSchedule({{1, 2, 0.3}, {3, 1000, 0.0005}});
    p.steps = 30;
    return p;
  };
  run_simulation(start, {.parameters = table_run(dir / "whole")});
  long steps_seen = 0;
  run_simulation(start, {.parameters = table_run(dir / "stopped"),
                         .progress = [&](const StepRecord& r) { steps_seen = r.step; },
                         .stop_requested = [&] { return steps_seen >= 9; }});
  const Checkpoint checkpoint = read_checkpoint(dir / "stopped/checkpoint.bin");
  ASSERT_EQ(checkpoint.step, 9);
  EXPECT_GT(checkpoint.bookkeeping.controller.table_lag, 0) << "not stopped among the adaptive steps";
  EXPECT_GT(checkpoint.bookkeeping.controller.fallback_left, 0);
  resume_simulation({.parameters = table_run(dir / "stopped")});
  EXPECT_EQ(test::read_file(dir / "stopped/metrics.csv"), test::read_file(dir / "whole/metrics.csv"));
}

TEST(RunControl, resume_without_a_checkpoint_starts_again_at_step_0)
{
  test::TempDir dir;
  const Mesh start = analytic::ellipsoid(3, 5, 4, 3);
  run_simulation(start, {.parameters = parameters(dir / "whole")});
  run_simulation(start, {.parameters = parameters(dir / "early")});
  fs::remove(dir / "early/checkpoint.bin");
  const SimulationResult resumed = resume_simulation({.parameters = parameters(dir / "early")});
  EXPECT_TRUE(resumed.restarted);
  EXPECT_EQ(test::read_file(dir / "early/metrics.csv"), test::read_file(dir / "whole/metrics.csv"));
}

TEST(RunControl, a_locked_directory_is_refused_and_released_with_its_lock)
{
  test::TempDir dir;
  fs::create_directories(dir / "run");
  {
    const RunLock held(dir / "run");
    try {
      run_simulation(analytic::icosphere(1), {.parameters = parameters(dir / "run")});
      ADD_FAILURE() << "a locked directory was used";
    } catch (const InvalidParameter& e) {
      EXPECT_NE(std::string(e.what()).find(std::to_string(::getpid())), std::string::npos) << e.what();
    }
    EXPECT_THROW(RunLock second(dir / "run"), InvalidParameter);
  }
  EXPECT_NO_THROW(run_simulation(analytic::icosphere(1), {.parameters = parameters(dir / "run")}));
}

TEST(RunControl, an_output_directory_that_is_a_file_is_refused_as_bad_input)
{
  test::TempDir dir;
  test::write_file(dir / "file", "x");
  EXPECT_THROW(run_simulation(analytic::icosphere(1), {.parameters = parameters(dir / "file")}), InvalidParameter);
  EXPECT_THROW(run_simulation(analytic::icosphere(1), {.parameters = parameters(dir / "file/run")}), IoError);
}

} // namespace
} // namespace sdflow
