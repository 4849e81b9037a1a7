//! Mesh quality statistics.
#include "sdflow/geometry/quality.h"
#include "support/analytic_meshes.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <numbers>
#include <random>

namespace sdflow {
namespace {

TEST(Quality, equilateral_lattice_torus_has_near_sixty_degree_angles_and_valence_six)
{
  const MeshQuality q = mesh_quality(analytic::conformal_torus(64, 6, 3));
  EXPECT_GT(q.min_angle_deg, 55.0);
  EXPECT_LT(q.max_angle_deg, 65.0);
  EXPECT_EQ(q.obtuse_triangle_fraction, 0.0);
  ASSERT_EQ(q.valence_histogram.size(), 1u);
  EXPECT_EQ(q.valence_histogram.begin()->first, 6);
  EXPECT_TRUE(q.boundary_valence_histogram.empty());
}

TEST(Quality, icosahedron_statistics_are_exact)
{
  const MeshQuality q = mesh_quality(analytic::icosphere(0, 1.0));
  EXPECT_NEAR(q.min_angle_deg, 60.0, 1e-9);
  EXPECT_NEAR(q.max_angle_deg, 60.0, 1e-9);
  const double edge = 4.0 / std::sqrt(10 + 2 * std::sqrt(5.0)); // icosahedron inscribed in the unit sphere
  EXPECT_NEAR(q.edge_min, edge, 1e-12);
  EXPECT_NEAR(q.edge_max, edge, 1e-12);
  EXPECT_NEAR(q.edge_stddev, 0.0, 1e-7);
  EXPECT_EQ(q.valence_histogram.at(5), 12);
}

// smallest_angle_deg measures only the corner facing the shortest side: it must be the smallest of
// the three corner angles, on slivers, needles and obtuse triangles alike.
TEST(Quality, smallest_angle_is_the_least_of_the_corner_angles)
{
  Mesh mesh = analytic::icosphere(2, 1.0);
  std::mt19937 random(7);
  std::uniform_real_distribution<double> jitter(-0.08, 0.08);
  for (const auto v : mesh.vertices())
    mesh.set_point(v, mesh.point(v) + Mesh::Point(jitter(random), jitter(random), jitter(random)));
  for (const auto f : mesh.faces()) {
    const std::array<double, 3> angles = corner_angles(mesh, f);
    const double least = *std::min_element(angles.begin(), angles.end()) * 180 / std::numbers::pi;
    EXPECT_NEAR(smallest_angle_deg(mesh, f), least, 1e-12) << "face " << f.idx();
    EXPECT_NEAR(smallest_angle_cosine(mesh, f), std::cos(least * std::numbers::pi / 180), 1e-12) << "face " << f.idx();
  }
  // A triangle with a side of zero length has a zero angle.
  VertexVectors x(3, 3);
  x << 0, 0, 0, 0, 0, 0, 1, 0, 0;
  FaceIndices t(1, 3);
  t << 0, 1, 2;
  EXPECT_EQ(smallest_angle_cosine(make_mesh(x, t), Mesh::FaceHandle(0)), 1.0);
}

TEST(Quality, disk_reports_boundary_valences_separately)
{
  const MeshQuality q = mesh_quality(analytic::disk(3));
  int boundary = 0;
  for (auto [valence, count] : q.boundary_valence_histogram)
    boundary += count;
  EXPECT_EQ(boundary, 18); // outer ring of 6·3 vertices
  EXPECT_GT(q.min_angle_p05_deg, 0.0);
  EXPECT_LE(q.min_angle_p05_deg, 60.0);
}

} // namespace
} // namespace sdflow
