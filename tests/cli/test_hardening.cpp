//! Hostile and careless inputs to the command line (issue 13): each never crashes, hangs, runs a
//! command or misleads, and exits with the documented code and a reason.
#include "io/temp_dir.h"
#include "sdflow/io/io.h"
#include "support/analytic_meshes.h"
#include "support/run_command.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace sdflow {
namespace {

namespace fs = std::filesystem;
using analytic::run_sdflow;

constexpr const char* octahedron_faces = "3 0 2 4\n3 2 1 4\n3 1 3 4\n3 3 0 4\n3 2 0 5\n3 1 2 5\n3 3 1 5\n3 0 3 5\n";

//! An octahedron as OFF text, with vertex 0 at `x0` on the x axis and every z scaled by `z`.
std::string octahedron(double x0 = 1, double z = 1)
{
  return fmt::format("OFF\n6 8 0\n{} 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0 0 {}\n0 0 {}\n{}", x0, z, -z, octahedron_faces);
}

void expect_mentions(const analytic::CommandResult& r, const std::string& part)
{
  EXPECT_NE(r.output.find(part), std::string::npos) << "'" << part << "' missing from: " << r.output;
}

// Defect 1: a far-away vertex crashed TetGen (exit 139); now a reason and exit 2, or 0 without it.
TEST(StatsHardening, far_away_vertex_gives_a_reason_not_a_crash)
{
  test::TempDir dir;
  for (const double far : {1e9, 4.3e9}) {
    SCOPED_TRACE(far);
    test::write_file(dir / "far.off", octahedron(far));
    const auto r = run_sdflow("stats " + (dir / "far.off").string());
    EXPECT_EQ(r.exit_code, 2) << r.output;
    expect_mentions(r, "--no-tetgen");
    EXPECT_EQ(run_sdflow("stats --no-tetgen " + (dir / "far.off").string()).exit_code, 0);
  }
  Mesh sphere = analytic::icosphere(2);
  sphere.set_point(Mesh::VertexHandle(7), Mesh::Point(0, 2e9, 0));
  write_mesh(sphere, dir / "sphere.ply", {.encoding = Encoding::binary});
  const auto r = run_sdflow("stats " + (dir / "sphere.ply").string());
  EXPECT_EQ(r.exit_code, 2) << r.output;
}

// Defect 2: flat closed surfaces aborted TetGen (exit 134) and `run` accepted them.
TEST(StatsHardening, flat_closed_surfaces_are_refused_as_zero_volume_by_stats_and_run)
{
  test::TempDir dir;
  const std::pair<const char*, std::string> flat[] = {
      {"z0", "OFF\n3 2 0\n0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n3 0 2 1\n"},
      {"z1", "OFF\n3 2 0\n0 0 1\n1 0 1\n0 1 1\n3 0 1 2\n3 0 2 1\n"},
      {"x0", "OFF\n3 2 0\n0 0 0\n0 1 0\n0 0 1\n3 0 1 2\n3 0 2 1\n"},
      {"octahedron", "OFF\n6 8 0\n1 0 0\n-1 0 0\n0 1 0\n0 -1 0\n0.25 0.25 0\n-0.25 -0.25 0\n" +
                         std::string(octahedron_faces)}};
  for (const auto& [name, text] : flat) {
    SCOPED_TRACE(name);
    test::write_file(dir / (std::string(name) + ".off"), text);
    const auto stats = run_sdflow("stats " + (dir / (std::string(name) + ".off")).string());
    EXPECT_EQ(stats.exit_code, 2) << stats.output;
    expect_mentions(stats, "encloses no volume");
    const auto run = run_sdflow("run --input " + (dir / (std::string(name) + ".off")).string() + " --out " +
                                (dir / name).string() + " --steps 2 --quiet");
    EXPECT_EQ(run.exit_code, 2) << run.output;
  }
}

// Defect 3: a newline in --title ended gnuplot's string; what followed ran as gnuplot commands.
TEST(RenderHardening, control_characters_never_reach_gnuplot)
{
  test::TempDir dir;
  write_mesh(analytic::icosphere(1), dir / "s.ply");
  const fs::path marker = dir / "pwned";
  // The shell passes the file's text as it is, newlines included.
  test::write_file(dir / "title", "x'\nsystem \"touch " + marker.string() + "\"\n#");
  const auto r = run_sdflow("render " + (dir / "s.ply").string() + " -o " + (dir / "s.png").string() +
                            " --title \"$(cat " + (dir / "title").string() + ")\"");
  EXPECT_EQ(r.exit_code, 2) << r.output;
  expect_mentions(r, "control character");
  EXPECT_FALSE(fs::exists(marker)) << "gnuplot ran a command from the title";
  // Quotes, backquotes and macros are only text in gnuplot's single-quoted strings.
  const auto q = run_sdflow("render " + (dir / "s.ply").string() + " -o " + (dir / "q.png").string() +
                            " --title \"it's \\`touch " + marker.string() + "\\` @x\"");
  EXPECT_EQ(q.exit_code, 0) << q.output;
  EXPECT_FALSE(fs::exists(marker)) << "gnuplot ran a command from the title";
  // render hands gnuplot only its own temporary paths: any output name is fine.
  test::write_file(dir / "path", (dir / "a\nb.png").string());
  const auto p = run_sdflow("render " + (dir / "s.ply").string() + " -o \"$(cat " + (dir / "path").string() + ")\"");
  EXPECT_EQ(p.exit_code, 0) << p.output;
  EXPECT_TRUE(fs::exists(dir / "a\nb.png"));
}

TEST(PlotHardening, event_names_from_metrics_are_quoted_for_gnuplot)
{
  test::TempDir dir;
  fs::create_directories(dir / "run");
  const fs::path marker = dir / "pwned";
  test::write_file(dir / "run/metrics.csv",
                   "step,time,tau,vertices,faces,components,genus,area,volume,mean_curvature,curvature_deviation_pct,"
                   "d1,d2,debris_volume,event\n0,0,0,100,196,1,0,10,2,-1,5,0,0,0,\n1,0.5,0.5,100,196,1,0,9.5,2,-1,4,0,0,0,x' ; system 'touch " +
                       marker.string() + "' ; #\n");
  const auto r = run_sdflow("plot " + (dir / "run").string());
  EXPECT_EQ(r.exit_code, 0) << r.output;
  EXPECT_FALSE(fs::exists(marker)) << "gnuplot ran a command from metrics.csv";
  // plot writes into paths gnuplot opens itself: one with a newline is refused.
  fs::create_directories(dir / "a\nb");
  fs::copy_file(dir / "run/metrics.csv", dir / "a\nb/metrics.csv");
  test::write_file(dir / "path", (dir / "a\nb").string());
  const auto p = run_sdflow("plot \"$(cat " + (dir / "path").string() + ")\"");
  EXPECT_EQ(p.exit_code, 2) << p.output;
  EXPECT_NE(p.output.find("control character"), std::string::npos) << p.output;
}

// Defect 4: overlapping closed bodies: reported, and TetGen's volume compared like with like.
TEST(StatsHardening, overlapping_bodies_are_reported_and_volumes_compare_like_with_like)
{
  test::TempDir dir;
  write_mesh(analytic::disjoint_union(analytic::icosphere(2), analytic::icosphere(2, 1.0, Eigen::Vector3d(0.5, 0, 0))),
             dir / "two.ply", {.encoding = Encoding::binary});
  const auto r = run_sdflow("stats --json " + (dir / "two.ply").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  expect_mentions(r, "\"self-intersection\"");
  EXPECT_EQ(r.output.find("\"self_intersecting_pairs\" : 0"), std::string::npos) << r.output;
  const auto t = run_sdflow("stats " + (dir / "two.ply").string());
  ASSERT_EQ(t.exit_code, 0) << t.output;
  expect_mentions(t, "triangles intersect");
  // TetGen is not asked to mesh components that cross each other (issue 32): stats says so and
  // gives no TetGen volume for them rather than one of a different body.
  expect_mentions(t, "TetGen not called on 2 closed component(s) with faces in intersecting pairs");
  EXPECT_EQ(t.output.find(" tetrahedra)"), std::string::npos) << t.output;
  EXPECT_EQ(t.output.find("relative difference"), std::string::npos) << t.output;
  const auto clean = run_sdflow("stats --json " + (dir / "two.ply").string() + ".none");
  EXPECT_EQ(clean.exit_code, 2);
}

// Defect 6: a surface united with itself came out empty.
TEST(UnionHardening, a_surface_with_itself_gives_the_surface_back)
{
  test::TempDir dir;
  write_mesh(analytic::icosphere(2), dir / "a.ply", {.encoding = Encoding::binary});
  const auto r = run_sdflow("union " + (dir / "a.ply").string() + " " + (dir / "a.ply").string() + " -o " +
                            (dir / "u.ply").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_EQ(read_mesh(dir / "u.ply").mesh.n_faces(), analytic::icosphere(2).n_faces());
}

// Defect 8: --out that cannot be a directory gave exit 1 "unexpected error: filesystem error".
TEST(RunHardening, out_that_cannot_be_a_directory_exits_2_with_the_reason)
{
  test::TempDir dir;
  write_mesh(analytic::icosphere(1), dir / "s.ply");
  test::write_file(dir / "file", "x");
  const std::pair<std::string, std::string> cases[] = {{(dir / "file").string(), "not a directory"},
                                                       {(dir / "file/run").string(), "cannot create"},
                                                       {"/dev/null", "not a directory"},
                                                       {(dir / std::string(300, 'n')).string(), "cannot create"}};
  for (const auto& [out, reason] : cases) {
    SCOPED_TRACE(out);
    const auto r = run_sdflow("run --input " + (dir / "s.ply").string() + " --out " + out + " --steps 1 --quiet");
    EXPECT_EQ(r.exit_code, 2) << r.output;
    expect_mentions(r, reason);
    EXPECT_EQ(r.output.find("unexpected"), std::string::npos) << r.output;
  }
}

// Defect 9: absurd sizes and iteration counts are refused up front with the estimate.
TEST(LimitsHardening, absurd_sizes_and_iterations_are_refused_with_the_estimate)
{
  test::TempDir dir;
  write_mesh(analytic::icosphere(2), dir / "s.ply", {.encoding = Encoding::binary});
  const std::string s = (dir / "s.ply").string(), o = (dir / "o.ply").string();
  const std::pair<std::string, std::string> cases[] = {
      {"run --input " + s + " --out " + (dir / "r").string() + " --retriangulate --edge-length 1e-6 --steps 1",
       "vertices"},
      {"run --input " + s + " --out " + (dir / "r").string() + " --retriangulate --edge-length 3 --steps 1",
       "too long"},
      {"remesh " + s + " -o " + o + " --edge-length 1e-5", "vertices"},
      {"retriangulate " + s + " -o " + o + " --edge-length 1e-5", "vertices"},
      {"remesh " + s + " -o " + o + " --edge-length 0.1 --remesh-iterations 1000000", "--remesh-iterations 1000000"},
      {"shape sphere --remesh-iterations 1000000000 -o " + o, "--remesh-iterations"},
      {"shape sphere --vertices 100000000 -o " + o, "vertices"},
      {"shape sphere --edge-length 1e-6 -o " + o, "vertices"},
      {"run --input " + s + " --out " + (dir / "r").string() + " --steps 1000000000000", "--steps"}};
  for (const auto& [arguments, reason] : cases) {
    SCOPED_TRACE(arguments);
    const auto r = run_sdflow(arguments);
    EXPECT_EQ(r.exit_code, 2) << r.output;
    expect_mentions(r, reason);
    expect_mentions(r, "--force");
  }
  EXPECT_FALSE(fs::exists(dir / "r/metrics.csv"));
  // --force lets a refused request through.
  const auto forced = run_sdflow("remesh " + s + " -o " + o + " --edge-length 0.2 --iterations 1001 --force");
  EXPECT_EQ(forced.exit_code, 0) << forced.output;
}

// Defect 12: numbers on the command line are plain decimals in range.
TEST(NumbersHardening, out_of_range_hexadecimal_and_blank_numbers_are_refused)
{
  test::TempDir dir;
  // 162 vertices: a 42-vertex sphere is refined for the flow (coarse_input.h) and its facets' edges
  // then take a τ far below 1e-3.
  write_mesh(analytic::icosphere(2), dir / "s.ply");
  const std::string run = "run --input " + (dir / "s.ply").string() + " --out " + (dir / "r").string() + " --quiet ";
  for (const std::string bad : {"--steps 9223372036854775808", "--snapshot-every 9223372036854775808", "--steps 0x10",
                                "--steps ' 5'", "--tau 0x1p-3", "--tau ' 0.1'", "--tau nan", "--steps 5e0"}) {
    SCOPED_TRACE(bad);
    const auto r = run_sdflow(run + bad);
    EXPECT_EQ(r.exit_code, 2) << r.output;
  }
  EXPECT_FALSE(fs::exists(dir / "r"));
  const auto good = run_sdflow(run + "--steps +2 --tau 1e-3");
  EXPECT_EQ(good.exit_code, 0) << good.output;
  const auto view = run_sdflow("render " + (dir / "s.ply").string() + " -o " + (dir / "s.png").string() +
                               " --view 60,30 --size 200,150");
  EXPECT_EQ(view.exit_code, 0) << view.output;
}

// Defect 12: a schedule that ends before the run says so.
TEST(NumbersHardening, a_schedule_that_ends_before_the_run_is_reported)
{
  test::TempDir dir;
  write_mesh(analytic::icosphere(2), dir / "s.ply");
  test::write_file(dir / "tau.csv", "1,2,1e-4\n");
  const auto r = run_sdflow("run --input " + (dir / "s.ply").string() + " --out " + (dir / "r").string() +
                            " --schedule " + (dir / "tau.csv").string() + " --steps 4"); // -q would hide the warning
  EXPECT_EQ(r.exit_code, 0) << r.output;
  expect_mentions(r, "schedule ends at step 2");
  EXPECT_NE(test::read_file(dir / "r/events.log").find("schedule ends at step 2"), std::string::npos);
}

} // namespace
} // namespace sdflow
