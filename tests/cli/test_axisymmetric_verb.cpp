//! `sdflow axisymmetric` end to end: events and bodies on stdout (text and JSON), the time series,
//! and bad parameters refused with exit code 2 and the reason.
#include "io/temp_dir.h"
#include "support/run_command.h"

#include <gtest/gtest.h>

#include <fstream>

namespace sdflow {
namespace {

TEST(AxisymmetricCommand, reports_a_seal_as_text_and_json_and_writes_the_series)
{
  test::TempDir dir;
  const std::string torus = "axisymmetric torus --major 3 --minor 1.5 --stop-at-first-event --max-displacement 0.02";
  const auto text = analytic::run_sdflow(torus + " --csv " + (dir / "series.csv").string());
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("seal at t = 4.3"), std::string::npos) << text.output;
  std::ifstream series(dir / "series.csv");
  std::string header;
  std::getline(series, header);
  EXPECT_EQ(header, "time,area,volume,neck_radius,bodies,steps");
  const auto json = analytic::run_sdflow(torus + " --json");
  ASSERT_EQ(json.exit_code, 0) << json.output;
  EXPECT_NE(json.output.find("\"event_time\""), std::string::npos) << json.output;
  EXPECT_NE(json.output.find("\"kind\" : \"seal\""), std::string::npos) << json.output;
}

TEST(AxisymmetricCommand, bad_parameters_exit_2_with_the_reason)
{
  const auto torus = analytic::run_sdflow("axisymmetric torus --major 1 --minor 2");
  EXPECT_EQ(torus.exit_code, 2);
  EXPECT_NE(torus.output.find("need 0 < r < R"), std::string::npos) << torus.output;
  const auto capsule = analytic::run_sdflow("axisymmetric capsule --length-ratio 0.5");
  EXPECT_EQ(capsule.exit_code, 2);
  EXPECT_NE(capsule.output.find("L/D ≥ 1"), std::string::npos) << capsule.output;
  const auto profile = analytic::run_sdflow("axisymmetric profile /nonexistent.csv --t-end 1");
  EXPECT_EQ(profile.exit_code, 2) << profile.output;
  EXPECT_NE(profile.output.find("cannot open the profile"), std::string::npos) << profile.output;
  const auto shape = analytic::run_sdflow("axisymmetric cube");
  EXPECT_EQ(shape.exit_code, 2) << shape.output;
}

} // namespace
} // namespace sdflow
