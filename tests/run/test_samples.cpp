//! The paper's experiments in samples/: every scenario file reads and validates, and every
//! schedule it names exists (their runs are long; samples/reproduce.sh runs them).
#include "sdflow/run/parameters.h"

#include <gtest/gtest.h>

#include <filesystem>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

TEST(Samples, every_scenario_reads_and_validates)
{
  const fs::path samples = fs::path(SDFLOW_SOURCE_DIR) / "samples";
  int scenarios = 0;
  for (const auto& entry : fs::directory_iterator(samples)) {
    if (entry.path().extension() != ".toml")
      continue;
    ++scenarios;
    RunParameters p;
    ASSERT_NO_THROW(read_run_parameters(entry.path(), p)) << entry.path();
    EXPECT_NO_THROW(validate_run_parameters(p)) << entry.path();
    EXPECT_FALSE(p.input.empty()) << entry.path() << " names no input mesh";
    EXPECT_FALSE(p.output_dir.empty()) << entry.path() << " names no run directory";
    if (p.time_step.mode == TimeStepMode::schedule && !p.time_step.schedule_file.empty()) {
      EXPECT_TRUE(fs::exists(p.time_step.schedule_file)) << p.time_step.schedule_file;
    }
  }
  EXPECT_GE(scenarios, 8);
}

} // namespace
} // namespace sdflow
