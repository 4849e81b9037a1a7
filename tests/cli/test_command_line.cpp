//! The command line's conventions, on every verb through the real binary: an output is `-o`,
//! `--output` or `--out`; `-q`/`-v` work after the verb; `--json` prints one parseable object on
//! success and on failure (with the findings' codes); results go to stdout and logs to stderr;
//! older option names still work; the help carries no CLI11 notation and no source-file pointers.
#include "io/temp_dir.h"
#include "support/json_query.h"
#include "sdflow/io/io.h"
#include "sdflow/io/point_cloud.h"
#include "support/analytic_meshes.h"
#include "support/run_command.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <optional>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace sdflow {
namespace {

namespace fs = std::filesystem;
using test::json_query;

//! Whether every line of stderr is a log line ("info: ...", "warning: ...") or an error message.
bool only_log_lines(const std::string& err)
{
  static const std::regex log_line(R"(^((debug|info|warning|error): |sdflow: ).*)");
  std::istringstream in(err);
  for (std::string line; std::getline(in, line);)
    if (!std::regex_match(line, log_line))
      return false;
  return true;
}

//! The verbs `sdflow --help` lists.
std::vector<std::string> all_verbs()
{
  const std::string help = analytic::run_sdflow("--help").output;
  std::istringstream in(help.substr(help.find("Subcommands:")));
  std::vector<std::string> names;
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line))
    if (std::istringstream words(line); words >> line)
      names.push_back(line);
  return names;
}

//! Small inputs for every verb, and how each verb is called before its output option.
class CommandLine : public ::testing::Test {
protected:
  static void SetUpTestSuite()
  {
    dir_ = new test::TempDir;
    write_mesh(analytic::icosphere(2, 1.0), *dir_ / "sphere.ply", {.encoding = Encoding::binary});
    write_mesh(analytic::icosphere(2, 1.0, Eigen::Vector3d(1.2, 0, 0)), *dir_ / "shifted.ply",
               {.encoding = Encoding::binary});
    Mesh holed = analytic::icosphere(2, 1.0);
    for (auto f : holed.faces())
      if (holed.calc_face_centroid(f)[2] > 0.8)
        holed.delete_face(f, true);
    holed.garbage_collection();
    write_mesh(holed, *dir_ / "holed.off");
    const Mesh cloud_source = analytic::icosphere(3, 1.0);
    write_point_cloud({vertex_positions(cloud_source), vertex_positions(cloud_source)}, *dir_ / "cloud.ply");
    // A run directory for `plot`.
    const auto run = analytic::run_sdflow("run -q --input " + path("sphere.ply") + " --out " + path("run") +
                                          " --steps 2");
    ASSERT_EQ(run.exit_code, 0) << run.output;
  }
  static void TearDownTestSuite()
  {
    delete dir_;
    dir_ = nullptr;
  }
  static std::string path(const std::string& name) { return (*dir_ / name).string(); }

  struct Call {
    std::string verb, arguments, output_extension; //!< output "": a directory
  };
  //! Every verb that writes something, with the arguments before its output.
  static std::vector<Call> writing_verbs()
  {
    return {{"components", "components " + path("sphere.ply"), ".ply"},
            {"fill-holes", "fill-holes " + path("holed.off"), ".ply"},
            {"intersections", "intersections " + path("sphere.ply"), ".ply"},
            {"normals", "normals " + path("sphere.ply"), ".ply"},
            {"reconstruct", "reconstruct " + path("cloud.ply"), ".ply"},
            {"remesh", "remesh " + path("sphere.ply") + " --edge-length 0.4", ".ply"},
            {"render", "render " + path("sphere.ply") + " --size 320,240", ".png"},
            {"retriangulate", "retriangulate " + path("sphere.ply"), ".ply"},
            {"shape", "shape sphere --vertices 200", ".ply"},
            {"union", "union " + path("sphere.ply") + " " + path("shifted.ply"), ".ply"},
            {"run", "run --input " + path("sphere.ply") + " --steps 1", ""},
            {"plot", "plot " + path("run"), ""}};
  }
  static test::TempDir* dir_;
};

test::TempDir* CommandLine::dir_ = nullptr;

TEST_F(CommandLine, every_verb_takes_each_output_spelling_and_quiet_after_the_verb_with_json_on_stdout)
{
  int n = 0;
  for (const Call& call : writing_verbs()) {
    for (const std::string spelling : {"-o", "--output", "--out"}) {
      SCOPED_TRACE(call.verb + " " + spelling);
      const std::string output = path(call.verb + std::to_string(n++) + call.output_extension);
      const auto r = analytic::run_sdflow_streams(call.arguments + " -q --json " + spelling + " " + output);
      ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
      EXPECT_TRUE(fs::exists(output)) << output;
      EXPECT_EQ(r.err, "") << "-q after the verb: errors only";
      const auto keys = json_query(r.out, "' '.join(sorted(d))");
      ASSERT_TRUE(keys) << "stdout is one JSON object: " << r.out;
      EXPECT_NE(keys->find("output"), std::string::npos) << *keys;
    }
  }
}

