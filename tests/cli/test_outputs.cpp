//! What `sdflow` writes for other tools, and its safe default: re-triangulation on, and without it a
//! run that stops at the first self-intersection; PLY files with H and N as `quality` and
//! `nx ny nz`; .vtp files it reads back; run.toml naming the sdflow that wrote it.
#include "io/temp_dir.h"
#include "sdflow/io/io.h"
#include "sdflow/io/vtk.h"
#include "sdflow/version.h"
#include "support/analytic_meshes.h"
#include "support/run_command.h"

#include <gtest/gtest.h>

#include <fmt/format.h>

#include <string>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

const VertexField* find_field(const PolygonSoup& soup, const std::string& name)
{
  for (const VertexField& f : soup.vertex_fields)
    if (f.name == name)
      return &f;
  return nullptr;
}

std::string last_line(const fs::path& file)
{
  const std::string text = test::read_file(file);
  const std::size_t end = text.find_last_not_of('\n');
  return text.substr(text.rfind('\n', end) + 1, end - text.rfind('\n', end));
}

//! A torus with a small hole (R = 1, r = 0.75), whose hole closes within t ≈ 0.013.
fs::path fat_torus(const test::TempDir& dir)
{
  const auto shape = analytic::run_sdflow("shape torus --major 1 --minor 0.75 --vertices 800 -o " +
                                          (dir / "torus.ply").string());
  EXPECT_EQ(shape.exit_code, 0) << shape.output;
  return dir / "torus.ply";
}

