//! The advancing front on groups of points apart (reconstruct/reconstruct_apart.h), and the test
//! whether a reconstruction joined two groups.
#include "sdflow/errors.h"
#include "sdflow/geometry/topology.h"
#include "sdflow/reconstruct/reconstruct_apart.h"
#include "support/analytic_meshes.h"
#include "support/mesh_checks.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <set>
#include <vector>

namespace sdflow {
namespace {

//! Points with unit normals.
struct Samples {
  VertexVectors points, normals;
};

//! The vertices of two unit icospheres (642 each) on the x axis `gap` apart, the first sphere's
//! rows first, with their exact outward normals.
Samples two_spheres(double gap)
{
  const Mesh a = analytic::icosphere(3, 1.0, {-1 - gap / 2, 0, 0});
  const Mesh b = analytic::icosphere(3, 1.0, {1 + gap / 2, 0, 0});
  Samples s{VertexVectors(a.n_vertices() + b.n_vertices(), 3), VertexVectors(a.n_vertices() + b.n_vertices(), 3)};
  Eigen::Index row = 0;
  for (const Mesh* m : {&a, &b}) {
    const Eigen::Vector3d centre(m == &a ? -1 - gap / 2 : 1 + gap / 2, 0, 0);
    for (const auto v : m->vertices()) {
      s.points.row(row) = to_eigen(m->point(v)).transpose();
      s.normals.row(row++) = (to_eigen(m->point(v)) - centre).normalized().transpose();
    }
  }
  return s;
}

//! Rows [begin, end).
std::vector<int> rows(int begin, int end)
{
  std::vector<int> r;
  for (int i = begin; i < end; ++i)
    r.push_back(i);
  return r;
}

TEST(ReconstructApart, each_group_is_rebuilt_on_its_own_and_points_of_no_group_are_unused)
{
  const Samples s = two_spheres(0.05);
  const int half = static_cast<int>(s.points.rows()) / 2;
  std::vector<int> second = rows(half, 2 * half);
  const int left_out = second.back();
  second.pop_back();
  const std::vector<std::vector<int>> groups{rows(0, half), second};
  const Reconstruction r = reconstruct_apart(s.points, s.normals, groups);
  const auto topology = component_topology(r.mesh);
  ASSERT_EQ(topology.size(), 2u);
  for (const auto& c : topology) {
    EXPECT_TRUE(c.closed());
    EXPECT_EQ(c.genus, 0);
  }
  EXPECT_TRUE(checks::is_two_manifold(r.mesh));
  EXPECT_EQ(r.unused, std::vector<int>{left_out});
  EXPECT_EQ(r.mesh.n_vertices(), static_cast<std::size_t>(2 * half - 1));
  // Every vertex comes from its own row, once, and no triangle mixes the groups.
  std::set<int> sources(r.source.begin(), r.source.end());
  EXPECT_EQ(sources.size(), r.source.size());
  for (const auto v : r.mesh.vertices())
    EXPECT_EQ(to_eigen(r.mesh.point(v)), s.points.row(r.source[static_cast<std::size_t>(v.idx())]).transpose());
  for (const auto f : r.mesh.faces()) {
    std::set<bool> sides;
    for (const auto v : r.mesh.fv_range(f))
      sides.insert(r.source[static_cast<std::size_t>(v.idx())] >= half);
    EXPECT_EQ(sides.size(), 1u);
  }
  EXPECT_FALSE(joins_groups(r, groups, static_cast<int>(s.points.rows())));
}

TEST(ReconstructApart, a_reconstruction_of_one_surface_across_two_groups_joins_them)
{
  // One sphere's points split into two hemispheres: rebuilt together they make one closed
  // surface, which joins the groups; rebuilt apart, two caps that do not.
  const Samples s = two_spheres(0.05);
  const int half = static_cast<int>(s.points.rows()) / 2;
  std::vector<std::vector<int>> hemispheres(2);
  for (int i = 0; i < half; ++i)
    hemispheres[s.points(i, 1) > 0 ? 0 : 1].push_back(i);
  VertexVectors points = s.points.topRows(half), normals = s.normals.topRows(half);
  const Reconstruction together = reconstruct_surface(points, normals);
  ASSERT_EQ(component_topology(together.mesh).size(), 1u);
  EXPECT_TRUE(joins_groups(together, hemispheres, half));
  const Reconstruction apart = reconstruct_apart(points, normals, hemispheres);
  EXPECT_EQ(component_topology(apart.mesh).size(), 2u);
  EXPECT_FALSE(joins_groups(apart, hemispheres, half));
  // Points of no group join nothing.
  EXPECT_FALSE(joins_groups(together, {hemispheres[0]}, half));
}

TEST(ReconstructApart, rows_out_of_range_or_in_two_groups_are_refused)
{
  const Samples s = two_spheres(0.5);
  const auto n = static_cast<int>(s.points.rows());
  EXPECT_THROW(reconstruct_apart(s.points, s.normals, {rows(0, 10), {n}}), InvalidParameter);
  EXPECT_THROW(reconstruct_apart(s.points, s.normals, {rows(0, 10), rows(9, 20)}), InvalidParameter);
  const Reconstruction r = reconstruct_apart(s.points, s.normals, {rows(0, n / 2)});
  EXPECT_THROW(joins_groups(r, {rows(0, 10)}, 5), InvalidParameter);
  EXPECT_THROW(joins_groups(r, {{-1}}, n), InvalidParameter);
}

TEST(ReconstructApart, a_group_too_small_for_a_triangle_is_left_over)
{
  // Found by fuzz_run: the pieces of a cut surface can hold a stray point, and rebuilding that
  // piece threw "1 points cannot make a triangle" out of the run's re-triangulation (exit 3).
  const Samples s = two_spheres(0.5);
  const auto n = static_cast<int>(s.points.rows());
  std::vector<int> first = rows(0, n / 2 - 2), stray{n / 2 - 2}, pair{n / 2 - 1, n / 2};
  const Reconstruction alone = reconstruct_surface(s.points(first, Eigen::all), s.normals(first, Eigen::all));
  const Reconstruction r = reconstruct_apart(s.points, s.normals, {first, stray, pair});
  EXPECT_EQ(r.mesh.n_faces(), alone.mesh.n_faces()) << "the small groups add nothing";
  for (const int row : {n / 2 - 2, n / 2 - 1, n / 2})
    EXPECT_NE(std::find(r.unused.begin(), r.unused.end(), row), r.unused.end()) << "point " << row << " left over";
}

} // namespace
} // namespace sdflow
