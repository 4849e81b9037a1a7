//! Every state a run directory can be in (README, "Run directory states") and what `run` and
//! `run --resume` do with it: fresh, running (locked), killed before or after its first checkpoint,
//! stopped by SIGINT / SIGTERM, disk full, finished. Issue 13, defects 7, 10 and 11.
#include "io/temp_dir.h"
#include "sdflow/io/io.h"
#include "sdflow/run/checkpoint.h"
#include "sdflow/run/simulation.h"
#include "support/analytic_meshes.h"
#include "support/run_command.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <csignal>
#include <fcntl.h>
#include <fstream>
#include <sys/file.h>
#include <sys/resource.h>
#include <sys/wait.h>
#include <unistd.h>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

using analytic::count_lines;
using analytic::start_sdflow;
using analytic::wait_exit_code;

class RunDirectory : public ::testing::Test {
protected:
  void SetUp() override
  {
    write_mesh(analytic::ellipsoid(3, 5, 4, 3), dir / "e.ply", {.encoding = Encoding::binary});
    common = " --input " + (dir / "e.ply").string() + " --steps 30 --checkpoint-every 7 --snapshot-every 5 --quiet";
  }
  //! The uninterrupted run, to compare with.
  std::string whole_metrics()
  {
    const auto whole = analytic::run_sdflow("run --out " + (dir / "whole").string() + common);
    EXPECT_EQ(whole.exit_code, 0) << whole.output;
    return test::read_file(dir / "whole/metrics.csv");
  }

  test::TempDir dir;
  std::string common;
};

TEST_F(RunDirectory, fresh_directory_runs_and_a_finished_one_is_refused_but_resumes_to_its_end)
{
  fs::create_directories(dir / "fresh");
  const auto first = analytic::run_sdflow("run --out " + (dir / "fresh").string() + common);
  ASSERT_EQ(first.exit_code, 0) << first.output;
  const auto again = analytic::run_sdflow("run --out " + (dir / "fresh").string() + common);
  EXPECT_EQ(again.exit_code, 2) << again.output;
  EXPECT_NE(again.output.find("already holds a run"), std::string::npos) << again.output;
  const std::string metrics = test::read_file(dir / "fresh/metrics.csv");
  const auto resumed = analytic::run_sdflow("run --resume " + (dir / "fresh").string() + " --quiet");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(test::read_file(dir / "fresh/metrics.csv"), metrics) << "a finished run stays as it is";
  const auto longer = analytic::run_sdflow("run --resume " + (dir / "fresh").string() + " --steps 32 --quiet");
  EXPECT_EQ(longer.exit_code, 0) << longer.output;
  EXPECT_EQ(count_lines(dir / "fresh/metrics.csv"), 34) << "header + rows 0..32";
}

// Defect 7: killed between writing step 0 and its first checkpoint.
TEST_F(RunDirectory, killed_before_its_first_checkpoint_resumes_from_step_0)
{
  const std::string expected = whole_metrics();
  ASSERT_EQ(analytic::run_sdflow("run --out " + (dir / "early").string() + common).exit_code, 0);
  // What start() leaves when killed between metrics.csv and checkpoint.bin: step 0 only.
  fs::remove(dir / "early/checkpoint.bin");
  for (const auto& entry : fs::directory_iterator(dir / "early/snapshots"))
    if (entry.path().stem() != "step_000000")
      fs::remove(entry.path());
  std::ifstream in(dir / "early/metrics.csv");
  std::string header, row0;
  std::getline(in, header);
  std::getline(in, row0);
  in.close();
  test::write_file(dir / "early/metrics.csv", header + "\n" + row0 + "\n");

  const auto refused = analytic::run_sdflow("run --out " + (dir / "early").string() + common);
  EXPECT_EQ(refused.exit_code, 2) << refused.output;
  EXPECT_NE(refused.output.find("--resume"), std::string::npos) << "the refusal says how to continue: " << refused.output;
  const auto resumed = analytic::run_sdflow("run --resume " + (dir / "early").string()); // -q would hide the info
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_NE(resumed.output.find("starting again at step 0"), std::string::npos) << resumed.output;
  EXPECT_EQ(test::read_file(dir / "early/metrics.csv"), expected);
  // Killed even earlier: run.toml only, not even the step-0 snapshot. The input is read again.
  ASSERT_EQ(analytic::run_sdflow("run --out " + (dir / "earlier").string() + common).exit_code, 0);
  for (const char* name : {"checkpoint.bin", "metrics.csv", "events.log", "series.pvd"})
    fs::remove(dir / "earlier" / name);
  fs::remove_all(dir / "earlier/snapshots");
  const auto restarted = analytic::run_sdflow("run --resume " + (dir / "earlier").string() + " --quiet");
  ASSERT_EQ(restarted.exit_code, 0) << restarted.output;
  EXPECT_EQ(test::read_file(dir / "earlier/metrics.csv"), expected);
  // Nothing at all written yet: there is nothing to resume, and a new run may use the directory.
  fs::create_directories(dir / "empty");
  const auto nothing = analytic::run_sdflow("run --resume " + (dir / "empty").string() + " --quiet");
  EXPECT_EQ(nothing.exit_code, 2) << nothing.output;
  EXPECT_NE(nothing.output.find("no run to resume"), std::string::npos) << nothing.output;
}