TEST_F(CommandLine, results_go_to_stdout_and_only_logs_to_stderr)
{
  int n = 0;
  for (const Call& call : writing_verbs()) {
    SCOPED_TRACE(call.verb);
    const std::string output = path("text_" + call.verb + std::to_string(n++) + call.output_extension);
    const auto r = analytic::run_sdflow_streams(call.arguments + " -o " + output);
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_FALSE(r.out.empty()) << "the result is printed on stdout";
    EXPECT_EQ(r.out.find("info: "), std::string::npos) << r.out;
    EXPECT_TRUE(only_log_lines(r.err)) << r.err;
  }
  for (const std::string verb : {"stats", "intersections"}) {
    const auto r = analytic::run_sdflow_streams(verb + " " + path("sphere.ply"));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_FALSE(r.out.empty());
    EXPECT_TRUE(only_log_lines(r.err)) << r.err;
  }
}

TEST_F(CommandLine, json_on_the_reporting_verbs_that_write_nothing)
{
  const std::vector<std::string> calls = {"stats " + path("sphere.ply"), "intersections " + path("sphere.ply"),
                                          "axisymmetric sphere-mode --end-time 0.001", "shape --list"};
  for (const std::string& call : calls) {
    SCOPED_TRACE(call);
    const auto r = analytic::run_sdflow_streams(call + " --json");
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_TRUE(json_query(r.out, "len(d)")) << r.out;
  }
}

TEST_F(CommandLine, json_on_failure_holds_the_error_kind_exit_code_and_findings_with_their_codes)
{
  test::write_file(*dir_ / "fan.off",
                   "OFF\n5 3 0\n0 0 0\n1 0 0\n0 1 0\n0 -1 0\n0 0 1\n3 0 1 2\n3 1 0 3\n3 0 1 4\n");
  const auto invalid = analytic::run_sdflow_streams("stats --json " + path("fan.off"));
  EXPECT_EQ(invalid.exit_code, 2);
  EXPECT_EQ(json_query(invalid.out, "d['error']"), "invalid-mesh") << invalid.out;
  EXPECT_EQ(json_query(invalid.out, "d['exit_code']"), "2");
  const auto codes = json_query(invalid.out, "' '.join(f['code'] for f in d['findings'])");
  ASSERT_TRUE(codes) << invalid.out;
  EXPECT_NE(codes->find("non-manifold-edge"), std::string::npos) << *codes;
  EXPECT_NE(invalid.err.find("shared by 3 faces"), std::string::npos) << "the message stays on stderr";

  // Every verb that reads a file: a missing one is an io-error, reported as JSON.
  for (Call call : writing_verbs()) {
    if (call.verb == "shape")
      continue; // reads no file
    SCOPED_TRACE(call.verb);
    for (const std::string& existing : {path("sphere.ply"), path("holed.off"), path("cloud.ply"), path("run")})
      if (const auto at = call.arguments.find(existing); at != std::string::npos)
        call.arguments.replace(at, existing.size(), path("missing.ply"));
    const auto r = analytic::run_sdflow_streams(call.arguments + " --json -o " + path("never" + call.output_extension));
    EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
    const auto kind = json_query(r.out, "d['error'] + ' ' + str(d['exit_code']) + ' ' + str(len(d['message']) > 0)");
    ASSERT_TRUE(kind) << r.out;
    EXPECT_NE(kind->find(" 2 True"), std::string::npos) << *kind;
  }

  const auto usage = analytic::run_sdflow_streams("stats --json --no-such-option " + path("sphere.ply"));
  EXPECT_EQ(usage.exit_code, 2);
  EXPECT_EQ(json_query(usage.out, "d['error']"), "usage") << usage.out;

  const auto parameter = analytic::run_sdflow_streams("remesh --json " + path("sphere.ply") + " -o " +
                                                      path("r.ply") + " --edge-length 1e-9");
  EXPECT_EQ(parameter.exit_code, 2);
  EXPECT_EQ(json_query(parameter.out, "d['error']"), "invalid-parameter") << parameter.out;
}

TEST_F(CommandLine, quiet_and_verbose_mean_the_same_before_and_after_the_verb)
{
  for (const std::string quiet : {"-q run", "run -q", "run --quiet", "--quiet run"}) {
    SCOPED_TRACE(quiet);
    const auto r = analytic::run_sdflow_streams(quiet + " --input " + path("sphere.ply") + " --steps 1 --out " +
                                                path("quiet_" + std::to_string(quiet.size()) + quiet.substr(0, 2)));
    ASSERT_EQ(r.exit_code, 0) << r.out << r.err;
    EXPECT_EQ(r.err, "");
    EXPECT_FALSE(r.out.empty());
  }
  const auto before = analytic::run_sdflow_streams("-v remesh " + path("sphere.ply") + " -o " + path("v1.ply") +
                                                   " --edge-length 0.4");
  const auto after = analytic::run_sdflow_streams("remesh " + path("sphere.ply") + " -o " + path("v2.ply") +
                                                  " --edge-length 0.4 --verbose");
  ASSERT_EQ(before.exit_code, 0) << before.err;
  ASSERT_EQ(after.exit_code, 0) << after.err;
  EXPECT_NE(before.err.find("debug: "), std::string::npos) << before.err;
  EXPECT_NE(after.err.find("debug: "), std::string::npos) << after.err;
}

