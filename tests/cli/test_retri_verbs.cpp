//! `sdflow intersections` and `sdflow components` end to end: results, files written, exit codes.
#include "sdflow/io/io.h"
#include "sdflow/spatial/intersect.h"
#include "support/analytic_meshes.h"
#include "support/run_command.h"
#include "support/test_meshes.h"

#include <fmt/format.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <filesystem>
#include <fstream>

namespace sdflow {
namespace {

namespace fs = std::filesystem;

class RetriCommands : public ::testing::Test {
protected:
  fs::path dir = fs::temp_directory_path() / ("sdflow_retri_cli_" + std::to_string(::getpid()));
  void SetUp() override { fs::create_directories(dir); }
  void TearDown() override { fs::remove_all(dir); }
  std::string path(const std::string& name) const { return (dir / name).string(); }
};

Mesh pushed_through_icosphere()
{
  return test::mapped(analytic::icosphere(3), [](const Eigen::Vector3d& p) {
    Eigen::Vector3d q = p;
    if (q.z() > 0.2)
      q.z() = 0.2 - 2.2 * (q.z() - 0.2);
    return q;
  });
}

TEST_F(RetriCommands, intersections_json_counts_and_lists_the_exact_pairs)
{
  write_mesh(pushed_through_icosphere(), path("pushed.ply"));
  const auto expected = self_intersections(read_mesh(path("pushed.ply")).mesh);
  ASSERT_FALSE(expected.empty());
  const auto r = analytic::run_sdflow("intersections --json " + path("pushed.ply"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* key : {"\"file\"", "\"faces\"", "\"intersecting_pairs\"", "\"pairs\"", "\"degenerate_faces\""})
    EXPECT_NE(r.output.find(key), std::string::npos) << key;
  EXPECT_NE(r.output.find(fmt::format("\"intersecting_pairs\" : {}", expected.size())), std::string::npos) << r.output;

  const auto text = analytic::run_sdflow("intersections " + path("pushed.ply"));
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find(fmt::format("  {} {}\n", expected[0].first, expected[0].second)), std::string::npos);
}

// Issue 32: a point given twice (bit-identical) where two bodies meet is one corner for the
// search of the file's faces, and two vertices in its repaired copy: both counts are given, and why.
TEST_F(RetriCommands, intersections_of_a_soup_with_a_pinch_point_give_the_repaired_copys_count)
{
  std::ofstream(path("pinch.off")) << "OFF\n8 8 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n0 0 0\n-2 0 0\n0 -2 0\n0 0 -2\n"
                                      "3 0 2 1\n3 0 1 3\n3 0 3 2\n3 1 2 3\n3 4 5 6\n3 4 7 5\n3 4 6 7\n3 5 7 6\n";
  const auto r = analytic::run_sdflow("intersections --json " + path("pinch.off"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("\"intersecting_pairs\" : 0"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"repair_split_points\" : 1"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"repaired_intersecting_pairs\" : 0"), std::string::npos) << r.output;
  const auto text = analytic::run_sdflow("intersections " + path("pinch.off"));
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("repaired copy (sdflow repair) has 0 intersecting pair(s), the same count"),
            std::string::npos) << text.output;
  // A valid file has nothing merged: no second count.
  write_mesh(analytic::icosphere(2), path("sphere.off"));
  EXPECT_EQ(analytic::run_sdflow("intersections --json " + path("sphere.off")).output.find("repaired_intersecting"),
            std::string::npos);
}

TEST_F(RetriCommands, intersections_output_has_none_left)
{
  write_mesh(pushed_through_icosphere(), path("pushed.off"));
  const auto r = analytic::run_sdflow("intersections " + path("pushed.off") + " -o " + path("clean.off"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  ASSERT_TRUE(fs::exists(path("clean.off")));
  EXPECT_TRUE(self_intersections(read_mesh(path("clean.off")).mesh).empty());
  const auto again = analytic::run_sdflow("intersections --json " + path("clean.off"));
  EXPECT_NE(again.output.find("\"intersecting_pairs\" : 0"), std::string::npos) << again.output;
}

TEST_F(RetriCommands, intersections_between_two_surfaces_and_bad_input)
{
  write_mesh(analytic::icosphere(2), path("a.off"));
  write_mesh(analytic::icosphere(2, 1.0, Eigen::Vector3d(1.2, 0.1, 0)), path("b.off"));
  const auto r = analytic::run_sdflow("intersections --json " + path("a.off") + " " + path("b.off"));
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto expected = surface_intersections(read_mesh(path("a.off")).mesh, read_mesh(path("b.off")).mesh);
  ASSERT_FALSE(expected.empty());
  EXPECT_NE(r.output.find(fmt::format("\"intersecting_pairs\" : {}", expected.size())), std::string::npos) << r.output;
  EXPECT_EQ(analytic::run_sdflow("intersections " + path("a.off") + " " + path("b.off") + " -o " + path("c.off"))
              .exit_code,
            2);
  EXPECT_EQ(analytic::run_sdflow("intersections " + path("missing.off")).exit_code, 2);
}

TEST_F(RetriCommands, components_keeps_large_bodies_or_splits_them)
{
  const Mesh sphere = analytic::icosphere(2, 1.0, Eigen::Vector3d(10, 0, 0));
  const Mesh torus = analytic::torus(20, 10, 3, 1);
  const Mesh small = analytic::icosphere(1, 0.5, Eigen::Vector3d(-10, 0, 0));
  write_mesh(test::disjoint_union({&small, &torus, &sphere}), path("bodies.obj"));

  const auto keep = analytic::run_sdflow("components " + path("bodies.obj") + " --min-faces 100 -o " + path("large.obj"));
  ASSERT_EQ(keep.exit_code, 0) << keep.output;
  EXPECT_EQ(read_mesh(path("large.obj")).mesh.n_faces(), 720u);

  const auto split =
    analytic::run_sdflow("components " + path("bodies.obj") + " --keep-largest 2 --split -o " + path("part.ply"));
  ASSERT_EQ(split.exit_code, 0) << split.output;
  EXPECT_EQ(read_mesh(path("part_0.ply")).mesh.n_faces(), 400u);
  EXPECT_EQ(read_mesh(path("part_1.ply")).mesh.n_faces(), 320u);
  EXPECT_FALSE(fs::exists(path("part_2.ply")));

  EXPECT_EQ(analytic::run_sdflow("components " + path("bodies.obj") + " --min-faces 0 -o " + path("x.obj")).exit_code, 2);
  EXPECT_EQ(analytic::run_sdflow("components " + path("bodies.obj")).exit_code, 2);
}

TEST_F(RetriCommands, retriangulate_joins_overlapping_bodies_and_reports_each_stage)
{
  const Mesh a = analytic::icosphere(3, 1.0, Eigen::Vector3d(-0.6, 0, 0));
  const Mesh b = analytic::icosphere(3, 1.0, Eigen::Vector3d(0.6, 0, 0));
  write_mesh(test::disjoint_union({&a, &b}), path("two.off"));
  const auto r = analytic::run_sdflow("retriangulate " + path("two.off") + " -o " + path("one.ply") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* key : {"\"merged_components\" : 1", "\"components_before\" : 2", "\"components_after\" : 1",
                          "\"intersecting_pairs\"", "\"seconds\""})
    EXPECT_NE(r.output.find(key), std::string::npos) << key << " in " << r.output;
  const Mesh one = read_mesh(path("one.ply")).mesh;
  EXPECT_TRUE(self_intersections(one).empty());

  const auto text = analytic::run_sdflow("retriangulate " + path("two.off") + " -o " + path("one.off"));
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("0. 1 intersecting component(s) joined"), std::string::npos) << text.output;
}

TEST_F(RetriCommands, retriangulate_splits_a_neck_crossed_at_its_pinch_and_says_it_rebuilt_each_piece_apart)
{
  const std::string crossed = std::string(SDFLOW_SOURCE_DIR) + "/tests/data/dumbbell-crossed-at-its-pinch.ply";
  const auto r =
      analytic::run_sdflow("retriangulate " + crossed + " -o " + path("two.ply") + " --edge-length 0.5 --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  for (const char* key : {"\"rebuilt_apart\" : true", "\"components_before\" : 1", "\"components_after\" : 2"})
    EXPECT_NE(r.output.find(key), std::string::npos) << key << " in " << r.output;
  const auto text = analytic::run_sdflow("retriangulate " + crossed + " -o " + path("two.off") + " --edge-length 0.5");
  ASSERT_EQ(text.exit_code, 0) << text.output;
  EXPECT_NE(text.output.find("each piece apart"), std::string::npos) << text.output;
}

TEST_F(RetriCommands, retriangulate_keep_boundary_returns_the_rim_vertex_for_vertex)
{
  // A mound rebuilt from its points: with --keep-boundary its rim's vertices come back exactly,
  // without it the rebuild re-triangulates them.
  const Mesh mound = test::mapped(analytic::disk(20, 2.0), [](const Eigen::Vector3d& p) {
    return Eigen::Vector3d(p.x(), p.y(), 0.5 * (1 - p.squaredNorm() / 4));
  });
  write_mesh(mound, path("mound.ply"));
  const auto rim = [](const Mesh& mesh) {
    std::vector<std::array<double, 3>> points;
    for (const auto v : mesh.vertices())
      if (mesh.is_boundary(v))
        points.push_back({mesh.point(v)[0], mesh.point(v)[1], mesh.point(v)[2]});
    std::sort(points.begin(), points.end());
    return points;
  };
  for (const bool keep : {true, false}) {
    const std::string out = path(keep ? "kept.ply" : "free.ply");
    const auto r = analytic::run_sdflow("retriangulate " + path("mound.ply") + " -o " + out +
                                        " --edge-length 0.12 --always-rebuild" + (keep ? " --keep-boundary" : ""));
    ASSERT_EQ(r.exit_code, 0) << r.output;
    EXPECT_EQ(rim(read_mesh(out).mesh) == rim(mound), keep);
  }
}

//! A thin plate with sharp edges whose remeshing crosses itself at its mean edge length whatever the
//! rounds finer there do (RetriangulationHook.a_remeshing_refused_with_nothing_rebuilt_is_reported_with_its_reason):
//! stage 1 is refused and the plate keeps its triangles. The report says so on line 1, where it
//! said "0 splits, 0 collapses, 0 flips" as if it had remeshed, and the JSON carries it.
TEST_F(RetriCommands, retriangulate_says_when_its_remeshing_was_refused)
{
  const Mesh plate = test::cad_plate(1, 0.3, 0.01, 20, 3); // ℓ (its mean edge) 0.075, 7 times its thickness
  write_mesh(plate, path("plate.off"));
  const auto r = analytic::run_sdflow("retriangulate " + path("plate.off") + " -o " + path("kept.ply") + " --json");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("\"remeshing_refused\" : true"), std::string::npos) << r.output;
  EXPECT_NE(r.output.find("\"remeshing_refinements\""), std::string::npos) << r.output;
  const std::string crossings = "\"remeshing_crossings\" : ";
  const auto at = r.output.find(crossings);
  EXPECT_NE(at, std::string::npos) << r.output;
  if (at != std::string::npos) {
    EXPECT_GT(std::stoi(r.output.substr(at + crossings.size())), 0) << r.output;
  }
  EXPECT_EQ(face_indices(read_mesh(path("kept.ply")).mesh), face_indices(plate)) << "a refusal keeps the triangles";

