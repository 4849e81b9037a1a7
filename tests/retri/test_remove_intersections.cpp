//! Removal of intersecting faces and of the vertices they leave alone.
#include "sdflow/retri/remove_intersections.h"
#include "support/analytic_meshes.h"
#include "support/test_meshes.h"

#include <gtest/gtest.h>

#include <random>

namespace sdflow {
namespace {

Mesh pushed_through_icosphere()
{
  return test::mapped(analytic::icosphere(3), [](const Eigen::Vector3d& p) {
    Eigen::Vector3d q = p;
    if (q.z() > 0.2)
      q.z() = 0.2 - 2.2 * (q.z() - 0.2);
    return q;
  });
}

//! Structural validity of the output and the bookkeeping against the input.
void expect_valid_removal(const Mesh& input, const RemovalResult& r)
{
  const Mesh& out = r.mesh;
  ASSERT_EQ(r.vertex_origin.size(), out.n_vertices());
  ASSERT_EQ(r.face_origin.size(), out.n_faces());
  EXPECT_EQ(out.n_faces() + r.removed_faces.size(), input.n_faces());
  EXPECT_EQ(out.n_vertices() + r.removed_vertices.size(), input.n_vertices());
  for (auto v : out.all_vertices()) {
    EXPECT_FALSE(out.status(v).deleted());
    EXPECT_FALSE(out.is_isolated(v)) << "vertex " << v.idx() << " has no face";
    EXPECT_EQ(out.point(v), input.point(Mesh::VertexHandle(r.vertex_origin[v.idx()])));
  }
  for (auto f : out.all_faces()) {
    EXPECT_FALSE(out.status(f).deleted());
    const Mesh::FaceHandle g(r.face_origin[f.idx()]);
    EXPECT_FALSE(std::binary_search(r.removed_faces.begin(), r.removed_faces.end(), g.idx()));
    std::vector<int> now, before;
    for (auto v : out.fv_range(f))
      now.push_back(r.vertex_origin[v.idx()]);
    for (auto v : input.fv_range(g))
      before.push_back(v.idx());
    // Same corners in the same cyclic order.
    std::rotate(now.begin(), std::min_element(now.begin(), now.end()), now.end());
    std::rotate(before.begin(), std::min_element(before.begin(), before.end()), before.end());
    EXPECT_EQ(now, before);
  }
  std::vector<char> in_pair(input.n_faces(), 0);
  for (const auto& p : r.intersecting_pairs)
    in_pair[p.first] = in_pair[p.second] = 1;
  for (std::size_t f = 0; f < in_pair.size(); ++f)
    EXPECT_EQ(in_pair[f] != 0, std::binary_search(r.removed_faces.begin(), r.removed_faces.end(), int(f)));
  // Faces keep their vertices, so pairs that did not intersect still do not: nothing is left.
  EXPECT_TRUE(self_intersections(out).empty());
}

TEST(RemoveIntersections, pushed_through_sphere_loses_exactly_its_intersecting_faces)
{
  const Mesh input = pushed_through_icosphere();
  const RemovalResult r = remove_self_intersections(input);
  ASSERT_FALSE(r.intersecting_pairs.empty());
  EXPECT_FALSE(r.removed_faces.empty());
  expect_valid_removal(input, r);
}

TEST(RemoveIntersections, crossing_sheets_and_folds_leave_valid_meshes)
{
  const Mesh flat = test::grid(8, 8, [](double i, double j) { return Eigen::Vector3d(i, j, 0); });
  const Mesh wall = test::grid(8, 8, [](double i, double j) { return Eigen::Vector3d(3.3, i - 0.2, j - 4.1); });
  const Mesh fold = test::grid(8, 4, [](double i, double j) { return Eigen::Vector3d(i <= 4 ? i : 8 - i, j, 0); });
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> jitter(-0.6, 0.6);
  const Mesh crumpled = test::grid(10, 10, [&](double i, double j) {
    return Eigen::Vector3d(i + jitter(rng), j + jitter(rng), jitter(rng));
  });
  for (const Mesh& input : {test::disjoint_union({&flat, &wall}), fold, crumpled}) {
    SCOPED_TRACE(input.n_faces());
    const RemovalResult r = remove_self_intersections(input);
    EXPECT_FALSE(r.removed_faces.empty());
    expect_valid_removal(input, r);
  }
}

TEST(RemoveIntersections, clean_surface_is_unchanged_and_isolated_vertices_go)
{
  const Mesh sphere = analytic::icosphere(2);
  const RemovalResult clean = remove_self_intersections(sphere);
  EXPECT_TRUE(clean.removed_faces.empty());
  EXPECT_TRUE(clean.removed_vertices.empty());
  EXPECT_EQ(clean.mesh.n_faces(), sphere.n_faces());
  expect_valid_removal(sphere, clean);

  // A vertex that had no face before is removed as well, and reported.
  VertexVectors x(vertex_positions(sphere).rows() + 1, 3);
  x << vertex_positions(sphere), Eigen::RowVector3d(5, 5, 5);
  const Mesh with_stray = make_mesh(x, face_indices(sphere));
  const RemovalResult r = remove_self_intersections(with_stray);
  EXPECT_EQ(r.removed_vertices, std::vector<int>{static_cast<int>(sphere.n_vertices())});
  expect_valid_removal(with_stray, r);
}

TEST(RemoveIntersections, degenerate_faces_are_removed)
{
  // A flat grid with one vertex moved onto the segment between two neighbours: the faces around
  // it that become collinear are reported as (f, f) and removed.
  const Mesh input = test::grid(4, 4, [](double i, double j) {
    return Eigen::Vector3d(i, i == 2 && j == 2 ? 1.0 : j, 0.0);
  });
  const RemovalResult r = remove_self_intersections(input);
  bool degenerate = false;
  for (const auto& p : r.intersecting_pairs)
    degenerate = degenerate || p.first == p.second;
  EXPECT_TRUE(degenerate);
  expect_valid_removal(input, r);
}

} // namespace
} // namespace sdflow