TEST_F(CommandLine, older_option_names_still_work)
{
  const std::vector<std::string> calls = {
      "normals " + path("sphere.ply") + " -o " + path("k.ply") + " --k 10",
      "normals " + path("sphere.ply") + " -o " + path("n.ply") + " --neighbours 10",
      "reconstruct " + path("cloud.ply") + " -o " + path("k.off") + " --k 10",
      "fill-holes " + path("holed.off") + " -o " + path("loop.off") + " --max-loop-length 100",
      "fill-holes " + path("holed.off") + " -o " + path("hole.off") + " --max-hole-length 100",
      "components " + path("sphere.ply") + " -o " + path("c.off") + " --min-faces 2",
      "components " + path("sphere.ply") + " -o " + path("d.off") + " --min-component-faces 2",
      "remesh " + path("sphere.ply") + " -o " + path("i.off") + " --edge-length 0.4 --iterations 1",
      "remesh " + path("sphere.ply") + " -o " + path("j.off") + " --edge-length 0.4 --remesh-iterations 1",
      "axisymmetric sphere-mode --t-end 0.001 --csv " + path("series_csv.csv"),
      "axisymmetric sphere-mode --end-time 0.001 --out " + path("series_out.csv"),
      "run --input " + path("sphere.ply") + " --steps 1 -q --output " + path("run_output"),
      "stats --json " + path("sphere.ply") + " -q",
  };
  for (const std::string& call : calls) {
    SCOPED_TRACE(call);
    const auto r = analytic::run_sdflow_streams(call);
    EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  }
  EXPECT_TRUE(fs::exists(*dir_ / "series_csv.csv"));
  EXPECT_TRUE(fs::exists(*dir_ / "series_out.csv"));
  // One default encoding: binary PLY, --ascii for text.
  ASSERT_EQ(analytic::run_sdflow("normals " + path("sphere.ply") + " -o " + path("binary.ply")).exit_code, 0);
  ASSERT_EQ(analytic::run_sdflow("normals " + path("sphere.ply") + " --ascii -o " + path("ascii.ply")).exit_code, 0);
  EXPECT_NE(test::read_file(*dir_ / "binary.ply").find("format binary_little_endian"), std::string::npos);
  EXPECT_NE(test::read_file(*dir_ / "ascii.ply").find("format ascii"), std::string::npos);
  EXPECT_EQ(analytic::run_sdflow("normals " + path("sphere.ply") + " --ascii --binary -o " + path("x.ply")).exit_code,
            2);
}

TEST(CommandLineHelp, lists_choices_without_cli11_notation_or_source_pointers)
{
  const std::vector<std::string> verbs = all_verbs();
  ASSERT_GE(verbs.size(), 14u);
  const std::regex source_file(R"(\b[A-Za-z_/]+\.(h|hpp|cpp)\b)");
  for (const std::string& verb : verbs) {
    SCOPED_TRACE(verb);
    const auto help = analytic::run_sdflow_streams(verb + " --help");
    ASSERT_EQ(help.exit_code, 0) << help.err;
    for (const char* noise : {"{false}", "{true}", "ENUM", "TEXT:", "->", "INT in [", "POSITIVE", "NONNEGATIVE"})
      EXPECT_EQ(help.out.find(noise), std::string::npos) << noise << " in:\n" << help.out;
    EXPECT_FALSE(std::regex_search(help.out, source_file)) << help.out;
    EXPECT_NE(help.out.find("-q, --quiet"), std::string::npos);
    EXPECT_NE(help.out.find("-v, --verbose"), std::string::npos);
    EXPECT_NE(help.out.find("--json"), std::string::npos) << "every verb reports as JSON";
  }
  const auto has = [](const std::string& verb, const std::string& text) {
    const std::string help = analytic::run_sdflow_streams(verb + " --help").out;
    return help.find(text) != std::string::npos;
  };
  EXPECT_TRUE(has("run", "--curvature cotangent|normal_integral|normal_integral_angle_sum"));
  EXPECT_TRUE(has("fill-holes", "--stages fair|refine|triangulate (default: fair)"));
  EXPECT_TRUE(has("render", "--colour curvature|none"));
  EXPECT_TRUE(has("axisymmetric", "torus|capsule|dumbbell|sphere-mode|profile"));
  EXPECT_TRUE(has("run", "--out, -o, --output") || has("run", "-o, --out, --output"));
  for (const std::string verb : {"components", "fill-holes", "normals", "plot", "reconstruct", "remesh", "render",
                                 "retriangulate", "shape", "union", "intersections", "axisymmetric"})
    EXPECT_TRUE(has(verb, "-o, --output, --out")) << verb;
}

} // namespace
} // namespace sdflow