  const auto text = analytic::run_sdflow("retriangulate " + path("plate.off") + " -o " + path("kept.off"));
  ASSERT_EQ(text.exit_code, 0) << text.output;
  const auto first = text.output.find("  1. ");
  ASSERT_NE(first, std::string::npos) << text.output;
  const std::string line = text.output.substr(first, text.output.find('\n', first) - first);
  EXPECT_NE(line.find("refused"), std::string::npos) << line;
  EXPECT_NE(line.find("kept its triangles"), std::string::npos) << line;
  EXPECT_EQ(line.find("splits"), std::string::npos) << line;
}

TEST_F(RetriCommands, retriangulate_refuses_bad_input_and_options_without_writing)
{
  write_mesh(analytic::icosphere(1), path("sphere.off"));
  EXPECT_EQ(analytic::run_sdflow("retriangulate " + path("missing.off") + " -o " + path("x.off")).exit_code, 2);
  EXPECT_EQ(analytic::run_sdflow("retriangulate " + path("sphere.off") + " -o " + path("x.off") + " --neighbours 3")
                .exit_code,
            2);
  const auto nothing_left =
      analytic::run_sdflow("retriangulate " + path("sphere.off") + " -o " + path("x.off") + " --min-component-faces 1000");
  EXPECT_NE(nothing_left.exit_code, 0);
  EXPECT_NE(nothing_left.output.find("nothing is left"), std::string::npos) << nothing_left.output;
  EXPECT_FALSE(fs::exists(path("x.off")));
}

} // namespace
} // namespace sdflow