// Defect 7 and 12 (out of space): a full disk stops the run with exit 4, and --resume finishes it.
TEST_F(RunDirectory, disk_full_stops_with_an_environment_failure_and_resume_finishes_the_run)
{
  const std::string expected = whole_metrics();
  for (const rlim_t limit : {rlim_t{3000}, rlim_t{60000}}) {
    SCOPED_TRACE(limit);
    const fs::path run = dir / fmt::format("full{}", limit);
    const int code = wait_exit_code(start_sdflow("run --out " + run.string() + common, dir / "full.log", limit));
    const std::string log = test::read_file(dir / "full.log");
    EXPECT_EQ(code, 4) << log;
    EXPECT_NE(log.find("environment failure"), std::string::npos) << log;
    const auto resumed = analytic::run_sdflow("run --resume " + run.string() + " --quiet");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_EQ(test::read_file(run / "metrics.csv"), expected);
  }
}

// Defect 10: one process at a time; a lock left by a dead process does not count.
TEST_F(RunDirectory, a_second_run_is_refused_while_the_first_lives_and_a_stale_lock_is_ignored)
{
  fs::create_directories(dir / "busy");
  {
    const int fd = ::open((dir / "busy/run.lock").c_str(), O_RDWR | O_CREAT, 0644);
    ASSERT_GE(fd, 0);
    ASSERT_EQ(::flock(fd, LOCK_EX | LOCK_NB), 0);
    ASSERT_EQ(::write(fd, "4242\n", 5), 5);
    const auto second = analytic::run_sdflow("run --out " + (dir / "busy").string() + common);
    EXPECT_EQ(second.exit_code, 2) << second.output;
    EXPECT_NE(second.output.find("in use by another sdflow run (process 4242"), std::string::npos) << second.output;
    EXPECT_FALSE(fs::exists(dir / "busy/run.toml")) << "the refused run wrote nothing";
    ::close(fd);
  }
  // The lock file stays behind, naming a process that is gone: it blocks nothing.
  const auto run = analytic::run_sdflow("run --out " + (dir / "busy").string() + common);
  EXPECT_EQ(run.exit_code, 0) << run.output;

  // Two real runs started together into one directory: one runs, the other is refused.
  const pid_t a = start_sdflow("run --out " + (dir / "both").string() + common, dir / "a.log");
  const pid_t b = start_sdflow("run --out " + (dir / "both").string() + common, dir / "b.log");
  const int code_a = wait_exit_code(a), code_b = wait_exit_code(b);
  EXPECT_EQ(std::min(code_a, code_b), 0) << test::read_file(dir / "a.log") << test::read_file(dir / "b.log");
  EXPECT_EQ(std::max(code_a, code_b), 2) << test::read_file(dir / "a.log") << test::read_file(dir / "b.log");
  EXPECT_EQ(count_lines(dir / "both/metrics.csv"), 32);

  // A killed run's lock does not block its resumption.
  const pid_t killed = start_sdflow("run --out " + (dir / "killed").string() + common, dir / "k.log");
  int finished_code = -1;
  ASSERT_TRUE(analytic::wait_while_running(killed, [&] { return fs::exists(dir / "killed/checkpoint.bin"); },
                                           finished_code))
      << "the run ended (exit " << finished_code << ") before its first checkpoint: " << test::read_file(dir / "k.log");
  kill(killed, SIGKILL);
  wait_exit_code(killed);
  const auto resumed = analytic::run_sdflow("run --resume " + (dir / "killed").string() + " --quiet");
  EXPECT_EQ(resumed.exit_code, 0) << resumed.output;
}

// Defect 11: SIGINT and SIGTERM stop between steps with a checkpoint, say how to resume, and exit
// 130 / 143; the resumed run equals the uninterrupted one.
TEST_F(RunDirectory, sigint_and_sigterm_write_a_checkpoint_and_exit_130_and_143)
{
  write_mesh(analytic::ellipsoid(4, 5, 4, 3), dir / "big.ply", {.encoding = Encoding::binary});
  const std::string args = " --input " + (dir / "big.ply").string() + " --steps 60 --checkpoint-every 50 --quiet";
  const auto whole = analytic::run_sdflow("run --out " + (dir / "whole").string() + args);
  ASSERT_EQ(whole.exit_code, 0) << whole.output;
  for (const int signal : {SIGINT, SIGTERM}) {
    SCOPED_TRACE(signal);
    const fs::path run = dir / fmt::format("signal{}", signal);
    const pid_t child = start_sdflow("run --out " + run.string() + args, dir / "signal.log");
    int finished_code = -1;
    ASSERT_TRUE(analytic::wait_while_running(child, [&] { return count_lines(run / "metrics.csv") >= 4; },
                                             finished_code))
        << "the run ended (exit " << finished_code << ") before its third step: " << test::read_file(dir / "signal.log");
    kill(child, signal);
    const int code = wait_exit_code(child);
    const std::string log = test::read_file(dir / "signal.log");
    if (code == 0) {
      GTEST_SKIP() << "the run finished before the signal arrived";
    }
    EXPECT_EQ(code, 128 + signal) << log;
    EXPECT_NE(log.find("sdflow run --resume " + run.string()), std::string::npos) << log;
    const Checkpoint checkpoint = read_checkpoint(run / "checkpoint.bin");
    EXPECT_GT(checkpoint.step, 0);
    EXPECT_LT(checkpoint.step, 60);
    EXPECT_EQ(count_lines(run / "metrics.csv"), checkpoint.step + 2) << "the checkpoint is the last row written";
    const auto resumed = analytic::run_sdflow("run --resume " + run.string() + " --quiet");
    ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
    EXPECT_EQ(test::read_file(run / "metrics.csv"), test::read_file(dir / "whole/metrics.csv"));
  }
}

} // namespace
} // namespace sdflow
