#include "io/temp_dir.h"
#include "sdflow/errors.h"
#include "sdflow/io/point_cloud.h"
#include "support/point_samples.h"

#include <gtest/gtest.h>

namespace sdflow {
namespace {

TEST(PointCloud, round_trip_is_exact_in_binary_and_ascii)
{
  const test::TempDir dir;
  const auto s = samples::torus(500, 1.0, 0.4, 81);
  for (auto encoding : {Encoding::binary, Encoding::ascii}) {
    SCOPED_TRACE(encoding == Encoding::binary ? "binary" : "ascii");
    write_point_cloud({s.points, s.normals}, dir / "cloud.ply", encoding);
    const PointCloud back = read_point_cloud(dir / "cloud.ply");
    EXPECT_EQ(back.points, s.points);
    EXPECT_EQ(back.normals, s.normals);
  }
}

TEST(PointCloud, points_without_normals_read_back_without_normals)
{
  const test::TempDir dir;
  const auto s = samples::sphere(100, 1.0, 82);
  write_point_cloud({s.points, VertexVectors(0, 3)}, dir / "bare.ply");
  const PointCloud back = read_point_cloud(dir / "bare.ply");
  EXPECT_EQ(back.points, s.points);
  EXPECT_EQ(back.normals.rows(), 0);
  // A file declaring only some of nx, ny, nz has no normals either.
  test::write_file(dir / "partial.ply", "ply\nformat ascii 1.0\nelement vertex 2\nproperty float x\nproperty float y\n"
                                        "property float z\nproperty float nx\nend_header\n0 0 0 1\n1 0 0 1\n");
  const PointCloud partial = read_point_cloud(dir / "partial.ply");
  EXPECT_EQ(partial.points.rows(), 2);
  EXPECT_EQ(partial.normals.rows(), 0);
}

TEST(PointCloud, bad_requests_are_rejected)
{
  const test::TempDir dir;
  const auto s = samples::sphere(10, 1.0, 83);
  EXPECT_THROW(write_point_cloud({s.points, s.normals}, dir / "cloud.off"), IoError);
  EXPECT_THROW(write_point_cloud({s.points, s.normals.topRows(5)}, dir / "cloud.ply"), InvalidParameter);
  EXPECT_THROW(read_point_cloud(dir / "missing.ply"), IoError);
}

} // namespace
} // namespace sdflow
