//! The strip between two loops (retri/zip_loops.h).
#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/io/validate.h"
#include "sdflow/retri/zip_loops.h"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

namespace sdflow {
namespace {

//! Two concentric circles in the plane z = 0, of n and m points, radii 2 and 1, both clockwise seen
//! from +z (as the boundary halfedges of an outward-facing disk run), the outer first.
VertexVectors circles(int n, int m)
{
  VertexVectors x(n + m, 3);
  for (int i = 0; i < n; ++i) {
    const double a = -2 * std::numbers::pi * i / n;
    x.row(i) << 2 * std::cos(a), 2 * std::sin(a), 0;
  }
  for (int j = 0; j < m; ++j) {
    const double a = -2 * std::numbers::pi * (j + 0.3) / m;
    x.row(n + j) << std::cos(a), std::sin(a), 0;
  }
  return x;
}

TEST(ZipLoops, two_circles_become_an_annulus_facing_up)
{
  constexpr int n = 17, m = 9;
  const VertexVectors x = circles(n, m);
  std::vector<int> outer(n), inner(m);
  for (int i = 0; i < n; ++i)
    outer[static_cast<std::size_t>(i)] = i;
  for (int j = 0; j < m; ++j)
    inner[static_cast<std::size_t>(j)] = n + j;
  VertexVectors up = VertexVectors::Zero(n + m, 3);
  up.col(2).setOnes();
  const auto strip = zip_loops(x, up, outer, inner);
  ASSERT_EQ(strip.size(), static_cast<std::size_t>(n + m)) << "one triangle per edge of either loop";
  FaceIndices t(static_cast<Eigen::Index>(strip.size()), 3);
  for (std::size_t f = 0; f < strip.size(); ++f) {
    t.row(static_cast<Eigen::Index>(f)) << strip[f][0], strip[f][1], strip[f][2];
    const Eigen::Vector3d a = x.row(strip[f][0]), b = x.row(strip[f][1]), c = x.row(strip[f][2]);
    EXPECT_GT((b - a).cross(c - a).z(), 0) << "triangle " << f << " faces up, as the disk it continues";
  }
  const Mesh annulus = make_mesh(x, t);
  const auto topology = component_topology(annulus);
  ASSERT_EQ(topology.size(), 1u);
  EXPECT_EQ(topology[0].boundary_loops, 2);
  EXPECT_EQ(topology[0].genus, 0);
}

TEST(ZipLoops, loops_running_opposite_ways_or_too_short_are_refused)
{
  const VertexVectors x = circles(8, 6);
  VertexVectors up = VertexVectors::Zero(14, 3);
  up.col(2).setOnes();
  const std::vector<int> outer{0, 1, 2, 3, 4, 5, 6, 7}, inner_reversed{13, 12, 11, 10, 9, 8};
  EXPECT_THROW(zip_loops(x, up, outer, inner_reversed), InvalidMesh);
  EXPECT_THROW(zip_loops(x, up, outer, {8, 9}), InvalidMesh);
}

TEST(ZipLoops, loops_touching_at_a_vertex_get_no_zero_area_triangle)
{
  // The inner loop's fourth vertex 2e-13 inside the outer loop's fourth, as a rebuilt rim can end on
  // the cut: the shortest diagonal there is that vertex pair, and its triangles have zero area,
  // which validation refuses (the re-triangulation would fail with "face … has zero area").
  constexpr int n = 8, m = 8;
  VertexVectors x = circles(n, m);
  x.row(n + 3) = x.row(3) * (1 - 1e-13);
  std::vector<int> outer(n), inner(m);
  for (int i = 0; i < n; ++i) {
    outer[static_cast<std::size_t>(i)] = i;
    inner[static_cast<std::size_t>(i)] = n + i;
  }
  VertexVectors up = VertexVectors::Zero(n + m, 3);
  up.col(2).setOnes();
  const auto strip = zip_loops(x, up, outer, inner);
  ASSERT_EQ(strip.size(), static_cast<std::size_t>(n + m));
  const double zero_area = BuildOptions{}.zero_area_tolerance;
  for (const auto& t : strip)
    EXPECT_FALSE(has_zero_area(x.row(t[0]).transpose(), x.row(t[1]).transpose(), x.row(t[2]).transpose(), zero_area))
        << "triangle " << t[0] << ", " << t[1] << ", " << t[2];
}

} // namespace
} // namespace sdflow