TEST(SafeDefaults, without_retriangulation_a_run_stops_at_its_first_self_intersection_naming_the_option)
{
  test::TempDir dir;
  const fs::path torus = fat_torus(dir);
  const auto r = analytic::run_sdflow("run --input " + torus.string() + " --out " + (dir / "off").string() +
                                      " --end-time 1 --no-retriangulate");
  EXPECT_EQ(r.exit_code, 3) << r.output;
  EXPECT_NE(r.output.find("makes the surface intersect itself"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("run with --retriangulate"), std::string::npos) << r.output;
  // The step that would intersect is not recorded: metrics.csv ends with the one before it.
  const std::string events = test::read_file(dir / "off/events.log");
  const std::size_t at = events.find("stopped: step ");
  ASSERT_NE(at, std::string::npos) << events;
  const long failed = std::stol(events.substr(at + 14));
  EXPECT_EQ(last_line(dir / "off/metrics.csv").substr(0, last_line(dir / "off/metrics.csv").find(',')),
            std::to_string(failed - 1));
}

TEST(SafeDefaults, by_default_the_same_run_goes_through_the_seal)
{
  test::TempDir dir;
  const fs::path torus = fat_torus(dir);
  const auto r = analytic::run_sdflow("run --input " + torus.string() + " --out " + (dir / "on").string() +
                                      " --end-time 1 --stop-at-topology-change --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string row = last_line(dir / "on/metrics.csv");
  EXPECT_NE(row.find("surgery"), std::string::npos) << row;
  const std::string toml = test::read_file(dir / "on/run.toml");
  EXPECT_NE(toml.find("[retriangulation]\nenabled = true\n"), std::string::npos) << toml;
}

TEST(Outputs, run_snapshots_carry_h_n_and_w_in_the_ply_as_in_the_vtp)
{
  test::TempDir dir;
  write_mesh(analytic::ellipsoid(2, 5, 4, 3), dir / "e.ply", {.encoding = Encoding::binary});
  // Without re-triangulation: a remeshed surface's w is 0 (flow.velocity()), this one's is the step's.
  const auto r = analytic::run_sdflow("run --input " + (dir / "e.ply").string() + " --out " + (dir / "run").string() +
                                      " --steps 2 --no-retriangulate --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const PolygonSoup ply = read_polygon_soup(dir / "run/snapshots/step_000002.ply");
  const PolygonSoup vtp = read_polygon_soup(dir / "run/snapshots/step_000002.vtp");
  const VertexField *quality = find_field(ply, "quality"), *w = find_field(ply, "w");
  const VertexField *h = find_field(vtp, "H"), *n = find_field(vtp, "N"), *vtp_w = find_field(vtp, "w");
  ASSERT_TRUE(quality && w && h && n && vtp_w);
  ASSERT_EQ(ply.normals.size(), ply.points.size());
  EXPECT_EQ(quality->values, h->values);
  EXPECT_EQ(w->values, vtp_w->values);
  EXPECT_GT(w->values.cwiseAbs().maxCoeff(), 0) << "w of the step, not zeros";
  for (std::size_t i = 0; i < ply.points.size(); ++i) {
    EXPECT_EQ(ply.points[i], vtp.points[i]);
    EXPECT_EQ(ply.normals[i], n->values.row(static_cast<Eigen::Index>(i)).transpose());
  }
}

TEST(Outputs, verb_outputs_carry_h_and_n_and_every_verb_reads_vtp)
{
  test::TempDir dir;
  const auto shape = analytic::run_sdflow("shape sphere --vertices 600 -o " + (dir / "s.ply").string());
  ASSERT_EQ(shape.exit_code, 0) << shape.output;
  const PolygonSoup soup = read_polygon_soup(dir / "s.ply");
  ASSERT_NE(find_field(soup, "quality"), nullptr);
  EXPECT_EQ(soup.normals.size(), soup.points.size());
  const auto remesh = analytic::run_sdflow("remesh " + (dir / "s.ply").string() + " -o " + (dir / "r.vtp").string() +
                                           " --edge-length 0.2");
  ASSERT_EQ(remesh.exit_code, 0) << remesh.output;
  const PolygonSoup remeshed = read_polygon_soup(dir / "r.vtp");
  ASSERT_NE(find_field(remeshed, "H"), nullptr);
  ASSERT_NE(find_field(remeshed, "N"), nullptr);
  const auto stats = analytic::run_sdflow("stats " + (dir / "r.vtp").string() + " --json --no-tetgen");
  ASSERT_EQ(stats.exit_code, 0) << stats.output;
  EXPECT_NE(stats.output.find(fmt::format("\"vertices\" : {}", remeshed.points.size())), std::string::npos)
      << stats.output;
  test::write_file(dir / "bad.vtp", "<?xml version=\"1.0\"?><VTKFile type=\"UnstructuredGrid\"/>");
  const auto bad = analytic::run_sdflow("stats " + (dir / "bad.vtp").string());
  EXPECT_EQ(bad.exit_code, 2) << bad.output;
  EXPECT_NE(bad.output.find("bad.vtp: a VTK XML file of type UnstructuredGrid"), std::string::npos) << bad.output;
}

TEST(Outputs, run_toml_records_the_version_and_commit_and_resume_reads_it)
{
  test::TempDir dir;
  write_mesh(analytic::ellipsoid(2, 5, 4, 3), dir / "e.ply", {.encoding = Encoding::binary});
  const auto r = analytic::run_sdflow("run --input " + (dir / "e.ply").string() + " --out " + (dir / "run").string() +
                                      " --steps 2 --quiet");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const std::string toml = test::read_file(dir / "run/run.toml");
  EXPECT_NE(toml.find(fmt::format("[written_by]")), std::string::npos) << toml;
  EXPECT_NE(toml.find(fmt::format("sdflow_version = \"{}\"\n", version())), std::string::npos) << toml;
  EXPECT_NE(toml.find(fmt::format("sdflow_commit = \"{}\"\n", git_commit())), std::string::npos) << toml;
  const std::string commit = git_commit();
  const std::string hash = commit.substr(0, commit.find('-'));
  EXPECT_TRUE(commit == "unknown" || (hash.size() == 40 && hash.find_first_not_of("0123456789abcdef") ==
                                                                 std::string::npos))
      << commit;
  const auto resumed = analytic::run_sdflow("run --resume " + (dir / "run").string() + " --steps 3 --quiet");
  ASSERT_EQ(resumed.exit_code, 0) << resumed.output;
  EXPECT_EQ(last_line(dir / "run/metrics.csv").substr(0, 2), "3,");
}

} // namespace
} // namespace sdflow
