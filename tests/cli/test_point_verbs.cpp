//! `sdflow normals`, `sdflow reconstruct` and `sdflow fill-holes` end to end: results, exit codes.
#include "io/temp_dir.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/io.h"
#include "sdflow/io/point_cloud.h"
#include "support/analytic_meshes.h"
#include "support/run_command.h"

#include <gtest/gtest.h>

#include <string>

namespace sdflow {
namespace {

TEST(PointVerbs, normals_then_reconstruct_recover_the_torus)
{
  const test::TempDir dir;
  constexpr double major = 1.0, minor = 0.4;
  write_mesh(analytic::torus(40, 20, major, minor), dir / "torus.off");
  auto r = analytic::run_sdflow("normals " + (dir / "torus.off").string() + " -o " + (dir / "cloud.ply").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const PointCloud cloud = read_point_cloud(dir / "cloud.ply");
  ASSERT_EQ(cloud.points.rows(), 800);
  ASSERT_EQ(cloud.normals.rows(), 800);
  for (Eigen::Index i = 0; i < cloud.points.rows(); ++i) {
    const Eigen::Vector3d p = cloud.points.row(i).transpose();
    const Eigen::Vector3d outward = p - major * Eigen::Vector3d(p.x(), p.y(), 0).normalized();
    ASSERT_GT(cloud.normals.row(i).dot(outward), 0) << i;
  }
  r = analytic::run_sdflow("reconstruct " + (dir / "cloud.ply").string() + " -o " + (dir / "torus_back.ply").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  const auto topology = component_topology(read_mesh(dir / "torus_back.ply").mesh);
  ASSERT_EQ(topology.size(), 1u);
  EXPECT_EQ(topology[0].genus, 1);
  EXPECT_TRUE(topology[0].closed());
}

TEST(PointVerbs, reconstruct_estimates_missing_normals)
{
  const test::TempDir dir;
  const Mesh sphere = analytic::icosphere(3, 1.0);
  write_point_cloud({vertex_positions(sphere), VertexVectors(0, 3)}, dir / "bare.ply");
  const auto r = analytic::run_sdflow("reconstruct " + (dir / "bare.ply").string() + " -o " + (dir / "sphere.obj").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("estimated"), std::string::npos) << r.output;
  const auto topology = component_topology(read_mesh(dir / "sphere.obj").mesh);
  ASSERT_EQ(topology.size(), 1u);
  EXPECT_EQ(topology[0].genus, 0);
  EXPECT_TRUE(topology[0].closed());
}

TEST(PointVerbs, fill_holes_closes_short_loops_only)
{
  const test::TempDir dir;
  Mesh sphere = analytic::icosphere(3, 1.0);
  for (auto f : sphere.faces())
    if (sphere.calc_face_centroid(f)[2] > 0.9)
      sphere.delete_face(f, true);
  sphere.garbage_collection();
  write_mesh(sphere, dir / "holed.off");
  auto r = analytic::run_sdflow("fill-holes " + (dir / "holed.off").string() + " -o " + (dir / "filled.off").string());
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_TRUE(component_topology(read_mesh(dir / "filled.off").mesh)[0].closed());
  r = analytic::run_sdflow("fill-holes " + (dir / "holed.off").string() + " -o " + (dir / "open.off").string() +
                           " --max-loop-length 0.1");
  ASSERT_EQ(r.exit_code, 0) << r.output;
  EXPECT_NE(r.output.find("longer than --max-hole-length"), std::string::npos) << r.output;
  EXPECT_EQ(component_topology(read_mesh(dir / "open.off").mesh)[0].boundary_loops, 1);
}

TEST(PointVerbs, bad_input_exits_with_code_2)
{
  const test::TempDir dir;
  write_mesh(analytic::icosphere(1, 1.0), dir / "sphere.off");
  EXPECT_EQ(analytic::run_sdflow("normals " + (dir / "missing.off").string() + " -o " + (dir / "x.ply").string()).exit_code, 2);
  EXPECT_EQ(analytic::run_sdflow("normals " + (dir / "sphere.off").string() + " -o " + (dir / "x.off").string()).exit_code, 2);
  EXPECT_EQ(analytic::run_sdflow("normals " + (dir / "sphere.off").string() + " -o " + (dir / "x.ply").string() + " --k 3").exit_code, 2);
  test::write_file(dir / "line.ply", "ply\nformat ascii 1.0\nelement vertex 4\nproperty double x\nproperty double y\n"
                                     "property double z\nproperty double nx\nproperty double ny\nproperty double nz\n"
                                     "end_header\n0 0 0 0 0 1\n1 0 0 0 0 1\n2 0 0 0 0 1\n3 0 0 0 0 1\n");
  EXPECT_EQ(analytic::run_sdflow("reconstruct " + (dir / "line.ply").string() + " -o " + (dir / "x.off").string()).exit_code, 2);
  EXPECT_EQ(analytic::run_sdflow("fill-holes " + (dir / "sphere.off").string() + " -o " + (dir / "y.off").string() +
                                 " --max-loop-length -1").exit_code, 2);
}

} // namespace
} // namespace sdflow
